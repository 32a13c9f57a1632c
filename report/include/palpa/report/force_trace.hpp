#pragma once
// The force and indentation-level traces of a session's force plot (images.hpp), gathered
// while the samples stream by and decimated as they come: a report needs the memory of the
// plot (about 2000 points a trace), not of the session, however many ticks it holds.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>

#include "palpa/plot/line_plot.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/session/session.hpp"

namespace palpa::report {

class ForceTrace {
 public:
  /// `head`: the session (its samples are not read; its case gives each contact's
  /// thickness); `samples`: how many add() will be given in all (SampleStream::declared_count),
  /// which sets the decimation.
  ForceTrace(const session::Session& head, std::uint64_t samples);
  ~ForceTrace();
  ForceTrace(const ForceTrace&) = delete;
  ForceTrace& operator=(const ForceTrace&) = delete;

  /// The next samples in tick order.
  void add(std::span<const engine::Sample> samples);
  /// Ends the last, partial run of samples; call once, after the last add().
  void finish();

  /// |F| (N) and the level (depth / thickness, or depth in mm without a case), decimated:
  /// the largest value of each run of samples, at its sample's time (peaks survive).
  const plot::Series& force() const { return force_; }
  const plot::Series& level() const { return level_; }
  double peak_force() const { return peak_; }
  double t0() const { return t0_; }
  double t1() const;
  /// True when the level is a share of the thickness (the case could be built).
  bool levels_are_shares() const { return scene_ != nullptr; }

 private:
  double level_of(const engine::Sample& s) const;

  std::unique_ptr<scene::Scene> scene_;
  std::uint64_t run_ = 1, in_run_ = 0, seen_ = 0;
  double t0_ = 0.0, last_t_ = 0.0, peak_ = 0.0;
  struct Point {
    double t = 0.0, y = 0.0;
  };
  Point best_force_, best_level_;  // the largest of the current run so far
  plot::Series force_, level_;
};

/// The trace of a session file, from one pass over its samples as a stream (none kept).
/// Throws session::SessionError as the session reader does.
std::unique_ptr<ForceTrace> read_force_trace(const std::filesystem::path& path);

}  // namespace palpa::report
