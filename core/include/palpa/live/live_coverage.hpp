#pragma once
// The exam's coverage while the trainee works (docs/user-guide.md, "Coverage overlay"),
// measured the way the score measures it (docs/scoring.md, "Coverage"): the same exam
// region on the same top-contour grid, the finger pad's radius around each contact, the
// deepest level reached per cell by the indentation's share of the local thickness. It is
// fed the contacts the GUI sees (one per snapshot, ~60 Hz) and fills in the way between
// two successive contacts on the same body, so a fast slide leaves no gaps.
#include <cstdint>
#include <memory>
#include <vector>

#include "palpa/io/thresholds.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/vec3.hpp"

namespace palpa::live {

class LiveCoverage {
 public:
  /// The exam region of `scene` under `thresholds` (exam_region, pad_radius, light_max,
  /// deep_min), nothing covered yet.
  LiveCoverage(const scene::Scene& scene, const io::Thresholds& thresholds);
  ~LiveCoverage();
  LiveCoverage(const LiveCoverage&) = delete;
  LiveCoverage& operator=(const LiveCoverage&) = delete;

  /// A contact: `body` (index in the scene, < 0: none), its skeleton parameters and its
  /// indentation (m). Stamps the pad there and along the way from the previous contact
  /// when it was on the same body. A contact with `body` < 0 lifts the finger.
  void contact(int body, double u, double v, double depth);
  /// The finger is off the body (or paused): the next contact starts afresh.
  void lift();

  /// Share (0..1) of the exam region's area covered at any level, and at deep pressure.
  double coverage() const;
  double deep_coverage() const;

  /// Per body: the grid's cell centres on the rest top contour (m), each cell's area in the
  /// exam region (m^2, 0 outside it), and the deepest level reached (0 untouched, 1 light,
  /// 2 medium, 3 deep).
  std::size_t bodies() const;
  int rows(std::size_t body) const;
  int cols(std::size_t body) const;
  const std::vector<Vec3>& centers(std::size_t body) const;
  const std::vector<double>& areas(std::size_t body) const;
  const std::vector<std::uint8_t>& levels(std::size_t body) const;
  /// Changes whenever a cell reaches a new level (to redraw only then).
  std::uint64_t version() const { return version_; }

 private:
  struct Impl;
  void stamp_at(std::size_t body, double u, double v, const Vec3& top, std::uint8_t level);
  std::unique_ptr<Impl> impl_;
  std::uint64_t version_ = 0;
};

}  // namespace palpa::live
