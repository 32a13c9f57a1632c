#pragma once
// Synthetic grids for the core tests.
#include <cmath>
#include <functional>
#include <vector>

#include "palpa/mat/body_grid.hpp"

namespace palpa::test {

/// rows x cols points of `dim` channels, channel c of point (i, j) = f(i, j, c).
inline std::vector<double> make_grid(int rows, int cols, int dim, const std::function<double(int, int, int)>& f) {
  std::vector<double> g(static_cast<std::size_t>(rows * cols * dim));
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j)
      for (int c = 0; c < dim; ++c) g[static_cast<std::size_t>((i * cols + j) * dim + c)] = f(i, j, c);
  return g;
}

/// A smooth, non-uniformly spaced, curved grid with four extra channels in other units.
inline std::vector<double> wavy_grid(int rows, int cols, int dim = 7) {
  return make_grid(rows, cols, dim, [rows, cols](int i, int j, int c) {
    const double s = i / double(rows - 1);
    const double t = j / double(cols - 1);
    const double x = 0.1 * (s + 0.15 * s * s);
    const double y = 0.12 * (t + 0.1 * std::sin(2.0 * t));
    switch (c) {
      case 0: return x;
      case 1: return y;
      case 2: return 0.02 * std::sin(3.0 * s) * std::cos(2.0 * t);
      case 3: return 0.01 + 0.005 * s * t;
      case 4: return 300.0 + 200.0 * s - 50.0 * t * t;
      case 5: return 0.3 + 0.1 * t;
      default: return 1e-3 * (1.0 + 0.5 * s);
    }
  });
}

/// A body on the plane z = 0, uniform spacing, radius r = r0 (1 - a^2)(1 - b^2) with a, b
/// in [-1, 1]: a polynomial of degree 2 per direction, which a bicubic spline reproduces.
inline mat::BodyGrid flat_body(int rows, int cols, double half = 0.05, double r0 = 0.02, double k = 200.0) {
  mat::BodyGrid g;
  g.id = "flat";
  g.rows = rows;
  g.cols = cols;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      const double a = -1.0 + 2.0 * i / (rows - 1);
      const double b = -1.0 + 2.0 * j / (cols - 1);
      g.medial.push_back({half * a, half * b, 0.0});
      g.radius.push_back(r0 * (1 - a * a) * (1 - b * b));
      g.stiffness.push_back(k);
    }
  }
  return g;
}

}  // namespace palpa::test
