#pragma once
// Global interpolation of curves and surfaces through data (The NURBS Book, A9.1 and A9.4).
#include <span>
#include <stdexcept>
#include <vector>

#include "palpa/spline/banded_lu.hpp"
#include "palpa/spline/bspline_curve.hpp"
#include "palpa/spline/bspline_surface.hpp"

namespace palpa::spline {

/// Data that cannot be interpolated (collapsed grid, coincident parameters, ...).
class InterpolationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class Parameterization {
  ChordLength,  ///< eq. 9.5: parameter steps proportional to |Q_k - Q_{k-1}|
  Centripetal,  ///< eq. 9.6: steps proportional to sqrt|Q_k - Q_{k-1}|, gentler on sharp turns
};

struct InterpolationOptions {
  Parameterization parameterization = Parameterization::ChordLength;
  int max_degree = 3;  ///< the degree per direction is min(max_degree, points - 1)
};

/// Parameters in [0, 1] for the points of one polyline (`count` points, `stride` values per
/// point, the first three being xyz; other channels never take part).
std::vector<double> curve_parameters(std::span<const double> values, int count, int stride,
                                     Parameterization method);

/// Parameters along u (rows) and v (cols) of a rows x cols grid, row-major with `stride`
/// values per point and xyz first (A9.3): each column (row) gets its own chord-length
/// parameters, which are then averaged; columns (rows) of zero length are skipped.
std::vector<double> grid_parameters_u(std::span<const double> values, int rows, int cols, int stride,
                                      Parameterization method);
std::vector<double> grid_parameters_v(std::span<const double> values, int rows, int cols, int stride,
                                      Parameterization method);

/// eq. 9.8, knots by averaging: p+1 zeros, U[j+p] = (1/p) sum_{i=j}^{j+p-1} params[i], p+1 ones.
std::vector<double> averaging_knots(std::span<const double> params, int degree);

/// The collocation matrix A[k][i] = N_i(params[k]) of one direction, factorized once.
class CollocationSolver {
 public:
  CollocationSolver(std::span<const double> params, std::span<const double> knots, int degree);
  /// Solves A X = B in place; B has params.size() rows of `width` contiguous values.
  void solve(double* rhs, int width) const { lu_.solve(rhs, width); }
  int lower_bandwidth() const { return lu_.lower(); }
  int upper_bandwidth() const { return lu_.upper(); }

 private:
  static BandedLU build(std::span<const double> params, std::span<const double> knots, int degree);
  BandedLU lu_;
};

/// A9.4 on fixed parameters and knots: one factorization per direction, reused for every
/// grid line, every channel and every surface interpolated on the same parameters (the
/// skeleton and both contours of a MAT body).
class GridInterpolator {
 public:
  GridInterpolator(std::vector<double> u_params, std::vector<double> v_params, int degree_u, int degree_v);

  /// Parameters from the xyz channels of the data, degrees min(max_degree, points - 1).
  static GridInterpolator from_grid(std::span<const double> values, int rows, int cols, int stride,
                                    const InterpolationOptions& options = {});

  /// The surface through values (rows x cols points of dim channels, row-major).
  BSplineSurface interpolate(std::span<const double> values, int dim) const;

  int rows() const { return static_cast<int>(u_.size()); }
  int cols() const { return static_cast<int>(v_.size()); }
  int degree_u() const { return p_; }
  int degree_v() const { return q_; }
  const std::vector<double>& u_params() const { return u_; }
  const std::vector<double>& v_params() const { return v_; }
  const std::vector<double>& knots_u() const { return knots_u_; }
  const std::vector<double>& knots_v() const { return knots_v_; }

 private:
  std::vector<double> u_, v_;
  int p_, q_;
  std::vector<double> knots_u_, knots_v_;
  CollocationSolver solve_u_, solve_v_;
};

/// A9.1: the curve through `count` points of dim channels (xyz first), degree
/// min(max_degree, count - 1).
BSplineCurve interpolate_curve(std::span<const double> values, int count, int dim,
                               const InterpolationOptions& options = {});

}  // namespace palpa::spline
