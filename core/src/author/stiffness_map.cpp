#include "palpa/author/stiffness_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "palpa/mat/layer_stiffness.hpp"
#include "palpa/mat/mat_body.hpp"

namespace palpa::author {
namespace {

// Index of (r, c) in a row-major array of `cols` columns.
std::size_t at_index(int r, int c, int cols) {
  return static_cast<std::size_t>(r) * static_cast<std::size_t>(cols) + static_cast<std::size_t>(c);
}

// Bilinear value at a continuous map position (row y, column x).
double bilinear(const StiffnessMap& m, double y, double x) {
  const int r0 = std::clamp(static_cast<int>(std::floor(y)), 0, std::max(m.rows - 2, 0));
  const int c0 = std::clamp(static_cast<int>(std::floor(x)), 0, std::max(m.cols - 2, 0));
  const int r1 = std::min(r0 + 1, m.rows - 1), c1 = std::min(c0 + 1, m.cols - 1);
  const double fy = std::clamp(y - r0, 0.0, 1.0), fx = std::clamp(x - c0, 0.0, 1.0);
  const auto at = [&](int r, int c) { return m.values[at_index(r, c, m.cols)]; };
  return (1 - fy) * ((1 - fx) * at(r0, c0) + fx * at(r0, c1)) + fy * ((1 - fx) * at(r1, c0) + fx * at(r1, c1));
}

void check_map(const StiffnessMap& map, double k_min, double k_max) {
  if (map.rows < 1 || map.cols < 1) throw std::invalid_argument("the stiffness map is empty");
  if (map.values.size() != at_index(map.rows, 0, map.cols)) {
    throw std::invalid_argument("the stiffness map's values do not match its rows x cols");
  }
  for (double x : map.values) {
    if (!(x >= 0.0 && x <= 1.0)) throw std::invalid_argument("a stiffness map value is outside [0, 1]");
  }
  if (!(k_min >= 0.0 && k_min <= k_max && std::isfinite(k_max))) {
    throw std::invalid_argument("the stiffness range must satisfy 0 <= k_min <= k_max");
  }
}

}  // namespace

double sample_map(const StiffnessMap& map, double u, double v, double half_u, double half_v) {
  // Continuous positions in pixels; the window shrinks symmetrically at the edges so that
  // its mean is the centre value for a linear map.
  const double y = std::clamp(u, 0.0, 1.0) * (map.rows - 1), x = std::clamp(v, 0.0, 1.0) * (map.cols - 1);
  const double hy = std::min({half_u * (map.rows - 1), y, map.rows - 1 - y});
  const double hx = std::min({half_v * (map.cols - 1), x, map.cols - 1 - x});
  // Samples about one pixel apart (odd counts: the pattern is symmetric about the centre).
  const int ny = 2 * static_cast<int>(std::ceil(hy)) + 1, nx = 2 * static_cast<int>(std::ceil(hx)) + 1;
  double sum = 0.0;
  for (int a = 0; a < ny; ++a) {
    const double yy = ny == 1 ? y : y - hy + 2.0 * hy * a / (ny - 1);
    for (int b = 0; b < nx; ++b) sum += bilinear(map, yy, nx == 1 ? x : x - hx + 2.0 * hx * b / (nx - 1));
  }
  return sum / (nx * ny);
}

std::vector<double> map_stiffness(const mat::BodyGrid& grid, const StiffnessMap& map, double k_min, double k_max) {
  check_map(map, k_min, k_max);
  if (grid.rows < 2 || grid.cols < 2) throw std::invalid_argument("the body grid needs at least 2 x 2 points");
  const double half_u = 0.5 / (grid.rows - 1), half_v = 0.5 / (grid.cols - 1);
  std::vector<double> k(at_index(grid.rows, 0, grid.cols));
  for (int i = 0; i < grid.rows; ++i) {
    for (int j = 0; j < grid.cols; ++j) {
      const double value = sample_map(map, static_cast<double>(i) / (grid.rows - 1),
                                      static_cast<double>(j) / (grid.cols - 1), half_u, half_v);
      k[at_index(i, j, grid.cols)] = k_min + (k_max - k_min) * value;
    }
  }
  return k;
}

namespace {

/// One pass of neighbour averaging over a rows x cols field: stays within the field's range
/// and flattens the jumps the spline overshoots on.
void smooth_once(std::vector<double>& field, int rows, int cols) {
  const auto old = field;
  const auto at = [&](int i, int j) { return old[at_index(i, j, cols)]; };
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      double sum = at(i, j);
      int n = 1;
      if (i > 0) sum += at(i - 1, j), ++n;
      if (i + 1 < rows) sum += at(i + 1, j), ++n;
      if (j > 0) sum += at(i, j - 1), ++n;
      if (j + 1 < cols) sum += at(i, j + 1), ++n;
      field[at_index(i, j, cols)] = sum / n;
    }
  }
}

/// Smooths `field` (after `derive` has brought grid.stiffness up to date with it) until the
/// body fits, at most max_passes times; the passes used.
template <typename Derive>
int smooth_until_fit(mat::BodyGrid& grid, std::vector<double>& field, int max_passes, Derive derive) {
  for (int pass = 0;; ++pass) {
    derive();
    try {
      (void)mat::MatBody::fit(grid);
      return pass;
    } catch (const mat::FitError&) {
      if (pass >= max_passes) throw;
    }
    smooth_once(field, grid.rows, grid.cols);
  }
}

}  // namespace

int apply_stiffness_map(mat::BodyGrid& grid, const StiffnessMap& map, double k_min, double k_max, int max_passes) {
  grid.stiffness = map_stiffness(grid, map, k_min, k_max);
  return smooth_until_fit(grid, grid.stiffness, max_passes, [] {});
}

int apply_modulus_map(mat::BodyGrid& grid, const StiffnessMap& map, double e_min, double e_max, int max_passes) {
  grid.modulus = map_stiffness(grid, map, e_min, e_max);
  return smooth_until_fit(grid, grid.modulus, max_passes,
                          [&grid] { grid.stiffness = mat::layer_stiffness_field(grid.modulus, grid.radius, grid.poisson); });
}

}  // namespace palpa::author
