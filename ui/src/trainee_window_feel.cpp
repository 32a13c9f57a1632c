// What the trainee window gives a mouse user instead of force (docs/perception.md): the
// finger that follows the pointer through the pseudo-haptic control/display ratio, and the
// push-back trace it feeds.
#include <QCheckBox>
#include <QCursor>
#include <vtkActor.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRegularPolygonSource.h>
#include <vtkRenderer.h>

#include "palpa/live/press_control.hpp"
#include "palpa/ui/push_back_trace.hpp"
#include "palpa/ui/trainee_window.hpp"
#include "palpa/ui/vtk_view.hpp"

namespace palpa::ui {

namespace {
Eigen::Vector2d to_eigen(const QPoint& p) { return {p.x(), p.y()}; }
QPoint to_pixel(const Eigen::Vector2d& p) { return {static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y()))}; }
constexpr double kLagToFollow = 0.5;  // px: a smaller lag is not worth a pick a frame
constexpr double kContactRingRadius = 0.004;  // m: about a fingertip's contact patch
}  // namespace

// The contact ring: where the finger went into the skin (the rest top of its column). Pressed
// deep into a curved body seen at a slant, the fingertip is drawn away from that place (up to
// ~10 mm of skin on the imported breast); the ring shows the place a mark or a second stroke
// comes back to, and, with the pointer hidden over a body, where the finger is aimed.
void TraineeWindow::show_contact_ring(const live::FeltPoint& at) {
  const bool on = at.thickness > 0.0;
  if (!ring_) {
    ring_source_ = vtkSmartPointer<vtkRegularPolygonSource>::New();
    ring_source_->SetNumberOfSides(24);
    ring_source_->SetRadius(kContactRingRadius);
    ring_source_->GeneratePolygonOff();
    auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
    mapper->SetInputConnection(ring_source_->GetOutputPort());
    ring_ = vtkSmartPointer<vtkActor>::New();
    ring_->SetMapper(mapper);
    ring_->GetProperty()->SetColor(1.0, 0.85, 0.2);
    ring_->GetProperty()->SetLineWidth(2.0);
    ring_->GetProperty()->LightingOff();
    ring_->VisibilityOff();
    renderer_->AddActor(ring_);
  }
  if (!on) {
    if (ring_->GetVisibility()) ring_->VisibilityOff(), request_render();
    return;
  }
  if (ring_->GetVisibility() && (at.skin - drawn_ring_).norm() < 2e-4) return;  // not worth a redraw
  const Vec3 c = at.skin + 5e-4 * at.normal;  // just over the skin, not inside it
  ring_source_->SetCenter(c.x(), c.y(), c.z());
  ring_source_->SetNormal(at.normal.x(), at.normal.y(), at.normal.z());
  ring_->VisibilityOn();
  drawn_ring_ = at.skin;
  request_render();
}

bool TraineeWindow::sticky_finger() const { return sticky_box_ && sticky_box_->isChecked(); }

std::optional<render::SurfacePick> TraineeWindow::pick_at(const QPoint& pos) const {
  const auto [near, far] = view_->pointer_ray(*renderer_, pos);
  return exercise_->pick(near, far - near);
}

void TraineeWindow::palpate_at(const QPoint& pos) {
  const double dt = pointer_clock_.isValid() ? static_cast<double>(pointer_clock_.restart()) * 1e-3 : 0.0;
  if (!pointer_clock_.isValid()) pointer_clock_.start();
  pointer_ = pos;
  const auto under_pointer = pick_at(pos);
  picked_ = under_pointer;
  if (!under_pointer || !sticky_finger()) {
    control_display_.reset(to_eigen(pos));  // off the bodies (or not sticking): the finger is the pointer
  } else {
    // Firmer than the stroke so far: the finger moves less than the pointer (Lecuyer et al.
    // 2000's stiffness by control/display ratio); it stays on the body the pointer is over.
    const double gain = live::control_display_gain(trace_->trace().contrast());
    const QPoint finger = to_pixel(control_display_.follow(to_eigen(pos), gain, dt));
    const auto under_finger = finger == pos ? under_pointer : pick_at(finger);
    if (under_finger && under_finger->body == under_pointer->body) {
      picked_ = under_finger;
    } else {
      control_display_.reset(to_eigen(pos));
    }
  }
  // Over a body the drawn fingertip is the pointer (a second arrow would show the lag as a
  // fault, not as the tissue holding the finger back).
  const auto shape = picked_ && sticky_finger() ? Qt::BlankCursor : Qt::ArrowCursor;
  if (view_->input()->cursor().shape() != shape) view_->input()->setCursor(shape);
  exercise_->aim(picked_);  // off the bodies: the finger lifts where it was
}

void TraineeWindow::feel() {
  // Everything the finger slid over since the last frame, not only where it is now: the
  // trace's bumps stay where the lumps are at any frame rate (live/felt_path.hpp). The thin
  // rim ends a stroke: there the skin and the support make up most of the column and every
  // stroke would end in a rise (the gauge says "thin tissue").
  const auto& felt = exercise_->felt();
  for (const auto& p : felt)
    trace_->feed(p.t, p.finger, p.thickness >= live::kThinTissue ? p.firmness : 0.0, pressure_setting(), p.skin);
  if (!felt.empty()) show_contact_ring(felt.back());
  if (pointer_ && control_display_.lag() > kLagToFollow) palpate_at(*pointer_);
}

}  // namespace palpa::ui
