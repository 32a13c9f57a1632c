#pragma once
// Level of detail by size on screen: how much of a body the camera magnifies, so that its
// display tessellation can be held to a tolerance in pixels (object_tolerance_from_screen)
// rather than in metres. Under software OpenGL a frame's cost grows with the triangles
// drawn: a body small on screen is drawn with a coarse grid, still within a fraction of a
// pixel of its surface; one close up keeps the tolerance's grid (BENCHMARKS.md, "Level of
// detail"). core/ knows nothing of VTK: the GUI passes its camera as plain numbers.
#include <Eigen/Core>

namespace palpa::render {

/// What the level of detail needs of a camera (perspective unless `parallel`).
struct ViewForDetail {
  Eigen::Vector3d eye = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = -Eigen::Vector3d::UnitZ();  ///< unit, from the eye into the scene
  double view_angle = 0.5236;      ///< rad, the full vertical field of view
  double viewport_height = 600.0;  ///< pixels
  double near = 1e-3;              ///< m: depths closer than this count as this
  bool parallel = false;
  double parallel_scale = 1.0;  ///< m: half the view's height, for a parallel projection
};

/// The largest magnification (pixels per metre) of any point of the box [lo, hi]: for a
/// perspective camera viewport_height / (2 d tan(view_angle / 2)) at the box's nearest
/// depth d along the view direction (at least `near`, so a box round the eye gets the
/// most detail); for a parallel one viewport_height / (2 parallel_scale).
double pixels_per_metre(const ViewForDetail& view, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

}  // namespace palpa::render
