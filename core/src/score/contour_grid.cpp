#include "contour_grid.hpp"

#include <algorithm>
#include <cmath>

namespace palpa::score::detail {

TopPoint top_point(const mat::MatBody& body, double u, double v) {
  TopPoint out;
  double p[3];
  body.top().evaluate(u, v, p, 3);
  out.point = Vec3(p[0], p[1], p[2]);
  double s[mat::kRadius + 1];
  body.skeleton().evaluate(u, v, s, mat::kRadius + 1);
  out.radius = std::max(0.0, s[mat::kRadius]);  // a dip below 0 at the boundary reads as 0
  return out;
}

namespace {

// Longest top-contour length along u (over several v lines), and along v.
void contour_lengths(const mat::MatBody& body, double& length_u, double& length_v) {
  constexpr int kLines = 17;
  constexpr int kSteps = 64;
  length_u = length_v = 0.0;
  for (int line = 0; line < kLines; ++line) {
    const double w = line / double(kLines - 1);
    double lu = 0.0, lv = 0.0;
    Vec3 prev_u = top_point(body, 0.0, w).point;
    Vec3 prev_v = top_point(body, w, 0.0).point;
    for (int k = 1; k <= kSteps; ++k) {
      const double s = k / double(kSteps);
      const Vec3 pu = top_point(body, s, w).point;
      const Vec3 pv = top_point(body, w, s).point;
      lu += (pu - prev_u).norm();
      lv += (pv - prev_v).norm();
      prev_u = pu;
      prev_v = pv;
    }
    length_u = std::max(length_u, lu);
    length_v = std::max(length_v, lv);
  }
}

// An even count, so a region edge at u or v = 0.5 (half a symmetric body) falls between cells.
int cells_for(double length, double cell_size) {
  const double n = 2.0 * std::ceil(0.5 * length / cell_size);
  return static_cast<int>(std::clamp(n, double(ContourGrid::kMinCells), double(ContourGrid::kMaxCells)));
}

}  // namespace

ContourGrid::ContourGrid(const mat::MatBody& body, const std::vector<io::RegionPart>& parts, bool whole,
                         double cell_size) {
  double length_u = 0.0, length_v = 0.0;
  contour_lengths(body, length_u, length_v);
  rows_ = cells_for(length_u, cell_size);
  cols_ = cells_for(length_v, cell_size);

  const auto node_count = static_cast<std::size_t>((rows_ + 1) * (cols_ + 1));
  node_top_.resize(node_count);
  node_radius_.resize(node_count);
  for (int i = 0; i <= rows_; ++i) {
    for (int j = 0; j <= cols_; ++j) {
      const TopPoint tp = top_point(body, i / double(rows_), j / double(cols_));
      const auto k = static_cast<std::size_t>(i * (cols_ + 1) + j);
      node_top_[k] = tp.point;
      node_radius_[k] = tp.radius;
    }
  }

  const auto n = static_cast<std::size_t>(cells());
  centers_.resize(n);
  areas_.assign(n, 0.0);
  cell_reach_.assign(n, 0.0);
  auto node = [&](int i, int j) -> const Vec3& { return node_top_[static_cast<std::size_t>(i * (cols_ + 1) + j)]; };
  Vec3 normal_sum = Vec3::Zero();  // area-weighted normal of the whole top contour
  for (int i = 0; i < rows_; ++i) {
    for (int j = 0; j < cols_; ++j) {
      const auto k = static_cast<std::size_t>(i * cols_ + j);
      const double uc = (i + 0.5) / rows_;
      const double vc = (j + 0.5) / cols_;
      centers_[k] = top_point(body, uc, vc).point;
      // The quad through the four corners: half the cross product of its diagonals.
      const Vec3 d1 = node(i + 1, j + 1) - node(i, j);
      const Vec3 d2 = node(i, j + 1) - node(i + 1, j);
      half_diagonal_ = std::max({half_diagonal_, 0.5 * d1.norm(), 0.5 * d2.norm()});
      cell_reach_[k] = std::max({0.5 * d1.norm(), 0.5 * d2.norm(), (node(i, j) - centers_[k]).norm(),
                                 (node(i + 1, j) - centers_[k]).norm(), (node(i, j + 1) - centers_[k]).norm(),
                                 (node(i + 1, j + 1) - centers_[k]).norm()});
      normal_sum += 0.5 * d1.cross(d2);
      bool in_region = whole;
      for (const auto& p : parts) {
        if (p.u0 <= uc && uc <= p.u1 && p.v0 <= vc && vc <= p.v1) in_region = true;
      }
      if (in_region) {
        areas_[k] = 0.5 * d1.cross(d2).norm();
        region_area_ += areas_[k];
      }
    }
  }
  // The top-down frame: e1, e2 across the mean normal, e1 as close to +x as it can be.
  if (normal_sum.norm() > 0.0) {
    const Vec3 axis = normal_sum.normalized();
    const Vec3 seed = std::abs(axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    e1_ = (seed - seed.dot(axis) * axis).normalized();
    e2_ = axis.cross(e1_);
  }
}

int ContourGrid::cell_of(double u, double v) const {
  // Clamped before the cast: a parameter far outside [0, 1] (or NaN) would make the cast
  // undefined; the reader refuses such samples, this keeps any caller defined.
  const auto index = [](double t, int n) {
    const double x = std::floor(std::clamp(std::isnan(t) ? 0.0 : t, 0.0, 1.0) * n);
    return std::min(static_cast<int>(x), n - 1);
  };
  return index(u, rows_) * cols_ + index(v, cols_);
}

void ContourGrid::lookup(double u, double v, Vec3& top, double& radius) const {
  const double x = std::clamp(u, 0.0, 1.0) * rows_;
  const double y = std::clamp(v, 0.0, 1.0) * cols_;
  const int i = std::min(static_cast<int>(x), rows_ - 1);
  const int j = std::min(static_cast<int>(y), cols_ - 1);
  const double a = x - i;
  const double b = y - j;
  const auto k00 = static_cast<std::size_t>(i * (cols_ + 1) + j);
  const auto k10 = k00 + static_cast<std::size_t>(cols_ + 1);
  const double w00 = (1 - a) * (1 - b), w01 = (1 - a) * b, w10 = a * (1 - b), w11 = a * b;
  top = w00 * node_top_[k00] + w01 * node_top_[k00 + 1] + w10 * node_top_[k10] + w11 * node_top_[k10 + 1];
  radius = w00 * node_radius_[k00] + w01 * node_radius_[k00 + 1] + w10 * node_radius_[k10] +
           w11 * node_radius_[k10 + 1];
}

}  // namespace palpa::score::detail
