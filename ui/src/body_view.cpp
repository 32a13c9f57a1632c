#include "palpa/ui/body_view.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
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
  // One colour, not a gradient: under software OpenGL the gradient is a shaded quad over the
  // whole view every frame, a tenth of a single body's frame (BENCHMARKS.md, "Level of detail").
  renderer->SetBackground(0.20, 0.22, 0.28);
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

void frame_region(vtkRenderer& renderer, const RegionFacing& region, std::array<double, 6> bounds, double margin) {
  auto* camera = renderer.GetActiveCamera();
  const Vec3 n = region.normal;
  const Vec3 up = picture_up(n);
  const Vec3 right = up.cross(n);
  const double tan_half = std::tan(0.5 * camera->GetViewAngle() * std::numbers::pi / 180.0) / margin;
  // The nearest eye on the normal that sees every point within the (square) view cone.
  double distance = 0.0;
  for (const auto& p : region.points) {
    const Vec3 d = p - region.centroid;
    const double lateral = std::max(std::abs(d.dot(up)), std::abs(d.dot(right)));
    distance = std::max(distance, d.dot(n) + lateral / tan_half);
  }
  if (!(distance > 0.0)) distance = 0.3;
  const Vec3 eye = region.centroid + distance * n;
  camera->SetFocalPoint(region.centroid.x(), region.centroid.y(), region.centroid.z());
  camera->SetPosition(eye.x(), eye.y(), eye.z());
  camera->SetViewUp(up.x(), up.y(), up.z());
  renderer.ResetCameraClippingRange(bounds.data());
}

std::optional<Vec3> free_side(const scene::Scene& scene) {
  Vec3 sum = Vec3::Zero();
  for (std::size_t b = 0; b < scene.size(); ++b) {
    if (scene.body(b).body.anchored()) sum += scene.body(b).press_axis.up;
  }
  if (!(sum.norm() > 0.0)) return std::nullopt;
  return sum.normalized();
}

Vec3 picture_up(const Vec3& normal) {
  Vec3 up = Vec3::UnitY() - Vec3::UnitY().dot(normal) * normal;
  if (up.norm() < 0.2) up = Vec3::UnitZ() - Vec3::UnitZ().dot(normal) * normal;
  return up.normalized();
}

void frame_from_free_side(vtkRenderer& renderer, std::array<double, 6> bounds, const Vec3& up, double zoom) {
  auto* camera = renderer.GetActiveCamera();
  const Vec3 centre(0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5]));
  const Vec3 eye = centre + up;
  const Vec3 view_up = picture_up(up);
  camera->SetFocalPoint(centre.x(), centre.y(), centre.z());
  camera->SetPosition(eye.x(), eye.y(), eye.z());
  camera->SetViewUp(view_up.x(), view_up.y(), view_up.z());
  renderer.ResetCamera(bounds.data());  // keeps the direction, backs off to see the box
  camera->Zoom(zoom);
  renderer.ResetCameraClippingRange(bounds.data());
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
