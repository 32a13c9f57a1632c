#pragma once
// What every window that draws bodies sets up the same way: the renderer (gradient
// background, no multisampling, trackball turning) and a camera looking at the bodies from
// the front and above.
#include <array>

#include <vtkSmartPointer.h>

#include "palpa/scene/scene.hpp"

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

/// Looks at the box from the front (-y) and above (`elevation` up per unit back), zoomed in.
void frame_from_front(vtkRenderer& renderer, std::array<double, 6> bounds, double elevation = 0.9,
                      double zoom = 1.25);

}  // namespace palpa::ui
