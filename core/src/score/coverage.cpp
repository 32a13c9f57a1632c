#include "coverage.hpp"

#include <algorithm>

namespace palpa::score::detail {

Coverage::Coverage(const ContourGrid& grid) : grid_(&grid) {
  const auto n = static_cast<std::size_t>(grid.cells());
  level_.assign(n, 0);
  dwell_.assign(n, 0.0f);
  peak_.assign(n, 0.0f);
  last_stamp_.assign(n, 0);
  visits_.assign(n, 0);
  seen_.assign(n, 0);
}

void Coverage::stamp(const Vec3& top, int cell, std::uint8_t level, double pad_radius, std::uint32_t stamp,
                     std::vector<int>& stamped) {
  stamped.clear();
  const auto& centers = grid_->centers();
  const int rows = grid_->rows();
  const int cols = grid_->cols();
  // Flood from the contact's cell through the cells that reach the pad (their centre at
  // most their own corner distance beyond it): they cover the pad's disc, so its cells are
  // connected through them, and one stretched cell elsewhere does not widen every flood.
  const auto& cell_reach = grid_->cell_reach();
  const double r2 = pad_radius * pad_radius;
  queue_.clear();
  queue_.push_back(cell);
  seen_[static_cast<std::size_t>(cell)] = stamp;
  for (std::size_t head = 0; head < queue_.size(); ++head) {
    const int c = queue_[head];
    const auto k = static_cast<std::size_t>(c);
    const double d2 = (centers[k] - top).squaredNorm();
    const double reach = pad_radius + cell_reach[k];
    if (d2 > reach * reach) continue;
    if (d2 <= r2) {
      level_[k] = std::max(level_[k], level);
      if (last_stamp_[k] == 0 || last_stamp_[k] + 1 < stamp) visits_[k] = static_cast<std::uint8_t>(std::min(255, visits_[k] + 1));
      last_stamp_[k] = stamp;
      stamped.push_back(c);
    }
    const int i = c / cols;
    const int j = c % cols;
    const int next[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
    for (const auto& n : next) {
      if (n[0] < 0 || n[0] >= rows || n[1] < 0 || n[1] >= cols) continue;
      const int nc = n[0] * cols + n[1];
      auto& s = seen_[static_cast<std::size_t>(nc)];
      if (s == stamp) continue;
      s = stamp;
      queue_.push_back(nc);
    }
  }
}

void Coverage::add_dwell(const std::vector<int>& cells, double dwell_s, double peak_force_n) {
  const auto dwell = static_cast<float>(dwell_s);
  const auto peak = static_cast<float>(peak_force_n);
  for (int c : cells) {
    const auto k = static_cast<std::size_t>(c);
    dwell_[k] += dwell;
    peak_[k] = std::max(peak_[k], peak);
  }
}

}  // namespace palpa::score::detail
