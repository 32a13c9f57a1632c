// What of the scene the trainee window draws for its camera: off-screen culling and the
// level of detail (a body small on screen gets a coarser grid: BENCHMARKS.md, "Level of
// detail").
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <vtkCamera.h>
#include <vtkRenderer.h>

#include "palpa/render/frustum.hpp"
#include "palpa/render/level_of_detail.hpp"
#include "palpa/render/tessellation_grid.hpp"
#include "palpa/ui/body_surfaces.hpp"
#include "palpa/ui/trainee_window.hpp"

namespace palpa::ui {

void TraineeWindow::set_detail_pixels(double pixels) {
  detail_pixels_ = std::max(pixels, 0.0);
  request_render();
}

render::ViewForDetail TraineeWindow::detail_view() const {
  auto* camera = renderer_->GetActiveCamera();
  render::ViewForDetail view;
  camera->GetPosition(view.eye.data());
  camera->GetDirectionOfProjection(view.direction.data());
  view.view_angle = camera->GetViewAngle() * std::numbers::pi / 180.0;
  view.viewport_height = std::max(1, renderer_->GetSize()[1]);
  view.parallel = camera->GetParallelProjection() != 0;
  view.parallel_scale = camera->GetParallelScale();
  return view;
}

double TraineeWindow::pixels_per_metre(const render::ViewForDetail& view, std::size_t body) const {
  const auto& box = exercise_->scene().body(body).bounds;
  return render::pixels_per_metre(view, box.lo, box.hi);
}

double TraineeWindow::drawn_deviation_px() const {
  const auto& meshes = exercise_->meshes();
  const auto view = detail_view();
  double px = 0.0;
  for (std::size_t b = 0; b < meshes.size(); ++b) {
    if (meshes.visible(b)) px = std::max(px, meshes.deviation(b) * pixels_per_metre(view, b));
  }
  return px;
}

double TraineeWindow::detail_tolerance(const render::ViewForDetail& view, std::size_t body) const {
  const double ppm = pixels_per_metre(view, body);
  // Off, or a camera with no finite magnification (a degenerate view): the options' own
  // tolerance (set_tolerance never goes finer than that).
  if (!(detail_pixels_ > 0.0) || !(ppm > 0.0) || !std::isfinite(ppm)) return 0.0;
  const double tolerance = render::object_tolerance_from_screen(detail_pixels_, ppm);
  // Rounded down to a step of 2^(1/4): a camera on the move re-tessellates a body only when
  // its size on screen changed by a fifth, and the tolerance never exceeds detail_pixels_.
  return std::exp2(std::floor(4.0 * std::log2(tolerance)) / 4.0);
}

void TraineeWindow::fit_bodies_to_view() {
  std::array<double, 24> planes{};
  renderer_->GetActiveCamera()->GetFrustumPlanes(renderer_->GetTiledAspectRatio(), planes.data());
  const render::Frustum frustum(planes);
  const auto& scene = exercise_->scene();
  const auto& meshes = exercise_->meshes();
  const auto view = detail_view();
  bool detail_changed = false;
  last_frame_.bodies_drawn = 0;
  last_frame_.triangles = 0;
  for (std::size_t b = 0; b < scene.size(); ++b) {
    // The rest box already allows the largest radius on every side of the skeleton's
    // control points; a press moves the drawn contours inwards, and the oscillators
    // overshoot by a few per cent of the press: a tenth of the diagonal is a safe margin.
    const auto& box = scene.body(b).bounds;
    const palpa::Vec3 pad = palpa::Vec3::Constant(0.1 * (box.hi - box.lo).norm());
    const bool visible = frustum.may_see(box.lo - pad, box.hi + pad);
    if (visible != meshes.visible(b)) {
      exercise_->set_body_visible(b, visible);
      surfaces_->set_visible(b, visible);
    }
    if (!visible) continue;
    detail_changed = exercise_->set_body_tolerance(b, detail_tolerance(view, b)) || detail_changed;
    ++last_frame_.bodies_drawn;
    last_frame_.triangles += meshes.top(b).triangle_count() + meshes.bottom(b).triangle_count();
  }
  // A running exercise re-tessellates at its next snapshot; otherwise nothing else would.
  if (detail_changed && (!exercise_->started() || exercise_->finished()) && exercise_->refresh_meshes() > 0) {
    surfaces_->sync(exercise_->meshes());
    request_render();
  }
}

}  // namespace palpa::ui
