#pragma once
// Where a finger meets a body at skeleton parameters (u, v): the skeleton point, the local
// half-thickness R, the skeleton normal N and the top-contour point P + R N above them.
// Shared by tumour placement and the scripted trainee; allocation-free.
#include <Eigen/Core>

#include "palpa/mat/mat_body.hpp"
#include "palpa/vec3.hpp"

namespace palpa::scripted::detail {


struct SurfaceFrame {
  Vec3 skeleton = Vec3::Zero();
  double radius = 0.0;  ///< m, R(u, v) clamped at 0; the tissue is 2R thick there
  Vec3 normal = Vec3::UnitZ();
  Vec3 top = Vec3::Zero();  ///< P + R N: the point the finger pad touches first
  bool ok = false;          ///< false where the skeleton has no normal
};

inline SurfaceFrame frame_at(const mat::MatBody& body, double u, double v) {
  SurfaceFrame f;
  double s[mat::kRadius + 1];
  body.skeleton().evaluate(u, v, s, mat::kRadius + 1);
  f.skeleton = Vec3(s[mat::kX], s[mat::kY], s[mat::kZ]);
  f.radius = s[mat::kRadius] > 0.0 ? s[mat::kRadius] : 0.0;
  double n[3];
  f.ok = mat::skeleton_normal(body.skeleton(), u, v, n);
  if (f.ok) f.normal = Vec3(n[0], n[1], n[2]);
  f.top = f.skeleton + f.radius * f.normal;
  return f;
}

}  // namespace palpa::scripted::detail
