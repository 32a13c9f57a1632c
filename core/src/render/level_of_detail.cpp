#include "palpa/render/level_of_detail.hpp"

#include <algorithm>
#include <cmath>

namespace palpa::render {

double pixels_per_metre(const ViewForDetail& view, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  if (view.parallel) return view.viewport_height / (2.0 * view.parallel_scale);
  // The box's nearest depth: the corner least far along the view direction.
  const Eigen::Vector3d& d = view.direction;
  const Eigen::Vector3d nearest(d.x() >= 0.0 ? lo.x() : hi.x(), d.y() >= 0.0 ? lo.y() : hi.y(),
                                d.z() >= 0.0 ? lo.z() : hi.z());
  const double depth = std::max((nearest - view.eye).dot(d), view.near);
  return view.viewport_height / (2.0 * depth * std::tan(0.5 * view.view_angle));
}

}  // namespace palpa::render
