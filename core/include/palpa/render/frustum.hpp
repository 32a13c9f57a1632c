#pragma once
// View-frustum culling for the drawn bodies: a body whose box lies wholly outside the
// camera's view volume is neither re-tessellated nor copied nor drawn. The frustum comes
// from the GUI's camera as six planes; core knows nothing of the camera itself.
#include <array>

#include <Eigen/Core>

namespace palpa::render {

class Frustum {
 public:
  /// Six planes a x + b y + c z + d = 0, each given as (a, b, c, d) with the normal
  /// (a, b, c) pointing into the view volume, in any order (VTK's
  /// vtkCamera::GetFrustumPlanes writes left, right, bottom, top, near, far like this).
  explicit Frustum(const std::array<double, 24>& planes);

  /// False only when the box [lo, hi] lies wholly on the outer side of one plane, so it
  /// cannot be seen. Conservative: a box outside the volume but not behind any single
  /// plane (near a corner of the frustum) still counts as visible, which only costs a
  /// body drawn needlessly.
  bool may_see(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const;

 private:
  std::array<Eigen::Vector4d, 6> planes_;
};

}  // namespace palpa::render
