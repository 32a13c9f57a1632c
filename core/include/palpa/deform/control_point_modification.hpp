#pragma once
// Control-point modification (paper section 3.3, after Piegl 1989): move the surface point
// S(u, v) by a vector D by changing the p' x q' most influential control points in
// proportion to their basis products, the least-norm change that lands exactly:
//   dP_kl = N_k(u) N_l(v) D / sum (N_k N_l)^2   over the chosen window.
#include <array>
#include <span>

#include "palpa/spline/basis.hpp"
#include "palpa/spline/bspline_surface.hpp"

namespace palpa::deform {

/// The control points a move at (u, v) changes and their weights; allocation-free.
struct Influence {
  int i0 = 0;  ///< first control-point row of the window
  int j0 = 0;  ///< first control-point column
  int rows = 0;
  int cols = 0;
  /// weight[a * cols + b] = N_{i0+a}(u) N_{j0+b}(v) / sum over the window of (N N)^2
  std::array<double, (spline::kMaxDegree + 1) * (spline::kMaxDegree + 1)> weight{};
};

/// The window of p' x q' control points (pu, pv; 0 or more than p+1, q+1: all) with the
/// largest basis products at (u, v), and its weights.
Influence influence_at(const spline::BSplineSurface& surface, double u, double v, int pu = 0, int pv = 0);

/// Adds weight * d[c] to channel first + c of every control point in the window
/// (c < d.size()), which moves S(u, v) by exactly d in those channels.
void displace(spline::BSplineSurface& surface, const Influence& influence, std::span<const double> d, int first);

}  // namespace palpa::deform
