#include "palpa/render/frustum.hpp"

namespace palpa::render {

Frustum::Frustum(const std::array<double, 24>& planes) {
  for (std::size_t k = 0; k < 6; ++k) {
    planes_[k] = Eigen::Vector4d(planes[4 * k], planes[4 * k + 1], planes[4 * k + 2], planes[4 * k + 3]);
  }
}

bool Frustum::may_see(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
  for (const auto& p : planes_) {
    // The box corner furthest along the plane's inward normal: if even it is outside,
    // every corner is.
    const Eigen::Vector3d far(p.x() >= 0.0 ? hi.x() : lo.x(), p.y() >= 0.0 ? hi.y() : lo.y(),
                              p.z() >= 0.0 ? hi.z() : lo.z());
    if (p.head<3>().dot(far) + p.w() < 0.0) return false;
  }
  return true;
}

}  // namespace palpa::render
