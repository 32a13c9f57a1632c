#pragma once
// A body of the medial-axis model (paper section 2.1): the skeleton surface SK carrying
// position, radius and material channels, and the top and bottom contour surfaces SC.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "palpa/mat/body_grid.hpp"
#include "palpa/spline/bspline_surface.hpp"
#include "palpa/spline/interpolation.hpp"

namespace palpa::mat {

/// Channels of the skeleton surface SK.
enum SkeletonChannel : int { kX = 0, kY, kZ, kRadius, kStiffness, kDamping, kMass, kSkeletonChannels };

/// A body that cannot be modelled: inconsistent sizes, data the spline cannot
/// interpolate, or a fit whose material fields leave their physical range between the
/// data sites (e.g. a negative stiffness where neighbouring values jump).
class FitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct FitOptions {
  spline::InterpolationOptions interpolation{};
  MaterialDefaults defaults{};
};

/// The skeleton samples of a grid with defaults filled in: rows*cols points of
/// kSkeletonChannels values (x, y, z, radius, stiffness, damping, mass).
std::vector<double> skeleton_samples(const BodyGrid& grid, const MaterialDefaults& defaults = {});

class MatBody {
 public:
  /// Fits SK through the grid, then the contours R = P + rN (top) and S = P - rN (bottom)
  /// on SK's parameters and knots, so that a contour point at (u, v) lies over SK(u, v).
  /// Throws FitError naming the body on degenerate input or an overshooting fit.
  static MatBody fit(const BodyGrid& grid, const FitOptions& options = {});

  const std::string& id() const { return id_; }
  /// Support::Bottom: only the top contour can be touched (docs/model.md).
  Support support() const { return support_; }
  bool anchored() const { return support_ == Support::Bottom; }
  const spline::BSplineSurface& skeleton() const { return skeleton_; }
  const spline::BSplineSurface& top() const { return top_; }
  const spline::BSplineSurface& bottom() const { return bottom_; }
  /// Parameters of the data sites: grid point (i, j) sits at (u_params()[i], v_params()[j]).
  const std::vector<double>& u_params() const { return u_params_; }
  const std::vector<double>& v_params() const { return v_params_; }

  /// Bytes held by the model (surfaces, knots, parameters).
  std::size_t memory_bytes() const;

 private:
  MatBody(std::string id, Support support, std::vector<double> u, std::vector<double> v, spline::BSplineSurface skeleton,
          spline::BSplineSurface top, spline::BSplineSurface bottom);

  std::string id_;
  Support support_ = Support::Free;
  std::vector<double> u_params_;
  std::vector<double> v_params_;
  spline::BSplineSurface skeleton_;
  spline::BSplineSurface top_;
  spline::BSplineSurface bottom_;
};

/// Samples SK between the data sites (4 per interval in each direction) and throws
/// FitError when radius, stiffness or damping dip below 0 by more than 5 % of their
/// largest value, or mass below 1e-3 of its smallest: a spline through values that jump
/// between close points overshoots, and a negative stiffness or mass would make forces
/// and dynamics diverge. Smaller dips are legitimate (a kinked field) and are clamped to
/// 0 where forces and dynamics read the channels. Damping and mass are checked only when
/// authored: their defaults derive from stiffness, which is checked itself.
void check_material_ranges(const spline::BSplineSurface& skeleton, const std::vector<double>& u_params,
                           const std::vector<double>& v_params, const std::vector<double>& samples,
                           bool damping_authored, bool mass_authored);

/// Unit normal of SK's xyz at (u, v): normalize(Su x Sv), with a fallback where the
/// cross product vanishes (a pole row or column): there the limit direction Su x Suv
/// (or Suv x Sv) is used. Returns false when no direction can be found.
bool skeleton_normal(const spline::BSplineSurface& skeleton, double u, double v, double normal[3]);

}  // namespace palpa::mat
