#pragma once
// Internal to core/anatomy: the support's parameterization (docs/anatomy-import.md,
// "The support"): the plane of least squares through points of the support's surface, and
// over it a quadric height field h = q0 + q1 s + q2 t + q3 s^2 + q4 s t + q5 t^2 kept when
// it fits twice as well as the plane (a chest wall curving around the ribcage).
#include <array>
#include <vector>

#include "palpa/anatomy/height_field.hpp"

namespace palpa::anatomy {

struct SupportModel {
  Frame frame;
  bool curved = false;
  std::array<double, 6> q{};  ///< the quadric's coefficients (all 0 for the plane)
  double rms = 0.0;           ///< m: the points' distance from the kept model, root mean square

  double height(double s, double t) const {
    return q[0] + q[1] * s + q[2] * t + q[3] * s * s + q[4] * s * t + q[5] * t * t;
  }
};

/// The frame of the plane through `points` (at least 3, not collinear), n turned towards
/// `inside`; e1 is the world axis (x, then y, then z) most parallel to the plane, projected,
/// and e2 = n x e1, so that the frame depends on the world alone, not on how a file orders
/// its voxels. Throws ImportError when the points do not span a plane.
Frame plane_frame(const std::vector<Vec3>& points, const Vec3& inside);

/// The frame with its origin and n given; e1, e2 chosen as in plane_frame.
Frame frame_with_normal(const Vec3& origin, const Vec3& n);

/// plane_frame, then the quadric over it when it fits at least twice as well (rms) and the
/// plane misses by more than `resolution`.
SupportModel fit_support(const std::vector<Vec3>& points, const Vec3& inside, double resolution);

}  // namespace palpa::anatomy
