#pragma once
// What every window that draws bodies sets up the same way: the renderer (gradient
// background, no multisampling, trackball turning) and a camera looking at the bodies from
// the front and above.
#include <array>
#include <optional>

#include <vtkSmartPointer.h>

#include "palpa/scene/scene.hpp"
#include "palpa/ui/coverage_overlay.hpp"

class vtkGenericOpenGLRenderWindow;
class vtkRenderer;

namespace palpa::ui {

class VtkView;

/// Makes `window` the view's render window and adds the bodies' renderer to it. No
/// multisampling: with software OpenGL (Mesa llvmpipe under Xvfb) 8x MSAA costs most of a
/// frame; smooth shading and the normals keep the surface smooth without it.
vtkSmartPointer<vtkRenderer> add_body_renderer(VtkView& view, vtkGenericOpenGLRenderWindow* window);

/// The box around every body of the scene: xmin, xmax, ymin, ymax, zmin, zmax (m).
std::array<double, 6> scene_bounds(const scene::Scene& scene);

/// Looks down on the exam region along its mean skin normal, from as close as lets every
/// point of it into the view with `margin` to spare (whatever the view's aspect, down to
/// square), the picture's up the way of +y: every touchable point of the region is in
/// view and faces the camera (the trainee's default view). `bounds`: the scene's box, for
/// the clipping range.
void frame_region(vtkRenderer& renderer, const RegionFacing& region, std::array<double, 6> bounds,
                  double margin = 1.12);

/// The way out of the support the scene's bodies rest on, their free side: the mean of their
/// press axes (scene::SceneBody::press_axis, the area-weighted mean skeleton normal); none
/// when no body rests on a support.
std::optional<Vec3> free_side(const scene::Scene& scene);

/// The picture's up when looking down `normal` (unit): +y across it, or +z when the normal
/// is along y (the trainee's default view, the report's maps).
Vec3 picture_up(const Vec3& normal);

/// Looks at the box from its free side: down `up` (unit) onto the box's centre, the
/// picture's up as picture_up, far enough to see the whole box, zoomed in.
void frame_from_free_side(vtkRenderer& renderer, std::array<double, 6> bounds, const Vec3& up, double zoom = 1.25);

/// Looks at the box from the front (-y) and above (`elevation` up per unit back), zoomed in.
void frame_from_front(vtkRenderer& renderer, std::array<double, 6> bounds, double elevation = 0.9,
                      double zoom = 1.25);

}  // namespace palpa::ui
