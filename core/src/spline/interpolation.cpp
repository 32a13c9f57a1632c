#include "palpa/spline/interpolation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "palpa/spline/basis.hpp"
#include "../common/numeric.hpp"

namespace palpa::spline {
namespace {


double step_length(const double* a, const double* b, Parameterization method) {
  const double dx = b[0] - a[0];
  const double dy = b[1] - a[1];
  const double dz = b[2] - a[2];
  const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
  return method == Parameterization::Centripetal ? std::sqrt(d) : d;
}

// Averaged parameters of `count` points along `lines` polylines; point k of line l sits at
// values[(l*across + k*along) * stride]. Lines of zero length are skipped (A9.3).
std::vector<double> averaged_parameters(std::span<const double> values, int count, int lines, int along,
                                        int across, int stride, Parameterization method, const char* what) {
  std::vector<double> params(idx(count), 0.0);
  std::vector<double> steps(idx(count), 0.0);
  int used = 0;
  for (int l = 0; l < lines; ++l) {
    double total = 0.0;
    for (int k = 1; k < count; ++k) {
      const double* a = &values[idx((l * across + (k - 1) * along) * stride)];
      const double* b = &values[idx((l * across + k * along) * stride)];
      steps[idx(k)] = step_length(a, b, method);
      total += steps[idx(k)];
    }
    if (!(total > 0.0)) continue;  // a pole: this line collapses to one point
    if (!std::isfinite(total)) throw InterpolationError(std::string("non-finite coordinates along ") + what);
    ++used;
    double sum = 0.0;
    for (int k = 1; k < count - 1; ++k) {
      sum += steps[idx(k)];
      params[idx(k)] += sum / total;
    }
  }
  if (used == 0) {
    throw InterpolationError(std::string("every line along ") + what + " has zero length (the grid collapses)");
  }
  for (int k = 1; k < count - 1; ++k) params[idx(k)] /= used;
  params[idx(count - 1)] = 1.0;
  for (int k = 1; k < count; ++k) {
    if (!(params[idx(k)] > params[idx(k - 1)])) {
      throw InterpolationError(fmt::format(
          "coincident points: parameters along {} do not increase between index {} and {}", what, k - 1, k));
    }
  }
  return params;
}

int default_degree(int points, int max_degree) {
  return std::max(1, std::min({max_degree, points - 1, kMaxDegree}));
}

}  // namespace

std::vector<double> curve_parameters(std::span<const double> values, int count, int stride,
                                     Parameterization method) {
  if (count < 2) throw InterpolationError("a curve needs at least 2 points");
  return averaged_parameters(values, count, 1, 1, 0, stride, method, "the curve");
}

std::vector<double> grid_parameters_u(std::span<const double> values, int rows, int cols, int stride,
                                      Parameterization method) {
  if (rows < 2 || cols < 1) throw InterpolationError("a grid needs at least 2 rows");
  return averaged_parameters(values, rows, cols, cols, 1, stride, method, "u (rows)");
}

std::vector<double> grid_parameters_v(std::span<const double> values, int rows, int cols, int stride,
                                      Parameterization method) {
  if (cols < 2 || rows < 1) throw InterpolationError("a grid needs at least 2 columns");
  return averaged_parameters(values, cols, rows, 1, cols, stride, method, "v (cols)");
}

std::vector<double> averaging_knots(std::span<const double> params, int degree) {
  const int n = static_cast<int>(params.size());
  if (degree < 1 || degree >= n || degree > kMaxDegree) {
    throw InterpolationError(fmt::format("degree {} must be in 1..min(points - 1, {})", degree, kMaxDegree));
  }
  std::vector<double> knots(idx(n + degree + 1), 0.0);
  for (int j = 1; j <= n - 1 - degree; ++j) {
    double sum = 0.0;
    for (int i = j; i <= j + degree - 1; ++i) sum += params[idx(i)];
    knots[idx(j + degree)] = sum / degree;
  }
  std::fill(knots.end() - degree - 1, knots.end(), 1.0);
  return knots;
}

BandedLU CollocationSolver::build(std::span<const double> params, std::span<const double> knots,
                                  int degree) {
  const int n = static_cast<int>(params.size());
  if (degree < 1 || degree >= n || degree > kMaxDegree || knots.size() != idx(n + degree + 1)) {
    throw InterpolationError("collocation: degree and knots do not fit the parameters");
  }
  std::vector<int> spans(idx(n));
  int lower = 0;
  int upper = 0;
  for (int k = 0; k < n; ++k) {
    spans[idx(k)] = find_span(n, degree, params[idx(k)], knots);
    lower = std::max(lower, k - (spans[idx(k)] - degree));
    upper = std::max(upper, spans[idx(k)] - k);
  }
  BandedLU lu(n, lower, upper);
  std::array<double, kMaxDegree + 1> basis{};
  for (int k = 0; k < n; ++k) {
    basis_functions(spans[idx(k)], params[idx(k)], degree, knots, basis.data());
    for (int j = 0; j <= degree; ++j) lu.at(k, spans[idx(k)] - degree + j) = basis[idx(j)];
  }
  try {
    lu.factorize();
  } catch (const std::runtime_error& e) {
    throw InterpolationError(e.what());
  }
  return lu;
}

CollocationSolver::CollocationSolver(std::span<const double> params, std::span<const double> knots,
                                     int degree)
    : lu_(build(params, knots, degree)) {}

GridInterpolator::GridInterpolator(std::vector<double> u_params, std::vector<double> v_params, int degree_u,
                                   int degree_v)
    : u_(std::move(u_params)),
      v_(std::move(v_params)),
      p_(degree_u),
      q_(degree_v),
      knots_u_(averaging_knots(u_, p_)),
      knots_v_(averaging_knots(v_, q_)),
      solve_u_(u_, knots_u_, p_),
      solve_v_(v_, knots_v_, q_) {}

GridInterpolator GridInterpolator::from_grid(std::span<const double> values, int rows, int cols, int stride,
                                             const InterpolationOptions& options) {
  if (stride < 3) throw InterpolationError("grid points need at least the three xyz channels");
  if (values.size() < idx(rows) * idx(cols) * idx(stride)) throw InterpolationError("grid data too short");
  auto u = grid_parameters_u(values, rows, cols, stride, options.parameterization);
  auto v = grid_parameters_v(values, rows, cols, stride, options.parameterization);
  return {std::move(u), std::move(v), default_degree(rows, options.max_degree),
          default_degree(cols, options.max_degree)};
}

BSplineSurface GridInterpolator::interpolate(std::span<const double> values, int dim) const {
  const int m = rows();
  const int n = cols();
  if (values.size() != idx(m) * idx(n) * idx(dim)) {
    throw InterpolationError("interpolate: data size does not match the grid");
  }
  std::vector<double> control(values.begin(), values.end());
  // Along u: rows of the system are grid rows, each row of n*dim contiguous values.
  solve_u_.solve(control.data(), n * dim);
  // Along v: each grid row is an n x dim system of its own.
  for (int i = 0; i < m; ++i) solve_v_.solve(&control[idx(i * n * dim)], dim);
  for (double c : control) {
    if (!std::isfinite(c)) throw InterpolationError("interpolation produced non-finite control points");
  }
  return {p_, q_, knots_u_, knots_v_, m, n, dim, std::move(control)};
}

BSplineCurve interpolate_curve(std::span<const double> values, int count, int dim,
                               const InterpolationOptions& options) {
  if (dim < 3) throw InterpolationError("curve points need at least the three xyz channels");
  if (values.size() != idx(count) * idx(dim)) throw InterpolationError("curve data size mismatch");
  const auto params = curve_parameters(values, count, dim, options.parameterization);
  const int p = default_degree(count, options.max_degree);
  auto knots = averaging_knots(params, p);
  const CollocationSolver solver(params, knots, p);
  std::vector<double> control(values.begin(), values.end());
  solver.solve(control.data(), dim);
  return {p, std::move(knots), dim, std::move(control)};
}

}  // namespace palpa::spline
