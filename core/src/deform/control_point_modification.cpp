#include "palpa/deform/control_point_modification.hpp"

#include <algorithm>

namespace palpa::deform {
namespace {

// The contiguous window of `width` of the p+1 non-zero basis values with the largest sum.
int best_window(const std::array<double, 8>& n, int p, int width) {
  int best = 0;
  double best_sum = -1.0;
  for (int start = 0; start + width <= p + 1; ++start) {
    double sum = 0.0;
    for (int a = 0; a < width; ++a) sum += n[static_cast<std::size_t>(start + a)];
    if (sum > best_sum) {
      best_sum = sum;
      best = start;
    }
  }
  return best;
}

}  // namespace

Influence influence_at(const spline::BSplineSurface& surface, double u, double v, int pu, int pv) {
  const auto basis = surface.basis(u, v);
  const int p = surface.degree_u();
  const int q = surface.degree_v();
  Influence inf;
  inf.rows = (pu <= 0 || pu > p + 1) ? p + 1 : pu;
  inf.cols = (pv <= 0 || pv > q + 1) ? q + 1 : pv;
  const int a0 = best_window(basis.nu, p, inf.rows);
  const int b0 = best_window(basis.nv, q, inf.cols);
  inf.i0 = basis.span_u - p + a0;
  inf.j0 = basis.span_v - q + b0;
  double sum_sq = 0.0;
  for (int a = 0; a < inf.rows; ++a) {
    for (int b = 0; b < inf.cols; ++b) {
      const double w = basis.nu[static_cast<std::size_t>(a0 + a)] * basis.nv[static_cast<std::size_t>(b0 + b)];
      inf.weight[static_cast<std::size_t>(a * inf.cols + b)] = w;
      sum_sq += w * w;
    }
  }
  // sum_sq > 0: the window holds the largest basis products, which sum to a partition of unity.
  for (int k = 0; k < inf.rows * inf.cols; ++k) inf.weight[static_cast<std::size_t>(k)] /= sum_sq;
  return inf;
}

void displace(spline::BSplineSurface& surface, const Influence& inf, std::span<const double> d, int first) {
  for (int a = 0; a < inf.rows; ++a) {
    for (int b = 0; b < inf.cols; ++b) {
      const double w = inf.weight[static_cast<std::size_t>(a * inf.cols + b)];
      auto cp = surface.control_point(inf.i0 + a, inf.j0 + b);
      for (std::size_t c = 0; c < d.size(); ++c) cp[static_cast<std::size_t>(first) + c] += w * d[c];
    }
  }
}

}  // namespace palpa::deform
