#include "palpa/ui/trainee_window.hpp"

#include <array>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <QApplication>
#include <QCheckBox>
#include <QCloseEvent>
#include <QMessageBox>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QKeyEvent>
#include <QLabel>
#include <QListWidget>
#include <QMouseEvent>
#include <QPushButton>
#include <QShortcut>
#include <QStatusBar>
#include <QVBoxLayout>
#include <QWheelEvent>
#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkLineSource.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>

#include "palpa/score/figures.hpp"
#include "palpa/ui/coverage_overlay.hpp"
#include "palpa/ui/body_view.hpp"
#include "palpa/ui/force_gauge.hpp"
#include "palpa/ui/push_back_trace.hpp"
#include "palpa/ui/score_card.hpp"
#include "palpa/ui/vtk_view.hpp"
#include "palpa/ui/window_frame.hpp"
#include "palpa/vec3.hpp"

namespace palpa::ui {
namespace {

constexpr double kFingertipRadius = 0.006;  // m: drawn probe
constexpr double kMinForceTarget = 1.0;     // N: force mode's range (a light touch to a firm
constexpr double kMaxForceTarget = 15.0;    //    clinical press, below the 20 N safety gate)
constexpr double kDefaultForceTarget = 6.0; // N
constexpr std::array<double, 3> kMarkColour = {0.25, 0.55, 0.95};  // a mark before the score: blue

vtkSmartPointer<vtkActor> sphere_actor(const palpa::Vec3& centre, double radius, double r, double g, double b) {
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(radius);
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(24);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->SetPosition(centre.x(), centre.y(), centre.z());
  actor->GetProperty()->SetColor(r, g, b);
  actor->GetProperty()->SetInterpolationToPhong();
  return actor;
}

vtkSmartPointer<vtkActor> line_actor(const palpa::Vec3& a, const palpa::Vec3& b, double r, double g, double bl) {
  vtkNew<vtkLineSource> line;
  line->SetPoint1(a.x(), a.y(), a.z());
  line->SetPoint2(b.x(), b.y(), b.z());
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(line->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(r, g, bl);
  actor->GetProperty()->SetLineWidth(3.0F);
  return actor;
}

}  // namespace

TraineeWindow::TraineeWindow(std::unique_ptr<live::LiveExercise> exercise, const QString& case_name, bool start,
                             QWidget* parent)
    : QMainWindow(parent),
      exercise_(std::move(exercise)),
      dial_(exercise_->thresholds(), live::PressureDial::middle_of(live::PressureLevel::Medium),
            exercise_->deepest_share()) {
  setWindowTitle(tr("Palpa: trainee exercise (%1)").arg(case_name));
  fit_to_screen(*this, {1200, 696});  // a 1280 x 800 screen under a title bar and a panel

  auto* central = new QWidget(this);
  auto* layout = new QHBoxLayout(central);
  view_ = new VtkView(central);
  // The pointer palpates without a button held: a native window gets every move.
  view_->input()->installEventFilter(this);
  layout->addWidget(view_, 1);

  QPushButton* mark_button = nullptr;
  QWidget* side_widget = build_side_panel(central, mark_button);
  layout->addWidget(side_widget);
  setCentralWidget(central);
  build_status_bar();

  connect(mark_button, &QPushButton::clicked, this, &TraineeWindow::place_mark);
  connect(remove_button_, &QPushButton::clicked, this, &TraineeWindow::remove_selected_mark);
  connect(finish_button_, &QPushButton::clicked, this, &TraineeWindow::finish);
  connect(&timer_, &QTimer::timeout, this, &TraineeWindow::frame);
  auto* close_key = new QShortcut(QKeySequence(tr("Ctrl+W")), this);
  connect(close_key, &QShortcut::activated, this, &QWidget::close);

  // Keys belong to the window, not to whichever panel widget was clicked last: the panel
  // takes no keyboard focus, the window's centre does (M and Up/Down work at once).
  for (auto* w : side_widget->findChildren<QWidget*>()) w->setFocusPolicy(Qt::NoFocus);
  central->setFocusPolicy(Qt::StrongFocus);
  central->setFocus();

  build_scene();
  apply_pressure();
  if (start) {
    scheduling_ = exercise_->start();
  } else {
    finish_button_->setEnabled(false);
    mark_button->setEnabled(false);
  }
  remove_button_->setEnabled(false);
  connect(marks_list_, &QListWidget::itemSelectionChanged, this,
          [this] { remove_button_->setEnabled(!marks_list_->selectedItems().isEmpty() && !score_); });
  update_status();
  fps_clock_.start();
  timer_.setTimerType(Qt::PreciseTimer);
  timer_.start(16);  // ~60 Hz
}

TraineeWindow::~TraineeWindow() = default;

// The panel beside the view: what to do, the device banner, the force gauge and pressure,
// the force mode, the marks and the finish button.
QWidget* TraineeWindow::build_side_panel(QWidget* central, QPushButton*& mark_button) {
  auto* side = new QVBoxLayout;
  const auto tumours = exercise_->placed_case().tumours.size();
  const QString task = tumours == 1 ? tr("Find the tumour.") : tumours == 0 ? tr("Is there a tumour?")
                                                                            : tr("Find the %1 tumours.").arg(tumours);
  auto* help = new QLabel(tr("<b>%1</b><br>Move the pointer over the body: the finger slides over the skin at the "
                             "pressure you choose (<b>wheel</b> or <b>Up/Down</b>). A lump pushes back: a bump in the "
                             "trace, the finger held back. <b>M</b> marks the finger's spot. Left drag turns the view, "
                             "Ctrl+wheel zooms.").arg(task),
                          central);
  help->setWordWrap(true);
  side->addWidget(help);
  device_banner_ = new QLabel(central);
  device_banner_->setWordWrap(true);
  device_banner_->setStyleSheet("background: #fbe3b0; color: #5a3b00; padding: 6px; border: 1px solid #d9a441");
  device_banner_->hide();
  side->addWidget(device_banner_);
  const auto& th = exercise_->thresholds();
  gauge_ = new ForceGauge(th.light_max, th.deep_min, central);
  side->addWidget(gauge_);
  pressure_label_ = new QLabel(central);
  pressure_label_->setWordWrap(true);
  side->addWidget(pressure_label_);
  trace_ = new PushBackTrace(central);
  side->addWidget(trace_);
  sticky_box_ = new QCheckBox(tr("Finger sticks on firm tissue"), central);
  sticky_box_->setObjectName("stickyFinger");
  sticky_box_->setToolTip(tr("Where the tissue is firmer than along the stroke so far, the finger follows the "
                             "pointer more slowly, as a firm lump holds a sliding finger back; it catches up "
                             "when the tissue is plain again or the pointer rests."));
  sticky_box_->setChecked(true);
  side->addWidget(sticky_box_);
  add_coverage_controls(side, central);
  force_mode_ = new QCheckBox(tr("Press to a force instead (F)"), central);
  force_mode_->setToolTip(tr("The finger sinks until it feels the chosen force (1-15 N): over a stiff lump it "
                             "sinks less. The wheel then sets the force."));
  side->addWidget(force_mode_);
  connect(force_mode_, &QCheckBox::toggled, this,
          [this](bool on) { set_force_mode(on ? (force_target_ > 0.0 ? force_target_ : kDefaultForceTarget) : 0.0); });
  auto* marks_box = new QGroupBox(tr("Marks"), central);
  auto* marks_layout = new QVBoxLayout(marks_box);
  marks_list_ = new QListWidget(marks_box);
  marks_list_->setMinimumHeight(3 * marks_list_->fontMetrics().lineSpacing());  // three marks; it grows with the window
  marks_layout->addWidget(marks_list_);
  mark_button = new QPushButton(tr("Mark here (M)"), marks_box);
  mark_button->setObjectName("markHere");
  mark_button_ = mark_button;
  remove_button_ = new QPushButton(tr("Remove"), marks_box);
  auto* mark_buttons = new QHBoxLayout;
  mark_buttons->addWidget(mark_button);
  mark_buttons->addWidget(remove_button_);
  marks_layout->addLayout(mark_buttons);
  side->addWidget(marks_box, 1);
  finish_button_ = new QPushButton(tr("Finish and score"), central);
  side->addWidget(finish_button_);
  auto* side_widget = new QWidget(central);
  side_widget->setLayout(side);
  side_widget->setFixedWidth(300);
  return side_widget;
}

// The live coverage figure and the overlay's switch; neither when the case turns the
// overlay off (an exam).
void TraineeWindow::add_coverage_controls(QVBoxLayout* side, QWidget* central) {
  training_ = io::training_from_case(exercise_->placed_case().document);
  coverage_label_ = new QLabel(central);
  coverage_label_->setObjectName("liveCoverage");
  coverage_label_->setToolTip(tr("The share of the exam region your finger pad has touched so far, and of it at "
                                 "deep pressure: what the score card will say."));
  side->addWidget(coverage_label_);
  overlay_box_ = new QCheckBox(tr("Show coverage on the body (C)"), central);
  overlay_box_->setObjectName("coverageOverlay");
  overlay_box_->setToolTip(tr("Orange: not touched yet; blue: touched at light or medium pressure only; green: "
                              "pressed deep"));
  overlay_box_->setChecked(training_.coverage_overlay);
  side->addWidget(overlay_box_);
  connect(overlay_box_, &QCheckBox::toggled, this, [this](bool on) {
    if (overlay_) overlay_->set_visible(on && !score_);
    request_render();
  });
  coverage_label_->setVisible(training_.coverage_overlay);
  overlay_box_->setVisible(training_.coverage_overlay);
}

QString TraineeWindow::coverage_text() const {
  if (!coverage_) return {};
  return tr("Covered so far: %1 (deep %2)")
      .arg(QString::fromStdString(score::percent_text(coverage_->coverage())),
           QString::fromStdString(score::percent_text(coverage_->deep_coverage())));
}

bool TraineeWindow::coverage_overlay_shown() const { return overlay_ && overlay_->visible(); }

// The snapshot's contact into the live coverage (once per snapshot); the overlay and the
// figure follow when a cell reached a new level.
void TraineeWindow::feed_coverage(const engine::SceneSnapshot& s) {
  if (s.tick == fed_tick_) return;
  fed_tick_ = s.tick;
  if (exercise_->paused()) {
    coverage_->lift();
  } else {
    coverage_->contact(s.body, s.u, s.v, s.depth);
  }
  if (coverage_->version() == shown_coverage_version_) return;
  shown_coverage_version_ = coverage_->version();
  coverage_label_->setText(coverage_text());
  if (overlay_->sync() && overlay_->visible()) request_render();
}

double TraineeWindow::exam_region_view_share() const {
  constexpr double kPickTolerance = 0.001;  // m: the pick lands on the point itself
  double total = 0.0, seen = 0.0;
  const QRect rect = view_->rect();
  for (std::size_t b = 0; b < coverage_->bodies(); ++b) {
    const auto& area = coverage_->areas(b);
    const auto& centre = coverage_->centers(b);
    for (std::size_t k = 0; k < centre.size(); ++k) {
      if (!(area[k] > 0.0)) continue;
      total += area[k];
      const QPoint at = to_view(centre[k]);
      if (!rect.contains(at)) continue;
      const auto [near, far] = view_->pointer_ray(*renderer_, at);
      const auto pick = exercise_->pick(near, far - near);
      if (pick && (pick->point - centre[k]).norm() <= kPickTolerance) seen += area[k];
    }
  }
  return total > 0.0 ? seen / total : 0.0;
}

void TraineeWindow::build_status_bar() {
  status_loop_ = new QLabel(this);
  status_fps_ = new QLabel(this);
  status_fps_->setToolTip(tr("Frames drawn in the last second: a view that does not change is redrawn only four times a second"));
  statusBar()->addWidget(status_loop_, 1);
  statusBar()->addPermanentWidget(status_fps_);
  status_upload_ = new QLabel(this);
  status_upload_->setObjectName("uploadState");
  status_upload_->setVisible(false);
  statusBar()->addPermanentWidget(status_upload_);

}

void TraineeWindow::build_scene() {
  render_window_ = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  renderer_ = add_body_renderer(*view_, render_window_);

  surfaces_ = std::make_unique<BodySurfaces>(exercise_->meshes(), renderer_);
  // Down on the exam region along its mean skin normal: a mouse can palpate only the skin it
  // can point at, and from the front the crest of a dome hides its far slope.
  coverage_ = std::make_unique<live::LiveCoverage>(exercise_->scene(), exercise_->thresholds());
  const auto bounds = scene_bounds(exercise_->scene());
  const Vec3 middle(0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5]));
  const RegionFacing region = region_facing(*coverage_, middle);
  if (region.points.empty()) {
    frame_from_front(*renderer_, bounds, 1.5);
  } else {
    frame_region(*renderer_, region, bounds);
  }
  double eye[3];
  renderer_->GetActiveCamera()->GetPosition(eye);
  overlay_ = std::make_unique<CoverageOverlay>(*coverage_, renderer_, Vec3(eye[0], eye[1], eye[2]));
  overlay_->set_visible(training_.coverage_overlay);
  coverage_label_->setText(coverage_text());

  probe_ = sphere_actor(palpa::Vec3::Zero(), kFingertipRadius, 0.85, 0.88, 0.95);
  // Opaque: one translucent actor makes VTK add its order-independent translucency passes
  // (extra full-window buffers and a composite), which with software OpenGL cost ~9 ms a
  // frame (palpa --bench, BENCHMARKS.md).
  probe_->VisibilityOff();
  renderer_->AddActor(probe_);
}

QPoint TraineeWindow::to_view(const palpa::Vec3& point) const {
  return view_->to_view(*renderer_, point);
}

void TraineeWindow::step_pressure(int steps) {
  if (force_target_ > 0.0) {
    force_target_ = std::clamp(force_target_ + steps, kMinForceTarget, kMaxForceTarget);
  } else {
    dial_.step(steps);
  }
  apply_pressure();
}

void TraineeWindow::set_force_mode(double newtons) {
  force_target_ = newtons > 0.0 ? std::clamp(newtons, kMinForceTarget, kMaxForceTarget) : 0.0;
  if (force_mode_->isChecked() != (force_target_ > 0.0)) {
    const QSignalBlocker quiet(force_mode_);
    force_mode_->setChecked(force_target_ > 0.0);
  }
  apply_pressure();
}

QString TraineeWindow::pressure_text() const {
  if (force_target_ > 0.0) {
    return tr("Pressure: to %1 N (force mode)").arg(force_target_, 0, 'f', 0);
  }
  return tr("Pressure: %1, step %2 of %3")
      .arg(live::to_string(dial_.level()))
      .arg(dial_.step_in_level())
      .arg(live::PressureDial::kStepsPerLevel);
}

void TraineeWindow::apply_pressure() {
  if (force_target_ > 0.0) {
    exercise_->set_force_target(force_target_);
  } else {
    exercise_->set_pressure_share(dial_.share());
  }
  pressure_label_->setText(pressure_text());
}

void TraineeWindow::place_mark() {
  request_render();
  if (!exercise_->started() || exercise_->finished()) return;
  const auto mark = exercise_->place_mark();
  // Drawn on the surface where the finger was, so it stays visible when the tissue springs back.
  palpa::Vec3 at = mark.position;
  if (picked_ && picked_->distance >= 0.0) at = picked_->point;
  // Neutral until the score says which marks hit (reveal: green for a hit, red for a false mark).
  auto actor = sphere_actor(at, 0.0025, kMarkColour[0], kMarkColour[1], kMarkColour[2]);
  renderer_->AddActor(actor);
  mark_actors_.emplace_back(mark.id, actor);
  auto* item = new QListWidgetItem(tr("Mark %1 at %2 s").arg(mark.id).arg(mark.t, 0, 'f', 1), marks_list_);
  item->setData(Qt::UserRole, QVariant::fromValue<qlonglong>(mark.id));
}

void TraineeWindow::remove_selected_mark() {
  request_render();
  const auto selected = marks_list_->selectedItems();
  for (auto* item : selected) {
    const auto id = static_cast<std::int64_t>(item->data(Qt::UserRole).toLongLong());
    if (!exercise_->remove_mark(id)) continue;
    for (auto it = mark_actors_.begin(); it != mark_actors_.end(); ++it) {
      if (it->first == id) {
        renderer_->RemoveActor(it->second);
        mark_actors_.erase(it);
        break;
      }
    }
    delete item;
  }
}

void TraineeWindow::finish() {
  if (!exercise_->started() || exercise_->finished()) return;
  try {
    score_ = exercise_->finish();
  } catch (const std::exception& e) {
    statusBar()->showMessage(tr("Could not score the session: %1").arg(e.what()));
    return;
  }
  finish_button_->setEnabled(false);
  remove_button_->setEnabled(false);
  mark_button_->setEnabled(false);
  gauge_->set_contact(live::ContactInfo{});  // no finger on the body any more
  trace_->clear();
  gauge_->setEnabled(false);
  update_status();
  emit session_ended(QString::fromStdString(exercise_->session_path().string()), true);
  reveal(*score_);
  score_card_ = new ScoreCard(*score_, QString::fromStdString(exercise_->session_path().string()), this);
  score_card_->setAttribute(Qt::WA_DeleteOnClose, false);
  // Without a window manager nothing gives the keys back to this window when the card
  // closes: take them back, so M, Ctrl+W and Ctrl+Q work without a click.
  connect(score_card_, &QDialog::finished, this, [this] { take_keys(*this, centralWidget()); });
  score_card_->show();
}

void TraineeWindow::reveal(const score::Score& score) {
  request_render();
  surfaces_->set_opacity(0.35);
  overlay_->set_visible(false);  // the tumours and the marks now; the score card has the maps
  for (const auto& t : score.tumours) {
    const palpa::Vec3 c(t.center[0], t.center[1], t.center[2]);
    renderer_->AddActor(t.found ? sphere_actor(c, t.radius, 0.20, 0.65, 0.25) : sphere_actor(c, t.radius, 0.75, 0.15, 0.15));
  }
  for (const auto& m : score.marks) {
    const palpa::Vec3 p(m.position[0], m.position[1], m.position[2]);
    colour_mark(m);
    if (m.tumour >= 0) {
      const auto& t = score.tumours[static_cast<std::size_t>(m.tumour)];
      renderer_->AddActor(line_actor(p, to_vec3(t.center), 0.2, 0.8, 0.3));
    } else if (!score.tumours.empty()) {
      // A false mark: a red line to the tumour nearest to it.
      const auto nearest = std::min_element(score.tumours.begin(), score.tumours.end(), [&](const auto& a, const auto& b) {
        return (to_vec3(a.center) - p).norm() <
               (to_vec3(b.center) - p).norm();
      });
      renderer_->AddActor(
          line_actor(p, to_vec3(nearest->center), 0.9, 0.2, 0.2));
    }
  }
  probe_->VisibilityOff();
  if (ring_) ring_->VisibilityOff();
  render_window_->Render();
}

void TraineeWindow::colour_mark(const score::MarkResult& m) {
  for (const auto& [id, actor] : mark_actors_) {
    if (id != m.id) continue;
    if (m.tumour >= 0) {
      actor->GetProperty()->SetColor(0.20, 0.80, 0.30);  // found a tumour: green
    } else if (m.duplicate) {
      actor->GetProperty()->SetColor(0.95, 0.70, 0.15);  // a tumour found already: amber
    } else {
      actor->GetProperty()->SetColor(0.90, 0.15, 0.15);  // a false mark: red
    }
  }
}

void TraineeWindow::look_at_body(std::size_t body) {
  request_render();
  const auto& box = exercise_->scene().body(body).bounds;
  double bounds[6] = {box.lo.x(), box.hi.x(), box.lo.y(), box.hi.y(), box.lo.z(), box.hi.z()};
  renderer_->ResetCamera(bounds);
  renderer_->GetActiveCamera()->Zoom(2.5);  // the body's middle fills the view
  renderer_->ResetCameraClippingRange();
}

void TraineeWindow::set_frame_interval(int ms) {
  skip_unchanged_ = ms >= 0;  // a driver calling frame() itself gets every frame drawn
  if (ms < 0) {
    timer_.stop();
  } else {
    timer_.start(ms);
  }
}

void TraineeWindow::frame() {
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); };
  auto t0 = Clock::now();
  auto t1 = t0, t2 = t0;
  last_frame_.bodies_changed = 0;
  fit_bodies_to_view();
  if (exercise_->started() && !exercise_->finished()) {
    exercise_->update();
    t1 = Clock::now();
    last_frame_.bodies_changed = surfaces_->sync(exercise_->meshes());
    t2 = Clock::now();
    const auto& s = exercise_->snapshot();
    feed_coverage(s);
    if (s.tick > 0) {
      // The fingertip rests on the dent: its centre one radius out from the probe point.
      const palpa::Vec3 n = picked_ ? picked_->normal : palpa::Vec3::UnitZ();
      const palpa::Vec3 c = to_vec3(s.probe) + kFingertipRadius * n;
      if (!probe_->GetVisibility() || (c - drawn_probe_).norm() > kProbeMoveToDraw) request_render();
      probe_->SetPosition(c.x(), c.y(), c.z());
      probe_->VisibilityOn();
      drawn_probe_ = c;
    }
    gauge_->set_contact(exercise_->contact());
    feel();
    if (exercise_->device_switched() && device_banner_->isHidden()) {
      // The chosen device was unplugged (or failed): the force went to zero and the mouse
      // drives the probe now; the session goes on.
      device_banner_->setText(QString::fromStdString(exercise_->device_message()));
      device_banner_->show();
      update_status();
    }
  }
  const auto t3 = Clock::now();
  // An unchanged scene is not drawn again (under a software renderer a frame costs a core),
  // except a few times a second in case something changed that nothing reported.
  if (last_frame_.bodies_changed > 0) request_render();
  if (overlay_->fit_to_view()) request_render();  // the camera moved: the dots thinned for it
  if (!skip_unchanged_ || render_requested_ || !since_render_.isValid() || since_render_.elapsed() >= kIdleRedrawMs) {
    if (!skip_unchanged_ || render_requested_) ++changed_frames_;
    render_window_->Render();
    render_requested_ = false;
    since_render_.start();
    ++frames_;
  }
  last_frame_.tessellate = seconds(t0, t1);
  last_frame_.upload = seconds(t1, t2);
  last_frame_.render = seconds(t3, Clock::now());
  if (fps_clock_.elapsed() >= 1000) {
    frame_rate_ = frames_ * 1000.0 / static_cast<double>(fps_clock_.restart());
    frames_ = 0;
    idle_ = changed_frames_ == 0;
    changed_frames_ = 0;
    update_status();
  }
}

void TraineeWindow::update_status() {
  // Only the few redraws of an unchanged view: the rate says nothing, the view is idle.
  status_fps_->setText(idle_ ? tr("idle") : tr("%1 fps").arg(frame_rate_, 0, 'f', 0));
  if (!exercise_->started()) {
    status_loop_->setText(tr("not started | device: %1").arg(QString::fromStdString(exercise_->device_name())));
    return;
  }
  const auto& stats = exercise_->loop_stats();
  const double mean = stats.mean_period();
  const double rate = mean > 0.0 ? 1.0 / mean : 0.0;
  const double jitter_us = (stats.period_percentile(0.99) - stats.period_percentile(0.5)) * 1e6;
  status_loop_->setText(tr("haptic %1 Hz | jitter (p99-p50) %2 us | missed %3 | device: %4%5")
                            .arg(rate, 0, 'f', 0)
                            .arg(jitter_us, 0, 'f', 0)
                            .arg(static_cast<qulonglong>(stats.missed()))
                            .arg(QString::fromStdString(exercise_->device_name()))
                            .arg(exercise_->finished() ? tr(" | finished") : QString()));
  status_loop_->setToolTip(QString::fromStdString(scheduling_));
}

bool TraineeWindow::handle_key(const QKeyEvent& event) {
  // Ctrl+W and Ctrl+Q also without a window manager (no active window: no shortcut fires).
  if (event.modifiers() & Qt::ControlModifier) {
    if (event.key() == Qt::Key_W) {
      close();
      return true;
    }
    if (event.key() == Qt::Key_Q) {
      QApplication::closeAllWindows();
      return true;
    }
    return false;
  }
  switch (event.key()) {
    case Qt::Key_M: place_mark(); return true;
    case Qt::Key_Up: step_pressure(1); return true;
    case Qt::Key_Down: step_pressure(-1); return true;
    case Qt::Key_F: set_force_mode(force_target_ > 0.0 ? 0.0 : kDefaultForceTarget); return true;
    case Qt::Key_C:
      if (training_.coverage_overlay && !score_) overlay_box_->toggle();
      return true;
    default: return false;
  }
}

void TraineeWindow::keyPressEvent(QKeyEvent* event) {
  if (!handle_key(*event)) QMainWindow::keyPressEvent(event);
}

bool TraineeWindow::eventFilter(QObject* watched, QEvent* event) {
  if (watched != view_->input()) return QMainWindow::eventFilter(watched, event);
  switch (event->type()) {
    case QEvent::MouseButtonPress:
    case QEvent::MouseButtonRelease:
    case QEvent::Resize:
    case QEvent::Expose:
    case QEvent::Show:
      request_render();  // a drag turns the view; a new size or an uncovered view needs a frame
      break;
    default:
      break;
  }
  switch (event->type()) {
    case QEvent::MouseMove: {
      auto* e = static_cast<QMouseEvent*>(event);
      if (e->buttons() != Qt::NoButton) {
        request_render();
        control_display_.reset(Eigen::Vector2d(e->pos().x(), e->pos().y()));  // the view turns under the pointer
      }
      if (e->buttons() == Qt::NoButton) palpate_at(e->pos());
      return false;  // VTK still turns the view on a drag
    }
    case QEvent::Wheel: {
      auto* e = static_cast<QWheelEvent*>(event);
      if (e->modifiers() & Qt::ControlModifier) return false;  // VTK zooms
      wheel_rest_ += e->angleDelta().y();
      const int notches = wheel_rest_ / 120;  // a notch is 120; touchpads send less at a time
      wheel_rest_ -= notches * 120;
      if (notches != 0) step_pressure(notches);
      return true;
    }
    case QEvent::KeyPress:
      handle_key(*static_cast<QKeyEvent*>(event));
      return true;  // no VTK key bindings (its 'q' and 'e' would end the application)
    default:
      return false;
  }
}

void TraineeWindow::show_upload_state(const QString& text) {
  status_upload_->setText(text);
  status_upload_->setToolTip(text);
  status_upload_->setVisible(!text.isEmpty());
}

void TraineeWindow::closeEvent(QCloseEvent* event) {
  if (exercise_->started() && !exercise_->finished()) {
    // Closed without a question: with a reason (a signal, the window destroyed) the attempt
    // is abandoned with it; without one (an instructor closing a Try it) it ends complete
    // and unscored.
    const bool ask = !property(kCloseWithoutAsking).toBool();
    const QString reason = property(kCloseReason).toString();
    switch (ask ? ask_before_closing() : reason.isEmpty() ? CloseChoice::Finish : CloseChoice::Abandon) {
      case CloseChoice::GoOn:
        event->ignore();
        return;
      case CloseChoice::FinishAndScore:
        finish();  // the score card opens; the window stays to show the tumours
        event->ignore();
        return;
      case CloseChoice::Abandon:
        try {
          exercise_->abandon(reason.isEmpty() ? "the trainee closed the window" : reason.toStdString());
        } catch (const std::exception&) {
          // The file keeps what was committed; nothing more to do on the way out.
        }
        break;
      case CloseChoice::Finish:
        try {
          exercise_->finish("window closed before finishing");  // the session ends complete, unscored here
        } catch (const std::exception&) {
        }
        break;
    }
    emit session_ended(QString::fromStdString(exercise_->session_path().string()), false);
  }
  timer_.stop();
  QMainWindow::closeEvent(event);
}

TraineeWindow::CloseChoice TraineeWindow::ask_before_closing() {
  QMessageBox box(QMessageBox::Question, tr("The exercise is still running"),
                  tr("Finish and score this attempt, abandon it (it is kept, marked as abandoned, and does not "
                     "count as an exam), or go on palpating?"),
                  QMessageBox::NoButton, this);
  box.setObjectName("closeQuestion");
  auto* finish = box.addButton(tr("Finish and score"), QMessageBox::AcceptRole);
  auto* abandon = box.addButton(tr("Abandon"), QMessageBox::DestructiveRole);
  auto* go_on = box.addButton(tr("Go on"), QMessageBox::RejectRole);
  box.setDefaultButton(go_on);
  box.setEscapeButton(go_on);
  box.exec();
  if (box.clickedButton() == finish) return CloseChoice::FinishAndScore;
  if (box.clickedButton() == abandon) return CloseChoice::Abandon;
  return CloseChoice::GoOn;
}

}  // namespace palpa::ui
