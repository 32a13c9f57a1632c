#pragma once
// The per-cell record of an exam over one body's top contour (docs/scoring.md,
// "Coverage"): deepest pressure level, dwell time, peak force and how many separate
// times the finger pad came over each cell.
#include <cstdint>
#include <vector>

#include "contour_grid.hpp"

namespace palpa::score::detail {

class Coverage {
 public:
  explicit Coverage(const ContourGrid& grid);

  /// Covers every cell whose centre lies within `pad_radius` (3-D) of `top`, the contact's
  /// top-contour point in cell `cell`, at pressure `level` (1 light .. 3 deep). `stamp`
  /// numbers stamps across the session: a cell not covered by the previous stamp starts a
  /// new visit. The covered cells are returned in `stamped`.
  void stamp(const Vec3& top, int cell, std::uint8_t level, double pad_radius, std::uint32_t stamp,
             std::vector<int>& stamped);
  /// Adds contact time and the largest force since the stamp to the cells it covered.
  void add_dwell(const std::vector<int>& cells, double dwell_s, double peak_force_n);

  int visits(int cell) const { return visits_[static_cast<std::size_t>(cell)]; }
  const std::vector<std::uint8_t>& level() const { return level_; }
  const std::vector<float>& dwell() const { return dwell_; }
  const std::vector<float>& peak_force() const { return peak_; }

 private:
  const ContourGrid* grid_;
  std::vector<std::uint8_t> level_;
  std::vector<float> dwell_;
  std::vector<float> peak_;
  std::vector<std::uint32_t> last_stamp_;  // 0: never covered
  std::vector<std::uint8_t> visits_;       // saturates at 255
  std::vector<std::uint32_t> seen_;        // flood-fill marks, by stamp number
  std::vector<int> queue_;
};

}  // namespace palpa::score::detail
