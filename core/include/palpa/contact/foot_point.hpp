#pragma once
// The foot point of a probe on the skeleton SK (paper section 3.1): the (u, v) whose
// skeleton normal passes through the probe Q, i.e. the skeleton point closest to Q.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "palpa/spline/bspline_surface.hpp"
#include "palpa/vec3.hpp"

namespace palpa::contact {


struct FootPoint {
  double u = 0.0;
  double v = 0.0;
  Vec3 point = Vec3::Zero();  ///< SK(u, v), xyz
  Vec3 su = Vec3::Zero();     ///< dSK/du (xyz) at (u, v)
  Vec3 sv = Vec3::Zero();     ///< dSK/dv (xyz) at (u, v)
  double distance = 0.0;      ///< |Q - SK(u, v)|
  int iterations = 0;         ///< Newton iterations or bisection levels used
  bool converged = false;
};

struct NewtonOptions {
  int max_iterations = 30;
  /// Stop when a step moves (u, v) by less than this (parameter units). Newton also stops
  /// (after taking that step) when the decrease a Newton step promises is below the
  /// round-off of the squared distance; in practice (u, v) then sits within ~1e-13.
  double parameter_tolerance = 1e-13;
};

/// Safeguarded Newton on f(u, v) = |SK(u, v) - Q|^2 / 2 over [0, 1]^2 from (u0, v0):
/// the full Hessian where it is positive definite, Gauss-Newton (plus a small
/// Levenberg term) where it is not, a projected step with an active set so foot points
/// on edges and corners converge along the boundary, and a backtracking line search so
/// f never increases. Allocation-free.
FootPoint newton_foot_point(const spline::BSplineSurface& skeleton, const Vec3& q, double u0, double v0,
                            const NewtonOptions& options = {});

/// The paper's method (section 3.1), kept as a reference: bisection of the (u, v) box,
/// halving each interval on the side the probe lies (by the sign of (Q - S) . Su and
/// (Q - S) . Sv) until it is shorter than 2^-levels. Right for convex, gently curved
/// skeletons; not for concave ones or foot points far from the box's centre line.
FootPoint bisect_foot_point(const spline::BSplineSurface& skeleton, const Vec3& q, int levels = 10);

/// The robust, fast search: Newton warm-started from the previous query or, when cold,
/// seeded from the nearest of a few samples per knot span. A warm result is checked
/// against the samples so it cannot stay in a local minimum that is farther than a
/// sample (a concave skeleton, a probe that jumped).
class FootPointSearch {
 public:
  explicit FootPointSearch(const spline::BSplineSurface& skeleton, int samples_per_span = 3);

  /// Samples the skeleton again (after it moved).
  void resample(const spline::BSplineSurface& skeleton);

  /// Cold query.
  FootPoint closest(const spline::BSplineSurface& skeleton, const Vec3& q, const NewtonOptions& options = {}) const;
  /// Warm query from the previous (u, v).
  FootPoint closest_from(const spline::BSplineSurface& skeleton, const Vec3& q, double u0, double v0,
                         const NewtonOptions& options = {}) const;

  int sample_count() const { return static_cast<int>(uv_.size()); }

 private:
  struct Sample {
    double u;
    double v;
  };
  /// The three samples nearest to q (nearest first) and their squared distances
  /// (infinite where there are fewer samples).
  std::array<std::size_t, 3> nearest_samples(const Vec3& q, std::array<double, 3>& distance2) const;
  /// Puts sample k (squared distance dk) among the three best unless it is farther or a
  /// copy of one of them.
  void insert_seed(std::size_t k, double dk, std::array<std::size_t, 3>& best, std::array<double, 3>& d2) const;

  int per_span_;
  double spacing_u_ = 0.0;  ///< widest gap between sample parameters
  double spacing_v_ = 0.0;
  double reach_ = 0.0;  ///< m: every skeleton point lies within this of a sample
  /// Samples grouped in blocks of up to 4 x 4 with a bounding sphere each, so a query
  /// skips the blocks that cannot hold a nearer sample (large grids stay cheap).
  struct Block {
    Vec3 center;
    double radius;
    std::size_t i0, i1, j0, j1;  // sample index ranges [i0, i1) x [j0, j1)
  };
  std::vector<Block> blocks_;
  std::size_t sample_cols_ = 0;
  std::vector<Sample> uv_;
  std::vector<Vec3> points_;
};

}  // namespace palpa::contact
