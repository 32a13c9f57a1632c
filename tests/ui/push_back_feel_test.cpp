// What a mouse user gets instead of force (docs/perception.md), through the window's own
// input events: sliding the pointer at one pressure across the default case's tumour makes
// a bump in the push-back trace and holds the finger back behind the pointer; the same
// stroke over the mirror spot (plain tissue, the breast is symmetric) shows neither; with
// "Finger sticks on firm tissue" off the finger is always under the pointer.
#include <QApplication>
#include <QCheckBox>
#include <QMouseEvent>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QVTKOpenGLNativeWidget.h>
#include <QWindow>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <memory>

#include "palpa/io/case_file.hpp"
#include "palpa/live/live_exercise.hpp"
#include "palpa/ui/push_back_trace.hpp"
#include "palpa/ui/screenshot.hpp"
#include "palpa/ui/trainee_window.hpp"
#include "palpa/ui/vtk_view.hpp"

namespace {

const std::string kDefaultCase = PALPA_SOURCE_DIR "/data/cases/default.json";

std::unique_ptr<palpa::ui::TraineeWindow> open_window(const QString& session) {
  palpa::live::LiveOptions o;
  o.trainee = "ui-test";
  o.seed = 11;
  o.session_path = session.toStdString();
  o.realtime.request_fifo = false;
  auto w = std::make_unique<palpa::ui::TraineeWindow>(
      std::make_unique<palpa::live::LiveExercise>(palpa::io::load_case(kDefaultCase), kDefaultCase, o), "default.json");
  if (!qEnvironmentVariableIsSet("PALPA_FEEL_SCREENSHOT")) w->resize(960, 640);  // else its own default size
  w->show();
  return w;
}

struct Stroke {
  double bump_near = 0.0, bump_far = 0.0;  // the trace's contrast, most, within / beyond 10 mm of (x, y0)
  double lag_near = 0.0, lag_far = 0.0;    // px between pointer and finger, most, the finger within / beyond 10 mm
  QString text_at_bump;                    // the trace's words at the largest bump
};

/// Slides the pointer along plan x = `x` from y0 - 45 mm to y0 + 45 mm at 10 cm/s of the
/// haptic clock, one mouse move per turn of the event loop.
Stroke slide(palpa::ui::TraineeWindow& w, double x, double y0) {
  auto& live = w.exercise();
  const auto skin = [&](double y) {
    const auto hit = live.pick(palpa::Vec3(x, y, 0.5), palpa::Vec3(0, 0, -1));
    return hit ? hit->point : palpa::Vec3(x, y, 0.0);
  };
  QWindow* view = w.view()->input();
  const auto move = [&](const palpa::Vec3& at) {
    const QPoint px = w.to_view(at);
    QMouseEvent e(QEvent::MouseMove, px, view->mapToGlobal(px), Qt::NoButton, Qt::NoButton, Qt::NoModifier);
    QApplication::sendEvent(view, &e);
  };
  move(skin(y0 - 0.045));
  QTest::qWait(800);  // onto the body and down to the pressure
  Stroke out;
  const double t0 = live.snapshot().t;
  for (double y = y0 - 0.045; y < y0 + 0.045; y = y0 - 0.045 + (live.snapshot().t - t0) * 0.1) {
    move(skin(y));
    QTest::qWait(10);
    const auto& s = live.snapshot();
    const double off = std::hypot(s.probe[0] - x, s.probe[1] - y0);
    const double bump = w.push_back_trace()->trace().contrast();
    auto& most = off < 0.010 ? out.bump_near : out.bump_far;
    if (bump > std::max(out.bump_near, out.bump_far)) {
      out.text_at_bump = w.push_back_trace()->text();
      // The documentation's screenshot of the window as a lump passes under the finger.
      const QString png = qEnvironmentVariable("PALPA_FEEL_SCREENSHOT");
      static bool taken = false;
      if (!png.isEmpty() && !taken && bump > 1.17 && w.sticky_finger() && x < 0.0) taken = palpa::ui::save_screenshot(w, png);
    }
    most = std::max(most, bump);
    auto& lag = off < 0.010 ? out.lag_near : out.lag_far;
    lag = std::max(lag, w.finger_lag());
  }
  return out;
}

}  // namespace

class PushBackFeelTest : public QObject {
  Q_OBJECT
 private slots:
  void aLumpIsABumpInTheTraceAndHoldsTheFingerBack() {
    QTemporaryDir dir;
    auto w = open_window(dir.filePath("feel.palpa"));
    QVERIFY(QTest::qWaitForWindowExposed(w.get()));
    QVERIFY(w->sticky_finger());
    const auto& t = w->exercise().placed_case().tumours.at(0);
    const Stroke over = slide(*w, t.center[0], t.center[1]);
    const Stroke mirror = slide(*w, -t.center[0], t.center[1]);
    qInfo("over the tumour at (%.1f, %.1f) mm: bump %+.1f %% (elsewhere on the stroke %+.1f %%), finger held back %.1f px "
          "(elsewhere %.1f px), \"%s\"; the mirror stroke: bump %+.1f %%, lag %.1f px",
          t.center[0] * 1e3, t.center[1] * 1e3, 100 * (over.bump_near - 1), 100 * (over.bump_far - 1), over.lag_near,
          over.lag_far, qPrintable(over.text_at_bump), 100 * (std::max(mirror.bump_near, mirror.bump_far) - 1),
          std::max(mirror.lag_near, mirror.lag_far));
    QVERIFY2(over.bump_near >= 1.15, qPrintable(QString::number(over.bump_near)));
    QVERIFY2(over.text_at_bump.contains("firmer than the stroke so far"), qPrintable(over.text_at_bump));
    QVERIFY2(over.lag_near >= 8.0, qPrintable(QString::number(over.lag_near)));
    QVERIFY2(std::max(mirror.bump_near, mirror.bump_far) < 1.10, "plain tissue shows a bump");
    QVERIFY2(std::max(mirror.lag_near, mirror.lag_far) < 0.5 * over.lag_near, "plain tissue holds the finger back");
    // Not sticking: the finger is under the pointer all along (the trace still shows the bump).
    w->findChild<QCheckBox*>("stickyFinger")->setChecked(false);
    const Stroke plain = slide(*w, t.center[0], t.center[1]);
    QCOMPARE(std::max(plain.lag_near, plain.lag_far), 0.0);
    QVERIFY(plain.bump_near >= 1.15);
  }

  /// The contact ring is drawn on the skin where the finger went in: with the pointer at rest
  /// over the body, around the pointer (the finger has caught up with it), as a grab of the
  /// window shows, whatever the fingertip's depth.
  void theContactRingIsDrawnWhereTheFingerWentIn() {
    QTemporaryDir dir;
    auto w = open_window(dir.filePath("ring.palpa"));
    QVERIFY(QTest::qWaitForWindowExposed(w.get()));
    const auto& t = w->exercise().placed_case().tumours.at(0);
    const auto hit = w->exercise().pick(palpa::Vec3(t.center[0] + 0.02, t.center[1], 0.5), palpa::Vec3(0, 0, -1));
    QVERIFY(hit);
    const QPoint px = w->to_view(hit->point);
    QWindow* view = w->view()->input();
    QMouseEvent e(QEvent::MouseMove, px, view->mapToGlobal(px), Qt::NoButton, Qt::NoButton, Qt::NoModifier);
    QApplication::sendEvent(view, &e);
    // Down to the pressure and the finger caught up (longer under the sanitizers).
    QTRY_VERIFY_WITH_TIMEOUT(w->exercise().contact().body >= 0 && w->finger_lag() < 0.5, 20000);
    QTest::qWait(300);
    const QImage shot = palpa::ui::grab_window(*w).convertToFormat(QImage::Format_RGB32);
    const QPoint centre = w->view()->mapTo(w.get(), px);
    double sx = 0.0, sy = 0.0;
    int n = 0;
    for (int y = centre.y() - 40; y <= centre.y() + 40; ++y)
      for (int x = centre.x() - 40; x <= centre.x() + 40; ++x) {
        if (!shot.rect().contains(x, y)) continue;
        const QColor c = shot.pixelColor(x, y);
        if (c.red() > 230 && c.green() > 190 && c.green() < 240 && c.blue() < 100) sx += x, sy += y, ++n;
      }
    qInfo("contact ring: %d pixels, centred at (%.1f, %.1f) against the pointer at (%d, %d)", n, n ? sx / n : 0.0,
          n ? sy / n : 0.0, centre.x(), centre.y());
    QVERIFY2(n >= 12, "no contact ring drawn near the pointer");
    QVERIFY(std::hypot(sx / n - centre.x(), sy / n - centre.y()) <= 4.0);
  }
};

int run_coverage_overlay_tests(int argc, char** argv);  // coverage_overlay_test.cpp
int run_level_of_detail_tests(int argc, char** argv);   // level_of_detail_test.cpp

int main(int argc, char** argv) {
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  PushBackFeelTest test;
  const int feel = QTest::qExec(&test, argc, argv);
  const int overlay = run_coverage_overlay_tests(argc, argv);
  return feel | overlay | run_level_of_detail_tests(argc, argv);
}

#include "push_back_feel_test.moc"
