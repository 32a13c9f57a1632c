// What the trainee window gives a mouse user instead of force (docs/perception.md): the
// finger that follows the pointer through the pseudo-haptic control/display ratio, and the
// push-back trace it feeds.
#include <QCheckBox>
#include <QCursor>

#include "palpa/live/press_control.hpp"
#include "palpa/ui/push_back_trace.hpp"
#include "palpa/ui/trainee_window.hpp"
#include "palpa/ui/vtk_view.hpp"

namespace palpa::ui {

namespace {
Eigen::Vector2d to_eigen(const QPoint& p) { return {p.x(), p.y()}; }
QPoint to_pixel(const Eigen::Vector2d& p) { return {static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y()))}; }
constexpr double kLagToFollow = 0.5;  // px: a smaller lag is not worth a pick a frame
}  // namespace

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

void TraineeWindow::feel(const engine::SceneSnapshot& snapshot) {
  const auto& c = exercise_->contact();
  // The thin rim ends a stroke: there the skin and the support make up most of the column
  // and every stroke would end in a rise (the gauge says "thin tissue").
  const bool tissue = c.body >= 0 && c.thickness >= live::kThinTissue;
  trace_->feed(snapshot.t, Vec3(snapshot.probe[0], snapshot.probe[1], snapshot.probe[2]), tissue ? c.firmness : 0.0,
               pressure_setting());
  if (pointer_ && control_display_.lag() > kLagToFollow) palpate_at(*pointer_);
}

}  // namespace palpa::ui
