#include "palpa/ui/body_view.hpp"

#include <algorithm>
#include <limits>

#include <vtkCamera.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkNew.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

#include "palpa/ui/vtk_view.hpp"

namespace palpa::ui {

vtkSmartPointer<vtkRenderer> add_body_renderer(VtkView& view, vtkGenericOpenGLRenderWindow* window) {
  window->SetMultiSamples(0);
  view.setRenderWindow(window);
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->SetBackground(0.13, 0.15, 0.19);
  renderer->SetBackground2(0.30, 0.33, 0.40);
  renderer->GradientBackgroundOn();
  window->AddRenderer(renderer);
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  view.interactor()->SetInteractorStyle(style);
  return renderer;
}

std::array<double, 6> scene_bounds(const scene::Scene& scene) {
  constexpr double big = std::numeric_limits<double>::max();
  std::array<double, 6> bounds = {big, -big, big, -big, big, -big};
  for (std::size_t b = 0; b < scene.size(); ++b) {
    const auto& box = scene.body(b).bounds;
    for (std::size_t k = 0; k < 3; ++k) {
      bounds[2 * k] = std::min(bounds[2 * k], box.lo[static_cast<Eigen::Index>(k)]);
      bounds[2 * k + 1] = std::max(bounds[2 * k + 1], box.hi[static_cast<Eigen::Index>(k)]);
    }
  }
  return bounds;
}

void frame_from_front(vtkRenderer& renderer, std::array<double, 6> bounds, double elevation, double zoom) {
  auto* camera = renderer.GetActiveCamera();
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetPosition(0.0, -1.0, elevation);
  camera->SetViewUp(0.0, 0.0, 1.0);
  renderer.ResetCamera(bounds.data());
  camera->Zoom(zoom);
  renderer.ResetCameraClippingRange(bounds.data());
}

}  // namespace palpa::ui
