// Acceptance: palpation as a person does it, through the trainee window's own input
// events (QTest mouse moves, wheel notches and keys sent to the window; nothing calls into
// the window to move the finger). Slides onto the body from each of its four edges at
// light, medium and deep; sweeps across it at 20, 50 and 150 mm/s; a press held at the
// thin rim; jumps between distant points; the level changed while moving. The recorded
// session is then checked against a fresh press at each sample's own spot. And a mouse
// trainee: a systematic exam in vertical strips a finger pad apart at three levels, marks
// where the tissue pushes back hardest for its depth, finishes, and passes; with light
// pressure only it fails deep coverage.
//
// The short form (CI) runs the default case and the two-domes case for the slides and the
// default case for the exam; PALPA_LONG_TESTS=1 adds every instructor preset with a
// tumour and a case with two tumours to the exam.
#include <QApplication>
#include <QMessageBox>
#include <QTimer>
#include <QMouseEvent>
#include <QPushButton>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QVTKOpenGLNativeWidget.h>
#include <QWheelEvent>
#include <QWindow>
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>


#include "palpa/author/presets.hpp"
#include "palpa/contact/contact.hpp"
#include "palpa/deform/deformed_body.hpp"
#include "palpa/engine/engine.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/live/live_exercise.hpp"
#include "palpa/render/surface_pick.hpp"
#include "palpa/ui/force_gauge.hpp"
#include "palpa/ui/trainee_window.hpp"
#include "palpa/ui/vtk_view.hpp"

namespace {

using palpa::Vec3;
using palpa::live::PressureDial;
using palpa::live::PressureLevel;

const std::string kCases = PALPA_SOURCE_DIR "/data/cases/";

bool long_form() { return std::getenv("PALPA_LONG_TESTS") != nullptr; }

std::unique_ptr<palpa::ui::TraineeWindow> open_window(const palpa::io::CaseFile& file, const std::string& name,
                                                      const QString& session, std::uint64_t seed = 11) {
  palpa::live::LiveOptions o;
  o.trainee = "mouse-trainee";
  o.seed = seed;
  o.session_path = session.toStdString();
  o.realtime.request_fifo = false;
  auto window = std::make_unique<palpa::ui::TraineeWindow>(
      std::make_unique<palpa::live::LiveExercise>(file, name, o), QString::fromStdString(name));
  window->resize(960, 640);  // a laptop's window (and half the pixels llvmpipe draws)
  window->show();
  window->activateWindow();
  return window;
}

/// What the test did, on the haptic clock: the pressure chosen and whether the pointer was
/// over a body (and how thick the tissue under it was).
struct Step {
  double t = 0.0;
  double share = 0.0;
  bool on_body = false;
  double thickness = 0.0;
  double x = 0.0, y = 0.0;       // the pointer's plan position
  bool follower_on = false;      // what the window's finger meant to do (for the problem report)
  double follower_press = 0.0;
};

/// A person at the mouse: moves the pointer over scene points, turns the wheel, presses
/// keys, and keeps a log of what it chose when.
class Hand {
 public:
  explicit Hand(palpa::ui::TraineeWindow& w) : w_(w) {}

  palpa::live::LiveExercise& live() { return w_.exercise(); }
  double now() const { return w_.exercise().snapshot().t; }

  /// The top contour's point over plan position (x, y), if the body is there.
  std::optional<palpa::render::SurfacePick> top_at(double x, double y) const {
    return w_.exercise().pick(Vec3(x, y, 1.0), Vec3(0, 0, -1));
  }

  /// Moves the pointer over plan position (x, y): onto the skin there, or where the
  /// chest wall would be beside the body.
  void point_at(double x, double y) {
    const auto hit = top_at(x, y);
    const Vec3 at = hit ? hit->point : Vec3(x, y, 0.0);
    const QPoint px = w_.to_view(at);
    QMouseEvent move(QEvent::MouseMove, px, w_.view()->input()->mapToGlobal(px), Qt::NoButton, Qt::NoButton,
                     Qt::NoModifier);
    QApplication::sendEvent(w_.view()->input(), &move);
    // On the body is what the pointer's pixel shows: the ray through it (a point on the far
    // slope at the silhouette may be a pixel off the body).
    const auto [near, far] = w_.view()->pointer_ray(*w_.renderer(), px);
    const auto seen = w_.exercise().pick(near, far - near);
    on_body_ = seen.has_value();
    pointer_ = Vec3(x, y, 0.0);
    thickness_ = 0.0;
    if (seen) {
      const auto& sb = w_.exercise().scene().body(seen->body);
      const auto foot = sb.search.closest(sb.body.skeleton(), seen->point);
      thickness_ = 2.0 * palpa::contact::make_contact(sb.body, foot, foot.point).radius;
    }
    log();
  }

  /// Turns the wheel (over the view) until the dial shows `index`.
  void set_level(int index) {
    while (w_.pressure().index() != index) {
      const int notch = w_.pressure().index() < index ? 1 : -1;
      const QPoint px = w_.view()->input()->geometry().center() - w_.view()->input()->geometry().topLeft();
      QWheelEvent e(QPointF(px), QPointF(w_.view()->input()->mapToGlobal(px)), QPoint(), QPoint(0, 120 * notch),
                    Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
      QApplication::sendEvent(w_.view()->input(), &e);
    }
    log();
  }

  /// Keys to the window itself (it is active: nothing was clicked first).
  void key(Qt::Key k) {
    QTest::keyClick(&w_, k);
    log();
  }

  /// Slides the pointer along the plan line a -> b at `speed` (m/s) of the haptic clock,
  /// one move per turn of the event loop (however long the machine takes to draw a frame).
  void slide(double ax, double ay, double bx, double by, double speed, const std::function<void()>& each = {}) {
    const double length = std::hypot(bx - ax, by - ay);
    const double t0 = now();
    for (;;) {
      const double s = length > 0.0 ? std::min(1.0, (now() - t0) * speed / length) : 1.0;
      point_at(ax + s * (bx - ax), ay + s * (by - ay));
      if (each) each();
      if (s >= 1.0) break;
      QTest::qWait(10);
    }
  }

  void wait(double seconds) {
    QTest::qWait(static_cast<int>(seconds * 1000.0));
    log();
  }

  const std::vector<Step>& steps() const { return steps_; }
  /// The plan position the pointer was last moved over.
  const Vec3& pointer() const { return pointer_; }

 private:
  void log() {
    const auto& f = w_.exercise().follower();
    steps_.push_back({now(), w_.pressure().share(), on_body_, thickness_, pointer_.x(), pointer_.y(), f.on_body(), f.press()});
  }

  palpa::ui::TraineeWindow& w_;
  bool on_body_ = false;
  Vec3 pointer_ = Vec3::Zero();
  double thickness_ = 0.0;
  std::vector<Step> steps_;
};

/// The force a fresh press from above gives at spot (u, v) of `body` at `share` of the thickness.
double fresh_press(const palpa::scene::Scene& scene, int body, double u, double v, double share) {
  const auto& sb = scene.body(static_cast<std::size_t>(body));
  palpa::contact::FootPoint foot;
  std::array<double, 7> sk{};
  sb.body.skeleton().evaluate(u, v, sk);
  const auto frame = palpa::live::surface_frame(sb.body, u, v);
  const Vec3 q = frame.top - share * frame.thickness * frame.normal;
  auto state = scene.make_state();
  return scene.probe(q, state, {}).force.total.norm();
}

struct Findings {
  int samples = 0, checked = 0, over = 0, zero_on_body = 0, off_band = 0, faulted = 0;
  double worst_ratio = 0.0;
  QString first_problem;
  QStringList problems;  // the first few of each kind, with what was chosen and felt
  std::map<char, int> noted;
  void note(char kind, const QString& what) {
    if (first_problem.isEmpty()) first_problem = what;
    if (noted[kind]++ < 5) problems << what;
  }
};

/// s: how long the finger may take to follow a change of the pointer or the pressure
/// (walk there, come down from the lift, sink to the new share).
constexpr double kSettle = 0.5;
constexpr double kTracking = 0.03;  // share of the local thickness

/// Checks every recorded sample against what the hand chose at that time (docs: the
/// acceptance criteria of docs/user-guide.md, "How pressure works").
Findings check_session(const palpa::session::Session& s, const palpa::scene::Scene& scene,
                       const std::vector<Step>& steps, const palpa::io::Thresholds& th) {
  Findings f;
  std::size_t at = 0;
  for (const auto& sample : s.samples) {
    ++f.samples;
    while (at + 1 < steps.size() && steps[at + 1].t <= sample.t) ++at;
    if (steps.empty() || sample.t < steps.front().t) continue;
    // What was chosen in the last half second (the finger needs time to get there), and
    // since when the choice and the pointer have been steady.
    double share = 0.0;
    bool steady = true, on_body = true;
    double thickness = 1.0;
    for (std::size_t k = at + 1; k-- > 0;) {
      // Step k was in force from its time to the next step's: does that reach into the window?
      if (k < at && steps[k + 1].t < sample.t - kSettle) break;
      share = std::max(share, steps[k].share);
      steady = steady && steps[k].share == steps[at].share;
      on_body = on_body && steps[k].on_body;
      thickness = std::min(thickness, steps[k].thickness);
    }
    const double force = std::hypot(sample.force[0], sample.force[1], sample.force[2]);
    // A tick after the loop stalled (the machine was busy: no real-time priority in tests)
    // ramps the force to zero on purpose (the watchdog); it is counted, not judged.
    if (sample.fault) ++f.faulted;
    if (!sample.fault && on_body && thickness > 2e-3 && (sample.body < 0 || !(force > 0.0))) {
      ++f.zero_on_body;
      f.note('z', QString("no force on the body at t = %1 s (body %2, at %3 %4 %5 mm; pointer at %6 %7 mm, finger %8 press %9)")
                 .arg(sample.t).arg(sample.body).arg(sample.position[0] * 1e3).arg(sample.position[1] * 1e3).arg(sample.position[2] * 1e3)
                 .arg(steps[at].x * 1e3).arg(steps[at].y * 1e3).arg(steps[at].follower_on ? "on" : "off").arg(steps[at].follower_press));
    }
    if (sample.body < 0) continue;
    ++f.checked;
    // The finger follows its target within kTracking of the thickness (the virtual device
    // smooths the 60 Hz targets; over a tumour a millimetre deeper is newtons more).
    const double reference = fresh_press(scene, sample.body, sample.u, sample.v, share + kTracking);
    const double ratio = force / std::max(reference, 0.2);  // below 0.2 N: the rim, nothing to feel
    f.worst_ratio = std::max(f.worst_ratio, ratio);
    if (force > 1.25 * reference + 0.05) {
      ++f.over;
      f.note('o', QString("%1 N at t = %2 s where a fresh press at %3 % gives %4 N (depth %5 mm, at %6 %7 %8 mm)")
                 .arg(force).arg(sample.t).arg(share * 100).arg(reference).arg(sample.depth * 1e3)
                 .arg(sample.position[0] * 1e3).arg(sample.position[1] * 1e3).arg(sample.position[2] * 1e3));
    }
    const auto frame = palpa::live::surface_frame(scene.body(static_cast<std::size_t>(sample.body)).body, sample.u, sample.v);
    if (steady && on_body && !sample.fault && frame.thickness > 4e-3) {
      const double fraction = sample.depth / frame.thickness;
      const auto chosen = palpa::live::level_of(steps[at].share, th);
      if (palpa::live::level_of(fraction, th) != chosen && std::abs(fraction - steps[at].share) > 0.05) {
        ++f.off_band;
        f.note('b', QString("depth %1 % at t = %2 s, chosen %3 %").arg(fraction * 100).arg(sample.t).arg(steps[at].share * 100));
      }
    }
  }
  return f;
}

/// How far the drawn dent's deepest point is from the finger, in the plane of the skin:
/// the drawn top contour of the newest snapshot (the control points the window draws from,
/// on the engine's refined net) against its rest, on a fine (u, v) grid around the contact.
double dent_offset(palpa::ui::TraineeWindow& w) {
  const auto& shot = w.exercise().snapshot();
  if (shot.body < 0) return 0.0;
  const auto b = static_cast<std::size_t>(shot.body);
  const auto& body = w.exercise().scene().body(b).body;
  const auto net = palpa::deform::display_net(body, palpa::engine::EngineOptions{}.deform);
  auto drawn = net.top;
  if (shot.bodies[b].top.size() != drawn.control().size()) return 1.0;  // not the engine's net: fail loudly
  for (int i = 0; i < drawn.rows(); ++i)
    for (int j = 0; j < drawn.cols(); ++j)
      for (int c = 0; c < 3; ++c) drawn.control_point(i, j)[static_cast<std::size_t>(c)] = shot.bodies[b].top[static_cast<std::size_t>((i * drawn.cols() + j) * 3 + c)];
  double deepest = 0.0;
  Vec3 at = Vec3::Zero();
  std::array<double, 3> now{}, rest{};
  for (int a = -40; a <= 40; ++a) {
    for (int c = -40; c <= 40; ++c) {
      const double u = std::clamp(shot.u + a * 0.0025, 0.0, 1.0), v = std::clamp(shot.v + c * 0.0025, 0.0, 1.0);
      drawn.evaluate(u, v, now);
      net.top.evaluate(u, v, rest);
      const double sink = std::hypot(rest[0] - now[0], rest[1] - now[1], rest[2] - now[2]);
      if (sink > deepest) {
        deepest = sink;
        at = Vec3(now[0], now[1], now[2]);
      }
    }
  }
  if (deepest < 1e-3) return 0.0;  // no dent to speak of
  const Vec3 finger(shot.probe[0], shot.probe[1], shot.probe[2]);
  const Vec3 n = palpa::live::surface_frame(body, shot.u, shot.v).normal;
  const Vec3 d = at - finger;
  return (d - d.dot(n) * n).norm();
}

QPushButton* finish_button(palpa::ui::TraineeWindow& w) {
  for (auto* b : w.findChildren<QPushButton*>()) {
    if (b->text().startsWith("Finish")) return b;
  }
  return nullptr;
}

// --- the mouse trainee --------------------------------------------------------------

struct Reading {
  Vec3 finger;
  double force, depth;
  double share;      // depth / local thickness
  double thickness;  // m, local
};

/// A systematic exam: vertical strips (along y) `spacing` apart over the body's plan box, at
/// each level in turn, reading the gauge as it goes; then marks the spots where the tissue
/// pushes back hardest for its depth (force / depth against the same ratio 15-30 mm
/// around), at most `tumours` of them; then finishes.
// Shares of the case's safety limit (max_force, 20 N by default) a careful person keeps to.
constexpr double kEaseOff = 0.80;     // ease off a step above this (planned and felt)
constexpr double kPressAgain = 0.70;  // press deeper again when the next step's force stays below
constexpr double kPlanned = 0.85;     // the most a planned deep press may be expected to need
constexpr double kLookAhead = 0.008;  // m along the strip: about half a finger pad

palpa::score::Score mouse_exam(palpa::ui::TraineeWindow& w, Hand& hand, const std::vector<int>& levels, int tumours) {
  const auto& box = w.exercise().scene().body(0).bounds;
  // The plan extent of the top contour: where the picks hit.
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (double x = box.lo.x(); x <= box.hi.x(); x += 0.002) {
    for (double y = box.lo.y(); y <= box.hi.y(); y += 0.002) {
      if (!hand.top_at(x, y)) continue;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  }
  constexpr double kSpacing = 0.012;  // at most a finger pad apart: the strips overlap
  constexpr double kEdge = 0.003;     // the outermost strips run this close to the rim
  const int strips = 1 + static_cast<int>(std::ceil((x1 - x0 - 2.0 * kEdge) / kSpacing));
  const double speed = 0.09, deep_speed = 0.05;  // m/s: slower where the force must be watched
  std::vector<Reading> search;       // at the medium level
  std::vector<Reading> deep_search;  // at the deep pass's own setting
  std::vector<Vec3> marks;
  const int medium = PressureDial::middle_of(PressureLevel::Medium);
  // The force a press to `share` would give at plan point p, from the medium pass's
  // nearest readings (0 before there are any: nothing known yet).
  const auto planned_force = [&](const Vec3& p, double share) {
    double best = 1e9, at_medium = 0.0, depth_medium = 0.0;
    for (const auto& r : search) {
      const double d = std::hypot(r.finger.x() - p.x(), r.finger.y() - p.y());
      if (d < best) best = d, at_medium = r.force, depth_medium = r.share;
    }
    if (best > 0.01 || depth_medium <= 0.0) return 0.0;
    return at_medium * std::pow(share / depth_medium, 1.7);
  };
  const auto near_a_mark = [&](double x, double y) {
    return std::any_of(marks.begin(), marks.end(), [&](const Vec3& m) { return std::hypot(m.x() - x, m.y() - y) < 0.016; });
  };
  const int light = PressureDial::middle_of(PressureLevel::Light);
  for (const int level : levels) {
    // To the first strip's start lightly (a long move pressing deep would cross the thick
    // middle and any lump at full force), then the pass's own level.
    hand.set_level(light);
    hand.point_at(x0 + kEdge, y0);
    hand.wait(0.6);
    hand.set_level(level);
    const bool deep = palpa::live::PressureDial(w.exercise().thresholds(), level).level() == PressureLevel::Deep;
    bool up = true;
    for (int strip = 0; strip < strips; ++strip) {
      const double x = x0 + kEdge + strip * (x1 - x0 - 2.0 * kEdge) / (strips - 1);
      const double from = up ? y0 : y1, to = up ? y1 : y0;
      int current = level;
      double last_change = -1.0;
      hand.slide(x, from, x, to, deep ? deep_speed : speed, [&] {
        if (deep) {
          // As a person watching the gauge: ease off a step when the force nears the safety
          // limit (20 N), press deep again once it is well below; never deep on a lump found.
          // Deeper again only when the force, scaled to the next step's share, stays clear of
          // the ease-off point, and not before the finger has settled at the last change.
          const double force = w.gauge()->contact().force;
          const auto share_of = [&](int index) { return PressureDial(w.exercise().thresholds(), index).share(); };
          // What the medium pass taught about this spot: the force there at the medium share,
          // scaled to the deep share (tissue stiffens: F grows about like depth^1.7 here).
          // A person looks ahead: the spot a finger pad further along the strip counts too.
          const Vec3 ahead = hand.pointer() + Vec3(0.0, to > from ? kLookAhead : -kLookAhead, 0.0);
          const double limit = w.exercise().thresholds().max_force;
          const double planned_ok = planned_force(hand.pointer(), share_of(level)) < kPlanned * limit &&
                                    planned_force(ahead, share_of(level)) < kPlanned * limit;
          if ((force > kEaseOff * limit || !planned_ok) && current > medium) {
            --current;
            last_change = hand.now();
          } else if (current < level && hand.now() - last_change > 0.12 &&
                     force * share_of(current + 1) / share_of(current) < kPressAgain * limit) {
            ++current;
            last_change = hand.now();
          }
          if (near_a_mark(hand.pointer().x(), hand.pointer().y()) || near_a_mark(ahead.x(), ahead.y()))
            current = std::min(current, medium);
          hand.set_level(current);
        }
        // What the finger feels at the medium level, and at the pass's own deep setting
        // (a lump under thick or stiff tissue may only be felt deep).
        auto* readings = level == medium ? &search : (deep && current == level ? &deep_search : nullptr);
        if (!readings) return;
        const auto c = w.gauge()->contact();
        const auto& s = w.exercise().snapshot();
        // Where the tissue is thick enough to compare (at the thin rim the shear springs
        // and round-off of a millimetre's press dominate force / depth).
        if (c.depth > 4e-3 && c.thickness > 0.012)
          readings->push_back({Vec3(s.probe[0], s.probe[1], s.probe[2]), c.force, c.depth, c.fraction, c.thickness});
      });
      up = !up;
    }
    if (level != medium && !deep) continue;
    // The spots where force per depth stands out from its surroundings, felt at one level.
    // Tissue given in kPa feels firmer where it thins over the chest wall, by the layer's
    // factor for that thickness; a person who knows the breast discounts it (as the scripted
    // expert does), comparing how firm the tissue is, not how thin.
    const auto& felt = level == medium ? search : deep_search;
    const auto& layer = w.exercise().scene().body(0).layer;
    const auto firmness = [&layer](const Reading& r) {
      const double factor = layer ? (*layer)(1.0, r.thickness) : 0.0;
      return r.force / r.depth / (factor > 0.0 ? factor : 1.0);
    };
    std::vector<std::pair<double, Vec3>> candidates;
    for (const auto& r : felt) {
      std::vector<double> around;
      for (const auto& o : felt) {
        const double d = std::hypot(o.finger.x() - r.finger.x(), o.finger.y() - r.finger.y());
        if (d > 0.015 && d < 0.03) around.push_back(firmness(o));
      }
      if (around.size() < 10) continue;
      std::nth_element(around.begin(), around.begin() + static_cast<std::ptrdiff_t>(around.size() / 2), around.end());
      candidates.emplace_back(firmness(r) / around[around.size() / 2], r.finger);
    }
    std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    for (std::size_t k = 0; k < std::min<std::size_t>(3, candidates.size()); ++k)
      qInfo("  %s candidate %zu: force/depth %.2f x its surroundings at (%.1f, %.1f) mm", level == medium ? "medium" : "deep", k, candidates[k].first,
            candidates[k].second.x() * 1e3, candidates[k].second.y() * 1e3);
    for (const auto& [ratio, at] : candidates) {
      if (static_cast<int>(marks.size()) >= tumours || ratio < 1.15) break;
      const bool apart = std::all_of(marks.begin(), marks.end(), [&](const Vec3& m) { return (m - at).norm() > 0.025; });
      if (apart) marks.push_back(at);
    }
  }
  // Mark them: slide there at medium, let the finger settle, press M. (A light-only exam
  // never searched at medium: it has nothing to mark.)
  for (const auto& m : marks) {
    hand.set_level(light);
    hand.point_at(m.x(), m.y());
    hand.wait(0.6);
    hand.set_level(medium);
    hand.wait(0.4);
    hand.key(Qt::Key_M);
  }
  QTest::mouseClick(finish_button(w), Qt::LeftButton);
  {
    const auto session = palpa::session::read_session(w.exercise().session_path());
    const palpa::engine::Sample* peak = nullptr;
    double most = 0.0;
    for (const auto& x : session.samples) {
      const double f = std::hypot(x.force[0], x.force[1], x.force[2]);
      if (f > most) most = f, peak = &x;
    }
    if (peak) {
      const auto frame = palpa::live::surface_frame(w.exercise().scene().body(0).body, peak->u, peak->v);
      double share = 0.0;
      for (const auto& st : hand.steps()) if (st.t <= peak->t) share = st.share;
      qInfo("  peak %.1f N at t = %.2f s at (%.1f, %.1f) mm, depth %.0f %% of %.0f mm, chosen %.0f %%", most, peak->t,
            peak->position[0] * 1e3, peak->position[1] * 1e3, 100 * peak->depth / frame.thickness, frame.thickness * 1e3, share * 100);
      for (const auto& st : hand.steps()) {
        if (st.t < peak->t - 0.4 || st.t > peak->t + 0.1) continue;
        const auto it = std::lower_bound(session.samples.begin(), session.samples.end(), st.t,
                                         [](const palpa::engine::Sample& a, double t) { return a.t < t; });
        const auto& x = it == session.samples.end() ? session.samples.back() : *it;
        qInfo("    t %.3f: chosen %.0f %%, felt %.1f N, depth %.1f mm", st.t, st.share * 100,
              std::hypot(x.force[0], x.force[1], x.force[2]), x.depth * 1e3);
      }
    }
  }
  for (const auto& m : w.score()->marks)
    qInfo("  mark at (%.1f, %.1f, %.1f) mm: %s", m.position[0] * 1e3, m.position[1] * 1e3, m.position[2] * 1e3,
          m.tumour >= 0 ? "on a tumour" : "no tumour");
  return *w.score();
}

/// The skin (the top contour's point) over plan position (x, y) of a case's scene.
palpa::render::SurfacePick skin_at(const palpa::scene::Scene& scene, double x, double y) {
  const auto skin = palpa::render::TopContourPicker(scene).pick(Vec3(x, y, 1.0), Vec3(0, 0, -1));
  if (!skin) throw std::invalid_argument("no skin at the tumour's plan position");
  return *skin;
}

/// A tumour of `radius` whose centre is the skeleton point (mid-depth) under the skin at
/// plan position (x, y): the foot point of the skin's point there.
palpa::mat::Tumour tumour_under(const palpa::io::CaseFile& file, double x, double y, double radius, double stiffness) {
  const auto scene = palpa::scene::Scene::build(file, "case");
  const auto& sb = scene.body(0);
  const auto foot = sb.search.closest(sb.body.skeleton(), skin_at(scene, x, y).point);
  return {sb.body.id(), {foot.point.x(), foot.point.y(), foot.point.z()}, radius, stiffness};
}

/// A tumour of `radius` whose centre is `depth` under the skin at plan position (x, y),
/// along the skin's inward normal.
palpa::mat::Tumour tumour_below_skin(const palpa::io::CaseFile& file, double x, double y, double depth, double radius,
                                     double stiffness) {
  const auto scene = palpa::scene::Scene::build(file, "case");
  const auto skin = skin_at(scene, x, y);
  const Vec3 c = skin.point - depth * skin.normal;
  return {scene.body(0).body.id(), {c.x(), c.y(), c.z()}, radius, stiffness};
}

/// The long form's cases: every instructor preset with a tumour at mid-depth, and the
/// default breast with two fixed tumours.
std::vector<std::pair<std::string, palpa::io::CaseFile>> long_form_cases() {
  std::vector<std::pair<std::string, palpa::io::CaseFile>> cases;
  using palpa::author::Preset;
  for (const Preset p : {Preset::Breast, Preset::Prostate, Preset::Patch, Preset::Slab}) {
    const auto params = palpa::author::preset_defaults(p);
    // As the instructor window makes it (tissue in N/m, as a new window starts): the
    // preset's body and its organ's scoring.
    auto file = palpa::author::make_preset_case(params, std::string("preset ") + palpa::author::to_string(p));
    // Off-centre, a third of the way out; the radius a fifth of the thickness (a 4-10 mm
    // nodule), five times the tissue's stiffness (carcinoma-like: docs/case-format.md).
    const double radius = std::clamp(0.2 * params.thickness, 0.003, 0.008);
    const double x = 0.15 * params.width, y = -0.15 * params.length;
    // The prostate's nodule where a rectal exam looks for it: a 6 mm nodule 5 mm under the
    // surface (Gerling 2010 found nodules of 4 mm and more at 5 mm depth in 21 kPa tissue).
    file.tumours.push_back(p == Preset::Prostate ? tumour_below_skin(file, x, y, 0.005 + 0.003, 0.003, 5.0 * params.stiffness)
                                                 : tumour_under(file, x, y, radius, 5.0 * params.stiffness));
    file.document = palpa::io::to_json(file);
    cases.emplace_back(file.title, palpa::io::parse_case(file.document.dump(), file.title));
  }
  auto two = palpa::io::load_case(kCases + "default.json");
  two.tumours.clear();
  two.tumours.push_back(tumour_under(two, 0.025, 0.02, 0.006, 1500.0));
  two.tumours.push_back(tumour_under(two, -0.025, -0.03, 0.006, 1500.0));
  two.document.erase("tumors");
  two.document = palpa::io::to_json(two);
  cases.emplace_back("two tumours", palpa::io::parse_case(two.document.dump(), "two tumours"));
  return cases;
}

}  // namespace

class PalpationAcceptanceTest : public QObject {
  Q_OBJECT

  /// The mouse trainee's whole exam at light, medium and just-deep pressure must pass.
  void exam_passes(const palpa::io::CaseFile& file, const std::string& name) {
    QTemporaryDir dir;
    auto w = open_window(file, name, dir.filePath("exam.palpa"));
    QVERIFY(QTest::qWaitForWindowExposed(w.get()));
    QTest::qWait(200);
    Hand hand(*w);
    const auto score = mouse_exam(*w, hand,
                                  {PressureDial::middle_of(PressureLevel::Light), PressureDial::middle_of(PressureLevel::Medium),
                                   PressureDial::kSettings - 3},
                                  static_cast<int>(file.tumours.size()));
    QString gates;
    for (const auto& g : score.gates) gates += QString::fromStdString((g.passed ? "PASS " : "FAIL ") + g.message) + "; ";
    qInfo("mouse trainee on %s: %s (%s)", name.c_str(), score.passed ? "passed" : "failed", qPrintable(gates));
    QVERIFY2(score.passed, qPrintable(QString::fromStdString(name) + ": " + gates));
  }

  void slides_on(const std::string& case_name) {
    QTemporaryDir dir;
    const auto file = palpa::io::load_case(kCases + case_name);
    auto w = open_window(file, case_name, dir.filePath("slides.palpa"));
    QVERIFY(QTest::qWaitForWindowExposed(w.get()));
    QTest::qWait(200);
    Hand hand(*w);
    const auto& box = w->exercise().scene().body(0).bounds;
    const double cx = 0.5 * (box.lo.x() + box.hi.x()), cy = 0.5 * (box.lo.y() + box.hi.y());
    const double hx = 0.5 * (box.hi.x() - box.lo.x()), hy = 0.5 * (box.hi.y() - box.lo.y());
    double worst_dent = 0.0;
    const auto watch_dent = [&] { worst_dent = std::max(worst_dent, dent_offset(*w)); };
    // Onto the body from beside each edge, at each level, to the middle and off again.
    for (const int level : {PressureDial::middle_of(PressureLevel::Light), PressureDial::middle_of(PressureLevel::Medium),
                            PressureDial::middle_of(PressureLevel::Deep)}) {
      hand.set_level(level);
      hand.slide(cx - hx - 0.015, cy, cx, cy, 0.05, watch_dent);
      hand.slide(cx, cy, cx + hx + 0.015, cy, 0.05);
      hand.slide(cx, cy - hy - 0.015, cx, cy, 0.05);
      hand.slide(cx, cy, cx, cy + hy + 0.015, 0.05);
    }
    // Sweeps at 20, 50 and 150 mm/s at medium, changing the level on the way back.
    hand.set_level(PressureDial::middle_of(PressureLevel::Medium));
    for (const double speed : {0.02, 0.05, 0.15}) hand.slide(cx - 0.5 * hx, cy - 0.2 * hy, cx + 0.5 * hx, cy + 0.2 * hy, speed, watch_dent);
    double next_change = hand.now() + 0.2;
    bool deeper = false;
    hand.slide(cx + 0.5 * hx, cy + 0.2 * hy, cx - 0.5 * hx, cy - 0.2 * hy, 0.05, [&] {
      if (hand.now() < next_change) return;  // a step of the level every 0.2 s while moving
      hand.key(deeper ? Qt::Key_Up : Qt::Key_Down);
      deeper = !deeper;
      next_change += 0.2;
    });
    // A press held at the thin rim, deep.
    hand.set_level(PressureDial::middle_of(PressureLevel::Deep));
    hand.point_at(cx + 0.93 * hx, cy);
    hand.wait(1.0);
    // Jumps between distant points, at medium.
    hand.set_level(PressureDial::middle_of(PressureLevel::Medium));
    for (int k = 0; k < 4; ++k) {
      hand.point_at(cx + (k % 2 == 0 ? -0.6 : 0.6) * hx, cy + (k < 2 ? -0.6 : 0.6) * hy);
      hand.wait(0.6);
    }
    QTest::mouseClick(finish_button(*w), Qt::LeftButton);
    QVERIFY(w->score().has_value());

    const auto session = palpa::session::read_session(w->exercise().session_path());
    const auto f = check_session(session, w->exercise().scene(), hand.steps(), w->exercise().thresholds());
    qInfo("%s: %d samples, %d in contact, %d after a stall of the loop; worst force / fresh press %.3f; over by > 25 %%: "
          "%d; no force on the body: %d; outside the chosen band: %d; dent's deepest point at most %.2f mm from the finger",
          case_name.c_str(), f.samples, f.checked, f.faulted, f.worst_ratio, f.over, f.zero_on_body, f.off_band,
          worst_dent * 1e3);
    QVERIFY2(f.faulted < f.samples / 20, "the loop stalled too often to judge the session");
    for (const auto& p : f.problems) qInfo("  %s", qPrintable(p));
    QVERIFY2(f.checked > 1000, qPrintable(QString::number(f.checked)));
    QVERIFY2(f.over == 0, qPrintable(f.first_problem));
    QVERIFY2(f.zero_on_body == 0, qPrintable(f.first_problem));
    QVERIFY2(f.off_band == 0, qPrintable(f.first_problem));
    QVERIFY2(worst_dent < 0.002, qPrintable(QString("dent %1 mm from the finger").arg(worst_dent * 1e3)));
    // Every level was reached for real (the test's own sanity).
    QVERIFY(session.samples.size() > 10000);
  }

 private slots:
  void keysWorkAsSoonAsTheWindowIsActive() {
    QTemporaryDir dir;
    auto w = open_window(palpa::io::load_case(kCases + "default.json"), "default.json", dir.filePath("keys.palpa"));
    QVERIFY(QTest::qWaitForWindowExposed(w.get()));
    QVERIFY(QTest::qWaitForWindowActive(w.get()));
    const int before = w->pressure().index();
    QTest::keyClick(w.get(), Qt::Key_Up);
    QCOMPARE(w->pressure().index(), before + 1);
    QVERIFY(w->pressure_text().contains("deep") || w->pressure_text().contains("medium"));
    QTest::keyClick(w.get(), Qt::Key_Down);
    QTest::keyClick(w.get(), Qt::Key_Down);
    QCOMPARE(w->pressure().index(), before - 1);
    Hand hand(*w);
    hand.point_at(0.0, 0.0);
    hand.wait(0.4);
    QTest::keyClick(w.get(), Qt::Key_M);
    QCOMPARE(w->exercise().marks().size(), std::size_t{1});
    // Force mode with F: the finger sinks to the chosen force (6 N by default).
    QTest::keyClick(w.get(), Qt::Key_F);
    QVERIFY(w->force_target() > 0.0);
    QVERIFY(QTest::qWaitFor([&] { return std::abs(w->gauge()->contact().force - w->force_target()) < 0.5; }, 5000));
    QTest::keyClick(w.get(), Qt::Key_F);
    QCOMPARE(w->force_target(), 0.0);
  }

  void theGaugeNeverOverlapsDownToTheMinimumSize() {
    QTemporaryDir dir;
    auto w = open_window(palpa::io::load_case(kCases + "default.json"), "default.json", dir.filePath("gauge.palpa"));
    QVERIFY(QTest::qWaitForWindowExposed(w.get()));
    Hand hand(*w);
    hand.set_level(PressureDial::middle_of(PressureLevel::Deep));
    hand.point_at(0.0, 0.0);
    hand.wait(0.5);
    w->resize(w->minimumSizeHint());
    QTest::qWait(100);
    auto* g = w->gauge();
    const auto box = g->layout();
    QVERIFY(!box.force_line.intersects(box.depth_line));
    QVERIFY(!box.bar.intersects(box.force_line));
    QVERIFY(box.depth_line.bottom() <= g->height());
    QVERIFY2(g->lines()[0].contains(" N") && g->lines()[1].contains("mm"), qPrintable(g->text()));
    const QFontMetrics fm(g->font());
    // The lines fit (elided at worst), the band names too: nothing overlaps.
    QVERIFY(fm.height() <= box.force_line.height());
  }

  void closingAsksAndAnAbandonedAttemptIsStoredAsSuch() {
    QTemporaryDir dir;
    const QString path = dir.filePath("close.palpa");
    auto w = open_window(palpa::io::load_case(kCases + "default.json"), "default.json", path);
    QVERIFY(QTest::qWaitForWindowExposed(w.get()));
    QTest::qWait(300);
    const auto answer = [](const QString& button) {
      QTimer::singleShot(200, [button] {
        auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
        if (!box) return;
        for (auto* b : box->buttons()) {
          if (b->text() == button) b->click();
        }
      });
    };
    answer("Go on");
    QVERIFY(!w->close());  // the exercise goes on
    QVERIFY(w->isVisible());
    QVERIFY(!w->exercise().finished());
    answer("Abandon");
    QVERIFY(w->close());
    const auto s = palpa::session::read_session(path.toStdString());
    QVERIFY(s.complete);
    QVERIFY(palpa::session::is_abandoned(s));
    QCOMPARE(palpa::session::session_mode(s.info), std::string("trainee"));
  }

  void slidesOnTheDefaultBreast() { slides_on("default.json"); }
  void slidesOnTheTwoDomes() { slides_on("two-bodies.json"); }

  void aMouseTraineePassesTheDefaultCase() {
    exam_passes(palpa::io::load_case(kCases + "default.json"), "default.json");
  }

  // One row per case, so that one can be run alone:
  //   ui_acceptance_tests aMouseTraineePassesEveryPresetAndTwoTumours:"preset prostate"
  void aMouseTraineePassesEveryPresetAndTwoTumours_data() {
    QTest::addColumn<int>("which");
    if (!long_form()) return;
    const auto cases = long_form_cases();
    for (std::size_t k = 0; k < cases.size(); ++k) QTest::newRow(cases[k].first.c_str()) << static_cast<int>(k);
  }
  void aMouseTraineePassesEveryPresetAndTwoTumours() {
    if (!long_form()) QSKIP("the presets and the two-tumour case run with PALPA_LONG_TESTS=1");
    QFETCH(int, which);
    const auto cases = long_form_cases();
    exam_passes(cases[static_cast<std::size_t>(which)].second, cases[static_cast<std::size_t>(which)].first);
  }

  void aMouseTraineeWithLightPressureOnlyFailsDeepCoverage() {
    QTemporaryDir dir;
    auto w = open_window(palpa::io::load_case(kCases + "default.json"), "default.json", dir.filePath("light.palpa"));
    QVERIFY(QTest::qWaitForWindowExposed(w.get()));
    QTest::qWait(200);
    Hand hand(*w);
    const auto score = mouse_exam(*w, hand, {PressureDial::middle_of(PressureLevel::Light)}, 1);
    QVERIFY(!score.passed);
    bool deep_failed = false;
    for (const auto& g : score.gates) deep_failed = deep_failed || (g.name == "deep_coverage" && !g.passed);
    QVERIFY2(deep_failed, "deep coverage should fail with light pressure only");
  }
};

int main(int argc, char** argv) {
  // The long form's exams run longer than QtTest's 5 minutes per test function.
  if (long_form() && qEnvironmentVariableIsEmpty("QTEST_FUNCTION_TIMEOUT")) qputenv("QTEST_FUNCTION_TIMEOUT", "3600000");
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  PalpationAcceptanceTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "palpation_acceptance_test.moc"
