#pragma once
// The two surfaces of a body lying on a support, as heights over the support's plane
// (docs/anatomy-import.md, "The fitting method"): the support (bottom) and the free skin
// (top), sampled on one regular grid of the plane, heights along the plane's normal.
#include <cmath>
#include <limits>
#include <vector>

#include "palpa/vec3.hpp"

namespace palpa::anatomy {

/// An orthonormal frame: the support's plane through `origin` spanned by e1 and e2, its
/// normal n (e1 x e2) pointing from the support into the tissue.
struct Frame {
  Vec3 origin = Vec3::Zero();
  Vec3 e1 = Vec3::UnitX();
  Vec3 e2 = Vec3::UnitY();
  Vec3 n = Vec3::UnitZ();

  Vec3 to_world(double s, double t, double h) const { return origin + s * e1 + t * e2 + h * n; }
  Vec3 to_local(const Vec3& p) const {
    const Vec3 d = p - origin;
    return {d.dot(e1), d.dot(e2), d.dot(n)};
  }
};

inline constexpr double kNoSurface = std::numeric_limits<double>::quiet_NaN();

/// Heights (m, along the frame's normal) sampled at (s0 + a step, t0 + b step), a < ns, b < nt.
struct HeightField {
  double s0 = 0.0, t0 = 0.0, step = 1e-3;
  int ns = 0, nt = 0;
  std::vector<double> h;  ///< ns * nt, a fastest; kNoSurface where there is none

  double& at(int a, int b) { return h[static_cast<std::size_t>(a) + static_cast<std::size_t>(ns) * static_cast<std::size_t>(b)]; }
  double at(int a, int b) const { return h[static_cast<std::size_t>(a) + static_cast<std::size_t>(ns) * static_cast<std::size_t>(b)]; }
  double s_at(int a) const { return s0 + a * step; }
  double t_at(int b) const { return t0 + b * step; }
  /// Bilinear height at (s, t), clamped to the sampled square; NaN where a corner has none.
  double sample(double s, double t) const;
  /// Bilinear height and its gradient (dh/ds, dh/dt) at (s, t); false where undefined.
  bool sample(double s, double t, double& height, double& dh_ds, double& dh_dt) const;
};

/// `field` smoothed by a Gaussian of standard deviation `sigma` (m) along the support,
/// samples without a surface left out of the average (and left without one).
HeightField blurred(const HeightField& field, double sigma);

/// The two surfaces of one body over its support's frame.
struct SurfacePair {
  Frame frame;
  HeightField bottom;  ///< the support under the body, defined everywhere on the grid
  HeightField top;     ///< the free surface; equal to bottom where there is no tissue
  /// Which support the frame came from: "plane" (a plane fitted to the support, or given)
  /// or "curved" (the support bends away from its plane; docs/anatomy-import.md).
  const char* support_kind = "plane";
  /// m: the input's resolution (voxel size, or the mesh's median edge), which sets how
  /// closely the fit can follow it.
  double resolution = 1e-3;
};

/// m: the first-order distance from `p` (world) to the surface `field` of `pair`: the
/// height difference along n times the cosine of the surface's slope there. NaN outside.
double surface_distance(const SurfacePair& pair, const HeightField& field, const Vec3& p);

}  // namespace palpa::anatomy
