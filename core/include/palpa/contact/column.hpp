#pragma once
// The column under a probe in a body on a support (docs/model.md, "Under the skeleton: the
// column"). Below its skeleton a thick, tightly bent body has points with two or more
// nearest skeleton points (under a conical apex, near a centre of curvature): there the
// paper's foot point jumps, and the force with it. The skeleton of a body resting on a
// support is a graph over the support: each line along the body's press axis meets it once,
// so the skeleton point straight above a probe moves continuously with the probe.
#include "palpa/contact/contact.hpp"
#include "palpa/contact/foot_point.hpp"
#include "palpa/mat/mat_body.hpp"

namespace palpa::contact {

/// The direction out of the support that a body's skeleton is a graph over.
struct PressAxis {
  Vec3 up = Vec3::UnitZ();  ///< unit: the area-weighted mean of the skeleton's normals N
  /// The smallest N . up over the skeleton's samples: 1 for a flat sheet, 0 where N turns
  /// perpendicular to the axis (the sheet stops being a graph over it).
  double min_cosine = 1.0;
  /// The column reading applies: every sampled normal is within kMaxColumnTilt of the axis.
  bool usable = false;
};

/// rad: the steepest skeleton a column reading accepts, 80 degrees from the press axis.
/// Steeper, the column's foot moves by more than 5.7 mm per mm of sideways motion (1/cos)
/// and the sheet is close to folding over the axis; such a body keeps the paper's reading.
inline constexpr double kMaxColumnTilt = 1.3962634015954636;

/// The press axis of `skeleton`, from its normals on a samples x samples grid of (u, v).
PressAxis press_axis_of(const spline::BSplineSurface& skeleton, int samples = 33);

/// The skeleton point on the line through q along `axis` (unit): Gauss-Newton on the
/// residual's part across the axis, from (u0, v0), projected into [0, 1]^2 and backtracked.
/// `converged` is false when the line misses the sheet (q beyond the body's footprint: the
/// nearest the search gets lies on the boundary, off the line). Allocation-free.
FootPoint column_foot_point(const spline::BSplineSurface& skeleton, const Vec3& axis, const Vec3& q, double u0,
                            double v0);

/// A probe below the skeleton, read along its column (`foot` from column_foot_point, q below
/// foot.point): depth = R - (Q - P) . N, from R at the skeleton to the thickness 2R at the
/// bottom contour, the rest support_depth; side +1; outward turning from N at the skeleton
/// to the press axis `up` at the bottom contour (linear in the depth past R). Continuous
/// with top_side_contact where the probe crosses the skeleton (both foot points are Q).
Contact column_contact(const mat::MatBody& body, const FootPoint& foot, const Vec3& q, const Vec3& up);

}  // namespace palpa::contact
