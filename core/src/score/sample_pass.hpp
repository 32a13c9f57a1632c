#pragma once
// One pass over a session's samples (docs/scoring.md): active time, contact, pressure
// levels, coverage stamps and dwell, peak force, the contact path, and the force near
// the marks against the force elsewhere. The samples may come in pieces (a session read as
// a stream): the pass keeps what it measures, never the samples.
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "exam_grids.hpp"
#include "marks.hpp"
#include "palpa/engine/engine.hpp"
#include "search_pattern.hpp"
#include "timeline.hpp"

namespace palpa::score::detail {

/// The most contact-path points the pass keeps (56 bytes each, 59 MB): a stamp every
/// 0.5 mm, so 524 m of contact path; a thorough 30-minute exam is well under 100 m. A
/// longer path (a hostile file jumping every tick) is thinned: every other point is
/// dropped and from then on one stamp in 2, 4, 8 ... is kept, so the pass's memory does
/// not grow with the session's length (docs/scoring.md, "Memory").
inline constexpr std::size_t kMaxPathPoints = std::size_t{1} << 20;

class SamplePass {
 public:
  SamplePass(ExamGrids& exam, const std::vector<Landing>& mark_tops, const Timeline& timeline,
             const Thresholds& thresholds, double rate_hz);

  /// Runs over `samples` in order (the pass is made once): add(samples), then finish().
  void run(std::span<const engine::Sample> samples);
  /// Takes the next samples in order. A sample's contact time is the step to the next one,
  /// so the last sample given is held (copied) until more come or finish().
  void add(std::span<const engine::Sample> samples);
  /// After the last add(): measures the held sample with one period and closes the stamp.
  void finish();

  double peak_force_n = 0.0;   ///< over every sample: safety is about what was applied
  double contact_time_s = 0.0;
  PressureLevels pressure;
  std::vector<PathPoint> path;
  std::size_t ignored = 0;     ///< active samples naming a body the case does not have
  std::uint64_t sample_count = 0;  ///< how many were given
  std::optional<double> last_t;  ///< the last sample's time (none given: nothing)

  /// Mean force within the palpate radius of a mark over the mean force elsewhere; 0 when
  /// either is missing.
  double palpate_search_ratio() const;

 private:
  void measure(const engine::Sample& s, double dt_to_next);
  bool is_active(const engine::Sample& s);
  void lift_off();
  void touch(const engine::Sample& s, double dt, double force);
  void look_up(const engine::Sample& s);
  std::uint8_t level_at(const engine::Sample& s) const;
  void add_force_near_marks(double force);
  void stamp(const engine::Sample& s, std::uint8_t level);
  void keep_path_point(const PathPoint& p);
  void flush();

  ExamGrids& exam_;
  const std::vector<Landing>& mark_tops_;
  const Timeline& tl_;
  const Thresholds& th_;
  double rate_;
  double dt_cap_;
  double palpate2_;

  std::vector<int> stamped_;  // cells the current stamp covered
  std::uint64_t path_stride_ = 1, stamps_seen_ = 0;  // the path keeps one stamp in path_stride_
  std::optional<engine::Sample> held_;  // the last sample given, measured when the next comes
  std::size_t pause_index_ = 0;
  bool was_contact_ = false, have_stamp_ = false;
  int stamp_body_ = -1, piece_ = 0;
  std::uint32_t stamp_number_ = 0;
  std::uint8_t stamp_level_ = 0;
  Vec3 stamp_top_ = Vec3::Zero();
  double pending_dwell_ = 0.0, pending_peak_ = 0.0;
  // The grid lookup of the last contact's (body, u, v): a held press repeats it.
  int cache_body_ = -1;
  double cache_u_ = std::numeric_limits<double>::quiet_NaN(), cache_v_ = cache_u_, cache_radius_ = 0.0;
  Vec3 cache_top_ = Vec3::Zero();
  double near_sum_ = 0.0, search_sum_ = 0.0;
  std::size_t near_count_ = 0, search_count_ = 0;
};

}  // namespace palpa::score::detail
