// The trainee window under Xvfb: it opens and records; the --screenshot image shows the
// body; a palpation scripted with mouse and wheel events presses the tissue (force and a
// moving surface); a mark over the tumour and Finish give a score card that found it; the
// command line answers --help, --version and a bad case file.
#include <atomic>

#include <QApplication>
#include <QKeyEvent>
#include <QLabel>
#include <QListWidget>
#include <QMouseEvent>
#include <QProcess>
#include <QPushButton>
#include <QSignalSpy>
#include <QSurfaceFormat>
#include <QElapsedTimer>
#include <QTemporaryDir>
#include <QVTKOpenGLNativeWidget.h>
#include <QWindow>
#include <QWheelEvent>
#include <QtTest>
#include <cmath>
#include <fstream>
#include <functional>
#include <QCheckBox>
#include <QDir>
#include <QStandardPaths>
#include <memory>
#include <vtkCamera.h>
#include <vtkPoints.h>
#include <vtkRenderer.h>
#include <vtkPolyData.h>

#include "palpa/io/case_file.hpp"
#include "palpa/live/live_exercise.hpp"
#include "palpa/score/figures.hpp"
#include "palpa/ui/body_view.hpp"
#include "palpa/ui/coverage_overlay.hpp"
#include "palpa/ui/force_gauge.hpp"
#include "palpa/ui/score_card.hpp"
#include "palpa/ui/trainee_window.hpp"
#include "palpa/ui/vtk_view.hpp"
#include "palpa/version.hpp"
#include "fits_screen.hpp"

namespace {

const std::string kDefaultCase = PALPA_SOURCE_DIR "/data/cases/default.json";

std::unique_ptr<palpa::live::LiveExercise> make_exercise(const QString& session,
                                                         const std::string& case_path = kDefaultCase) {
  palpa::live::LiveOptions o;
  o.trainee = "ui-test";
  o.seed = 11;
  o.session_path = session.toStdString();
  o.realtime.request_fifo = false;
  o.device_settling = 0.01;
  return std::make_unique<palpa::live::LiveExercise>(palpa::io::load_case(case_path), case_path, o);
}

/// The default case with `change` applied to its document, saved in `dir`.
std::string changed_default_case(const QTemporaryDir& dir, const std::function<void(nlohmann::json&)>& change) {
  std::ifstream in(kDefaultCase);
  nlohmann::json doc = nlohmann::json::parse(in);
  change(doc);
  const std::string path = dir.filePath("case.json").toStdString();
  std::ofstream(path) << doc.dump();
  return path;
}

/// The rest top contour under (x, y) (m), seen from above.
palpa::Vec3 skin_at(palpa::live::LiveExercise& live, double x, double y) {
  const auto hit = live.pick(palpa::Vec3(x, y, 0.5), palpa::Vec3(0, 0, -1));
  return hit ? hit->point : palpa::Vec3(x, y, 0.0);
}

/// Pixels near `at` (within `r`) of a colour close to `rgb`.
int pixels_like(const QImage& image, const QPoint& at, int r, const std::array<int, 3>& rgb, int tolerance = 40) {
  int n = 0;
  for (int y = at.y() - r; y <= at.y() + r; ++y) {
    for (int x = at.x() - r; x <= at.x() + r; ++x) {
      if (!image.rect().contains(x, y)) continue;
      const QColor c = image.pixelColor(x, y);
      if (std::abs(c.red() - rgb[0]) + std::abs(c.green() - rgb[1]) + std::abs(c.blue() - rgb[2]) < tolerance) ++n;
    }
  }
  return n;
}

QPushButton* button_named(QWidget& window, const QString& start) {
  for (auto* b : window.findChildren<QPushButton*>())
    if (b->text().startsWith(start)) return b;
  return nullptr;
}

/// Lets the event loop (and the haptic thread) run until `done` or a generous deadline.
bool wait_for(const std::function<bool()>& done, int ms = 5000) {
  QElapsedTimer clock;
  clock.start();
  while (clock.elapsed() < ms) {
    QTest::qWait(10);
    if (done()) return true;
  }
  return false;
}

/// Screen position over the placed tumour: its centre seen straight from above, on the rest top contour.
palpa::Vec3 top_over_tumour(palpa::live::LiveExercise& live) {
  const auto& t = live.placed_case().tumours.at(0);
  const palpa::Vec3 c(t.center[0], t.center[1], t.center[2]);
  const auto hit = live.pick(c + palpa::Vec3(0, 0, 0.5), palpa::Vec3(0, 0, -1));
  return hit ? hit->point : c;
}

void move_pointer(QWindow* view, const QPoint& at) {
  QMouseEvent move(QEvent::MouseMove, at, view->mapToGlobal(at), Qt::NoButton, Qt::NoButton, Qt::NoModifier);
  QApplication::sendEvent(view, &move);
}

void wheel(QWindow* view, const QPoint& at, int notches) {
  QWheelEvent e(QPointF(at), QPointF(view->mapToGlobal(at)), QPoint(), QPoint(0, 120 * notches), Qt::NoButton,
                Qt::NoModifier, Qt::NoScrollPhase, false);
  QApplication::sendEvent(view, &e);
}

/// A probe that rests above the body for a moment and is then unplugged: read() turns
/// Disconnected after `reads_before_unplug` ticks, as a driver reports a pulled cable.
class UnpluggedProbe final : public palpa::engine::Device {
 public:
  explicit UnpluggedProbe(int reads_before_unplug) : left_(reads_before_unplug) {
    caps_.name = "Test probe";
    caps_.max_force = 10.0;
    caps_.force_output = true;
  }
  const palpa::engine::DeviceCapabilities& capabilities() const override { return caps_; }
  palpa::engine::DeviceStatus read(double, palpa::engine::DevicePose& pose) noexcept override {
    pose.position = palpa::Vec3(0.0, 0.0, 0.2);
    return --left_ > 0 ? palpa::engine::DeviceStatus::Ok : palpa::engine::DeviceStatus::Disconnected;
  }
  palpa::engine::DeviceStatus write_force(const palpa::Vec3&) noexcept override {
    return left_ > 0 ? palpa::engine::DeviceStatus::Ok : palpa::engine::DeviceStatus::Disconnected;
  }
  std::string fault_message() const override { return "cable pulled"; }

 private:
  palpa::engine::DeviceCapabilities caps_;
  std::atomic<int> left_;
};

/// Counts pixels of the skin colour the bodies are drawn in (reddish, lit or shaded): the
/// background is blue-grey and the side panel grey, so neither counts.
int skin_pixels(const QImage& image) {
  int count = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const QColor c = image.pixelColor(x, y);
      if (c.red() > 90 && c.red() - c.blue() > 35 && c.green() > c.blue()) ++count;
    }
  }
  return count;
}

struct Run {
  int code = -1;
  QString out, err;
};

Run run_palpa(const QStringList& arguments) {
  QProcess p;
  p.start(PALPA_GUI_EXE, arguments);
  p.waitForFinished(60000);
  return {p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1, QString::fromUtf8(p.readAllStandardOutput()),
          QString::fromUtf8(p.readAllStandardError())};
}

}  // namespace

class TraineeWindowTest : public QObject {
  Q_OBJECT
 private slots:
  void opensAndRecordsASession() {
    QTemporaryDir dir;
    const QString session = dir.filePath("open.palpa");
    palpa::ui::TraineeWindow window(make_exercise(session), "default.json");
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QVERIFY(window.windowTitle().contains("trainee"));
    QVERIFY(window.exercise().started());
    QVERIFY(QFile::exists(session));
    // The status bar reports the haptic loop once it has published statistics.
    QVERIFY(wait_for([&] { return window.exercise().loop_stats().ticks() >= 100; }));
    QVERIFY(wait_for([&] { return window.frame_rate() > 0.0; }, 3000));
    qInfo("frame rate under this display: %.1f fps (timer at 60 Hz)", window.frame_rate());  // for the record, not a test
  }

  // A view nothing changes in is redrawn only a few times a second (a software renderer
  // would otherwise spend a core on identical frames); the finger moving over the body
  // brings the frames back.
  void anUnchangedViewIsNotRedrawnEveryFrame() {
    QTemporaryDir dir;
    palpa::ui::TraineeWindow window(make_exercise(dir.filePath("idle.palpa")), "default.json");
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QTest::qWait(2300);  // two whole seconds of frame counting with no input
    const double idle_rate = window.frame_rate();
    QVERIFY2(idle_rate <= 6.0, qPrintable(QString::number(idle_rate)));
    // The status bar says so instead of a meaningless "4 fps".
    QVERIFY(window.idle());
    bool says_idle = false;
    for (auto* l : window.findChildren<QLabel*>()) says_idle = says_idle || l->text() == "idle";
    QVERIFY(says_idle);
    auto* view = window.view();
    const QPoint centre = window.to_view(top_over_tumour(window.exercise()));
    QElapsedTimer clock;
    clock.start();
    for (int k = 0; clock.elapsed() < 2300; ++k) {
      move_pointer(view->input(), centre + QPoint((k % 40) - 20, ((k / 40) % 2) * 10));
      QTest::qWait(15);
    }
    qInfo("frames drawn: moving %.1f per second", window.frame_rate());
    QVERIFY(!window.idle());
    // Well above the idle rate (llvmpipe under the sanitizers, beside another test, draws
    // the body and its coverage overlay at 7-15 frames a second; a release build at 30+).
    QVERIFY2(window.frame_rate() >= std::max(6.5, idle_rate + 2.0), qPrintable(QString::number(window.frame_rate())));
  }

  void mousePalpationPressesTheTissue() {
    QTemporaryDir dir;
    palpa::ui::TraineeWindow window(make_exercise(dir.filePath("press.palpa")), "default.json");
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QTest::qWait(100);
    auto* view = window.view();
    vtkPoints* points = window.surfaces().tops()->GetPoints();  // one body: all its points
    std::vector<double> rest_z(static_cast<std::size_t>(points->GetNumberOfPoints()));
    for (vtkIdType k = 0; k < points->GetNumberOfPoints(); ++k) rest_z[static_cast<std::size_t>(k)] = points->GetPoint(k)[2];

    const QPoint at = window.to_view(top_over_tumour(window.exercise()));
    QVERIFY(view->rect().contains(at));
    move_pointer(view->input(), at);
    QCOMPARE(window.pressure().level(), palpa::live::PressureLevel::Medium);  // medium 2 of 3 to start
    wheel(view->input(), at, 2);  // two notches deeper: deep 1 of 3
    QCOMPARE(window.pressure().level(), palpa::live::PressureLevel::Deep);
    QCOMPARE(window.pressure().step_in_level(), 1);
    QVERIFY2(window.pressure_text().contains("deep, step 1 of 3"), qPrintable(window.pressure_text()));
    QVERIFY2(wait_for([&] { return window.gauge()->contact().force > 1.0; }),
             qPrintable(window.gauge()->text()));
    QVERIFY(window.gauge()->contact().level != palpa::live::PressureLevel::None);
    QVERIFY(window.exercise().meshes().version(0) > 0);
    // The drawn surface (the VTK points themselves) sank under the finger by at least 2 mm.
    QVERIFY(wait_for([&] {
      vtkPoints* now = window.surfaces().tops()->GetPoints();
      double sink = 0.0;
      for (vtkIdType k = 0; k < now->GetNumberOfPoints() && static_cast<std::size_t>(k) < rest_z.size(); ++k)
        sink = std::max(sink, rest_z[static_cast<std::size_t>(k)] - now->GetPoint(k)[2]);
      return sink > 0.002;
    }));
  }

  void markOverTheTumourAndFinishGiveAScoreCardThatFoundIt() {
    QTemporaryDir dir;
    palpa::ui::TraineeWindow window(make_exercise(dir.filePath("mark.palpa")), "default.json");
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QTest::qWait(100);
    auto* view = window.view();
    const QPoint at = window.to_view(top_over_tumour(window.exercise()));
    move_pointer(view->input(), at);
    QVERIFY(wait_for([&] { return window.gauge()->contact().force > 1.0; }));
    QTest::keyClick(view->input(), Qt::Key_M);
    auto* marks = window.findChild<QListWidget*>();
    QVERIFY(marks);
    QCOMPARE(marks->count(), 1);
    QCOMPARE(window.exercise().marks().size(), std::size_t{1});

    QPushButton* finish = nullptr;
    for (auto* b : window.findChildren<QPushButton*>()) {
      if (b->text().startsWith("Finish")) finish = b;
    }
    QVERIFY(finish);
    QTest::mouseClick(finish, Qt::LeftButton);
    QVERIFY(window.score().has_value());
    QCOMPARE(window.score()->sensitivity, 1.0);
    QCOMPARE(window.score()->false_positives, 0);
    QVERIFY(window.score_card());
    QVERIFY2(window.score_card()->headline().contains("1 of 1 tumours found"),
             qPrintable(window.score_card()->headline()));
    QVERIFY(window.score_card()->text().contains("sensitivity"));
    QVERIFY(!finish->isEnabled());
  }

  // At 1280 x 800 a window's frame has about 1280 x 730 under a title bar and the desktop
  // panel. The trainee window (1200 x 760 before) and the score card (968 px tall before,
  // its Close off the screen) fit it; the card's Close is clicked and closes it.
  void windowAndScoreCardFitA1280x800Screen() {
    QTemporaryDir dir;
    palpa::ui::TraineeWindow window(make_exercise(dir.filePath("fit.palpa")), "default.json");
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    palpa::ui::testing::check_fits_screen(window, {button_named(window, "Mark here"), button_named(window, "Finish")});
    QTest::mouseClick(button_named(window, "Finish"), Qt::LeftButton);
    auto* card = window.score_card();
    QVERIFY(card);
    QVERIFY(QTest::qWaitForWindowExposed(card));
    palpa::ui::testing::check_fits_screen(*card, {card->close_button()});
    QVERIFY(card->findChild<QLabel*>("mapView")->text().contains("seen from the free side, along the support's normal"));
    QTest::mouseClick(card->close_button(), Qt::LeftButton);
    QTRY_VERIFY(!card->isVisible());
  }

  // Pressing deep on a case whose safety limit is low holds the press at the bound: the
  // gauge's words for it ("held at 3 N: the safety limit is 3 N", cut off after "the safety
  // lim" before) wrap onto a second row; no text of the side panel or the status bar is cut.
  void noMessageIsCutOffAtTheDefaultSize() {
    QTemporaryDir dir;
    const auto path = changed_default_case(dir, [](nlohmann::json& d) { d["scoring"]["max_force"] = 3.0; });
    palpa::ui::TraineeWindow window(make_exercise(dir.filePath("bound.palpa"), path), "bound.json");
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    auto* view = window.view();
    const QPoint at = window.to_view(top_over_tumour(window.exercise()));
    move_pointer(view->input(), at);
    wheel(view->input(), at, 3);  // deep
    auto* g = window.gauge();
    QVERIFY2(wait_for([&] { return g->alert() == palpa::ui::ForceGauge::Alert::Bound; }), qPrintable(g->text()));
    QTest::qWait(50);
    const QString words = g->lines()[0];
    QVERIFY2(words.contains("the safety limit is 3 N"), qPrintable(words));
    const auto box = g->layout();
    QFont bold = g->font();
    bold.setBold(true);
    const QFontMetrics fm(bold);
    qInfo("gauge %d px wide; \"%s\" is %d px", g->width(), qPrintable(words), fm.horizontalAdvance(words));
    const QRect wrapped = fm.boundingRect(box.force_line.toRect(), Qt::TextWordWrap, words);
    QVERIFY2(wrapped.height() <= box.force_line.height() + 0.5 && wrapped.width() <= box.force_line.width() + 0.5,
             qPrintable(QString("%1 x %2 in %3 x %4").arg(wrapped.width()).arg(wrapped.height())
                            .arg(box.force_line.width()).arg(box.force_line.height())));
    QVERIFY(!box.force_line.intersects(box.depth_line));
    QVERIFY(box.depth_line.bottom() <= g->height());
    for (auto* w : window.findChildren<QWidget*>()) {
      if (!w->isVisible() || w == g || w->window() != &window) continue;
      auto* label = qobject_cast<QLabel*>(w);
      const bool text = label || qobject_cast<QAbstractButton*>(w);
      if (!text || (label && label->text().isEmpty())) continue;
      const bool fits = label && label->wordWrap() ? label->heightForWidth(label->width()) <= label->height()
                                                   : w->sizeHint().width() <= w->width();
      QVERIFY2(fits, qPrintable(QString("%1 \"%2\": %3 x %4 for a hint of %5 x %6")
                                    .arg(w->metaObject()->className(), label ? label->text() : qobject_cast<QAbstractButton*>(w)->text())
                                    .arg(w->width()).arg(w->height()).arg(w->sizeHint().width()).arg(w->sizeHint().height())));
    }
  }

  // A body whose support faces +y (the imported breast) is seen from its free side: the
  // default view looks down its press axis, as it looks down +z on the bundled breast.
  void theDefaultViewLooksDownThePressAxis() {
    for (const char* name : {"victre-breast.json", "default.json"}) {
      QTemporaryDir dir;
      const std::string path = std::string(PALPA_SOURCE_DIR "/data/cases/") + name;
      palpa::ui::TraineeWindow window(make_exercise(dir.filePath("v.palpa"), path), name, false);
      const palpa::Vec3 up = window.exercise().scene().body(0).press_axis.up;
      double d[3];
      window.renderer()->GetActiveCamera()->GetDirectionOfProjection(d);
      const double along = palpa::Vec3(d[0], d[1], d[2]).dot(up);
      qInfo("%s: press axis (%.2f, %.2f, %.2f), view direction . axis = %.3f", name, up.x(), up.y(), up.z(), along);
      QVERIFY2(along < -0.95, qPrintable(QString::number(along)));
    }
  }

  // From the default view the pointer reaches the whole exam region of every bundled case
  // (from the front, the crest of the default breast hid its far slope).
  void defaultViewShowsTheWholeExamRegionOfEveryCase() {
    const QDir cases(PALPA_SOURCE_DIR "/data/cases");
    int tried = 0;
    for (const QString& name : cases.entryList({"*.json"}, QDir::Files)) {
      const std::string path = cases.filePath(name).toStdString();
      QTemporaryDir dir;
      palpa::ui::TraineeWindow window(make_exercise(dir.filePath("v.palpa"), path), name, false);
      window.show();
      QVERIFY(QTest::qWaitForWindowExposed(&window));
      window.frame();
      const double share = window.exam_region_view_share();
      qInfo("%s: %.2f %% of the exam region visible and pickable from the default view", qPrintable(name),
            100.0 * share);
      QVERIFY2(share >= 0.99, qPrintable(name + ": " + QString::number(100.0 * share, 'f', 2) + " %"));
      ++tried;
    }
    QVERIFY(tried >= 5);
  }

  // The measure can fail: from the front and above (the earlier default view, 56 degrees
  // up), the crest of the default breast hides its far slope.
  void theViewShareDropsWhenTheCrestHidesTheFarSlope() {
    QTemporaryDir dir;
    palpa::ui::TraineeWindow window(make_exercise(dir.filePath("v.palpa")), "default.json", false);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    palpa::ui::frame_from_front(*window.renderer(), palpa::ui::scene_bounds(window.exercise().scene()), 1.5);
    window.frame();
    const double share = window.exam_region_view_share();
    qInfo("from the front (the earlier default view): %.1f %%", 100.0 * share);
    QVERIFY2(share < 0.97, qPrintable(QString::number(share)));  // 94.5 % on a 2-core Debian 12 VM
  }

  // The overlay shows what was touched, live; its figure is the score's coverage.
  void coverageOverlayMarksTheSweptRegionAndAgreesWithTheScore() {
    QTemporaryDir dir;
    palpa::ui::TraineeWindow window(make_exercise(dir.filePath("sweep.palpa")), "default.json");
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QVERIFY(window.coverage_overlay_shown());
    auto* view = window.view();
    auto& live = window.exercise();
    const palpa::Vec3 swept = skin_at(live, 0.0, 0.0), untouched = skin_at(live, -0.045, 0.045);
    const std::array<int, 3> orange = {240, 140, 30};
    const auto colour = [](const std::array<std::uint8_t, 3>& c) { return std::array<int, 3>{c[0], c[1], c[2]}; };
    QTest::qWait(300);
    QVERIFY(pixels_like(view->frame(), window.to_view(swept), 6, orange) > 0);
    // Strips 10 mm apart over x, y in [-20, 20] mm, sliding at about 40 mm/s.
    for (int strip = 0; strip <= 4; ++strip) {
      const double x = -0.02 + 0.01 * strip;
      for (int k = 0; k <= 40; ++k) {
        const double y = (strip % 2 == 0 ? -0.02 : 0.02) + (strip % 2 == 0 ? 1 : -1) * 0.001 * k;
        move_pointer(view->input(), window.to_view(skin_at(live, x, y)));
        QTest::qWait(25);
      }
    }
    QTest::qWait(300);
    const QImage after = view->frame();
    QCOMPARE(pixels_like(after, window.to_view(swept), 6, orange), 0);
    QVERIFY(pixels_like(after, window.to_view(swept), 6, colour(palpa::ui::CoverageOverlay::kColours[2])) +
                pixels_like(after, window.to_view(swept), 6, colour(palpa::ui::CoverageOverlay::kColours[3])) > 0);
    QVERIFY(pixels_like(after, window.to_view(untouched), 6, orange) > 0);
    const double live_share = window.live_coverage().coverage();
    QVERIFY(live_share > 0.05);
    auto* figure = window.findChild<QLabel*>("liveCoverage");
    QVERIFY(figure && figure->isVisible());
    QVERIFY2(figure->text().contains(QString::fromStdString(palpa::score::percent_text(live_share))),
             qPrintable(figure->text()));
    QTest::mouseClick(button_named(window, "Finish"), Qt::LeftButton);
    QVERIFY(window.score().has_value());
    qInfo("live coverage %.2f %%, score %.2f %%", 100.0 * live_share, 100.0 * window.score()->coverage);
    QVERIFY(std::abs(live_share - window.score()->coverage) <= 0.02);
  }

  // A case for an exam turns the overlay off; the key cannot turn it on.
  void aCaseCanTurnTheOverlayOff() {
    QTemporaryDir dir;
    const auto path = changed_default_case(dir, [](nlohmann::json& d) { d["training"] = {{"coverage_overlay", false}}; });
    palpa::ui::TraineeWindow window(make_exercise(dir.filePath("exam.palpa"), path), "exam.json");
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QVERIFY(!window.coverage_overlay_shown());
    QTest::keyClick(window.view()->input(), Qt::Key_C);
    QVERIFY(!window.coverage_overlay_shown());
    QVERIFY(!window.findChild<QLabel*>("liveCoverage")->isVisible());
    QVERIFY(!window.findChild<QCheckBox*>("coverageOverlay")->isVisible());
    // Allowed (the default case): C turns it off and on.
    palpa::ui::TraineeWindow training(make_exercise(dir.filePath("train.palpa")), "default.json");
    training.show();
    QVERIFY(QTest::qWaitForWindowExposed(&training));
    QVERIFY(training.coverage_overlay_shown());
    QTest::keyClick(training.view()->input(), Qt::Key_C);
    QVERIFY(!training.coverage_overlay_shown());
    QTest::keyClick(training.view()->input(), Qt::Key_C);
    QVERIFY(training.coverage_overlay_shown());
  }

  // After Finish: a hit mark green, a false one red; Mark here off, the gauge cleared; the
  // keys work again once the score card closes.
  void afterFinishTheMarksTellHitFromMissAndTheControlsStop() {
    QTemporaryDir dir;
    palpa::ui::TraineeWindow window(make_exercise(dir.filePath("marks.palpa")), "default.json");
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    auto* view = window.view();
    auto& live = window.exercise();
    const palpa::Vec3 hit = top_over_tumour(live), miss = skin_at(live, -0.04, -0.03);
    for (const auto& p : {hit, miss}) {
      move_pointer(view->input(), window.to_view(p));
      QVERIFY(wait_for([&] { return window.gauge()->contact().force > 1.0; }));
      QTest::qWait(200);
      QTest::keyClick(view->input(), Qt::Key_M);
    }
    QCOMPARE(live.marks().size(), std::size_t{2});
    QTest::mouseClick(button_named(window, "Finish"), Qt::LeftButton);
    QVERIFY(window.score().has_value());
    QCOMPARE(window.score()->false_positives, 1);
    QVERIFY(!button_named(window, "Mark here")->isEnabled());
    QCOMPARE(window.gauge()->contact().force, 0.0);
    window.frame();
    QTest::qWait(100);
    const QImage image = view->frame();
    const std::array<int, 3> red = {230, 38, 38}, green = {51, 204, 77};
    const QPoint at_hit = window.to_view(window.score()->marks[0].tumour >= 0 ? hit : miss);
    const QPoint at_miss = window.to_view(window.score()->marks[0].tumour >= 0 ? miss : hit);
    QVERIFY2(pixels_like(image, at_hit, 4, green, 90) > pixels_like(image, at_hit, 4, red, 90), "hit mark not green");
    QVERIFY2(pixels_like(image, at_miss, 4, red, 90) > pixels_like(image, at_miss, 4, green, 90), "false mark not red");
    window.score_card()->close();
    QTRY_VERIFY(window.isActiveWindow());
    QVERIFY(window.centralWidget()->hasFocus() || window.focusWidget() != nullptr);
  }

  // The task counts the tumours.
  void theTaskSaysHowManyTumours() {
    QTemporaryDir dir;
    const auto path = changed_default_case(dir, [](nlohmann::json& d) {
      nlohmann::json second = d["tumors"][0];
      second["center"] = {-0.02, -0.02, 0.02};
      second.erase("placement");
      d["tumors"].push_back(second);
    });
    palpa::ui::TraineeWindow two(make_exercise(dir.filePath("two.palpa"), path), "two.json", false);
    bool says = false;
    for (auto* l : two.findChildren<QLabel*>()) says = says || l->text().contains("Find the 2 tumours.");
    QVERIFY(says);
    palpa::ui::TraineeWindow one(make_exercise(dir.filePath("one.palpa")), "default.json", false);
    says = false;
    for (auto* l : one.findChildren<QLabel*>()) says = says || l->text().contains("Find the tumour.");
    QVERIFY(says);
  }

  // Ctrl+W closes the window and Ctrl+Q all of them from the view's keys, with or without a
  // window manager.
  void ctrlWClosesTheWindow() {
    QTemporaryDir dir;
    palpa::ui::TraineeWindow window(make_exercise(dir.filePath("w.palpa")), "default.json", false);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QTest::keyClick(window.view()->input(), Qt::Key_W, Qt::ControlModifier);
    QTRY_VERIFY(!window.isVisible());
    // Ctrl+Q closes every window.
    palpa::ui::TraineeWindow first(make_exercise(dir.filePath("q1.palpa")), "default.json", false);
    palpa::ui::TraineeWindow second(make_exercise(dir.filePath("q2.palpa")), "default.json", false);
    first.show();
    second.show();
    QVERIFY(QTest::qWaitForWindowExposed(&second));
    QTest::keyClick(second.view()->input(), Qt::Key_Q, Qt::ControlModifier);
    QTRY_VERIFY(!first.isVisible() && !second.isVisible());
  }

  void bodiesOutOfViewAreCulled() {
    // Two bodies side by side (x < -0.02 m and x > 0.02 m): with the camera close on the
    // left one, the right one is neither re-tessellated nor drawn; back in view, it is again.
    QTemporaryDir dir;
    palpa::live::LiveOptions o;
    o.trainee = "ui-test";
    o.session_path = dir.filePath("cull.palpa").toStdString();
    o.realtime.request_fifo = false;
    const std::string two = PALPA_SOURCE_DIR "/data/cases/two-bodies.json";
    palpa::ui::TraineeWindow window(
        std::make_unique<palpa::live::LiveExercise>(palpa::io::load_case(two), two, o), "two-bodies.json");
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.frame();
    QCOMPARE(window.last_frame().bodies_drawn, std::size_t{2});
    window.look_at_body(0);
    window.renderer()->GetActiveCamera()->Zoom(2.0);
    window.frame();
    QCOMPARE(window.last_frame().bodies_drawn, std::size_t{1});
    QVERIFY(window.exercise().meshes().visible(0));
    QVERIFY(!window.exercise().meshes().visible(1));
    window.look_at_body(1);
    window.renderer()->GetActiveCamera()->Zoom(2.0);
    window.frame();
    QCOMPARE(window.last_frame().bodies_drawn, std::size_t{1});
    QVERIFY(window.exercise().meshes().visible(1));
    QVERIFY(!window.exercise().meshes().visible(0));
  }

  void unpluggedDeviceFallsBackToTheMouseAndSaysSo() {
    QTemporaryDir dir;
    palpa::live::LiveOptions o;
    o.trainee = "ui-test";
    o.seed = 11;
    o.session_path = dir.filePath("unplug.palpa").toStdString();
    o.realtime.request_fifo = false;
    o.device = std::make_shared<UnpluggedProbe>(300);  // unplugged after ~0.3 s
    palpa::ui::TraineeWindow window(
        std::make_unique<palpa::live::LiveExercise>(palpa::io::load_case(kDefaultCase), kDefaultCase, o),
        "default.json");
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QVERIFY(window.device_banner()->isHidden());
    QVERIFY(wait_for([&] { return window.device_banner()->isVisible(); }));
    QVERIFY2(window.device_banner()->text().contains("Test probe"), qPrintable(window.device_banner()->text()));
    // The force ramps to zero first, then the mouse's virtual device takes over.
    QVERIFY(wait_for([&] { return window.exercise().device_name() != "Test probe"; }));
    // The exercise goes on with the mouse: a press over the tumour is felt.
    const QPoint at = window.to_view(top_over_tumour(window.exercise()));
    move_pointer(window.view()->input(), at);
    QVERIFY(wait_for([&] { return window.gauge()->contact().force > 1.0; }));
  }

  void screenshotShowsTheBody() {
    QTemporaryDir dir;
    const QString png = dir.filePath("trainee.png");
    const Run r = run_palpa({"--case", QString::fromStdString(kDefaultCase), "--seed", "3", "--screenshot", png});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QImage image(png);
    QVERIFY(!image.isNull());
    QCOMPARE(image.size(), QSize(1200, 696));  // fits a 1280 x 800 screen with a title bar and a panel
    // The body covers a good part of the view (about a fifth of the window at the default
    // camera); an empty view has none of its colour.
    const int skin = skin_pixels(image);
    QVERIFY2(skin > image.width() * image.height() / 10, qPrintable(QString::number(skin)));
    QVERIFY(!QFile::exists(dir.filePath("trainee.palpa")));
  }

  // On a smaller screen (1024 x 600) each window opens within the screen's available
  // geometry less a title bar: the trainee, instructor and review windows drawn by
  // palpa --screenshot on such a display.
  void onASmallScreenEveryWindowFitsIt() {
    const QString xvfb = QStandardPaths::findExecutable("xvfb-run");
    if (xvfb.isEmpty()) QSKIP("xvfb-run is not installed");
    QTemporaryDir dir;
    const QStringList modes[] = {{"--case", QString::fromStdString(kDefaultCase)},
                                 {"--mode", "instructor"},
                                 {"--mode", "review", "--session", PALPA_SOURCE_DIR "/data/sessions/expert.palpa"}};
    for (const auto& mode : modes) {
      const QString png = dir.filePath("small.png");
      QFile::remove(png);
      QProcess p;
      p.start(xvfb, QStringList{"-a", "-s", "-screen 0 1024x600x24", PALPA_GUI_EXE} + mode + QStringList{"--screenshot", png});
      QVERIFY(p.waitForFinished(120000));
      QVERIFY2(p.exitCode() == 0, qPrintable(QString::fromUtf8(p.readAllStandardError())));
      const QSize size = QImage(png).size();
      qInfo("%s on 1024 x 600: %d x %d", qPrintable(mode.join(' ')), size.width(), size.height());
      QVERIFY2(size.width() <= 1016 && size.height() <= 566 && !size.isEmpty(), qPrintable(mode.join(' ')));
    }
  }

  // The gauge on its own, fed contacts: words and colours for the bound, a stall and a
  // fault; the stiffness in force mode with the band by the score's own edges; no share of
  // a rim; the needle in its own strip, clear of the band names.
  void gaugeSaysBoundStallFaultStiffnessAndRim() {
    palpa::ui::ForceGauge g(0.2, 0.5);
    g.resize(300, g.minimumSizeHint().height());
    palpa::live::ContactInfo c;
    c.body = 0;
    c.force = 6.0;
    c.depth = 0.02498;
    c.thickness = 0.05;
    c.fraction = 0.4996;  // the score calls this medium: never printed as "50 %"
    c.level = palpa::live::PressureLevel::Medium;
    c.force_bound = 18.0;
    c.safety_limit = 20.0;
    g.set_contact(c);
    QCOMPARE(g.lines()[0], QString("6.0 N  medium"));
    QVERIFY2(g.lines()[1].contains("(49 % of 50 mm)"), qPrintable(g.text()));
    c.fraction = 0.5;
    c.depth = 0.025;
    c.level = palpa::live::PressureLevel::Deep;
    c.force_mode = true;
    c.stiffness = 240.0;  // N/m: 6 N over 25 mm, a body given in N/m
    g.set_contact(c);
    QCOMPARE(g.lines()[0], QString("6.0 N  stiffness 0.24 N/mm"));
    c.firmness = 28460.0;  // Pa: a body given by its modulus reads in kPa
    g.set_contact(c);
    QCOMPARE(g.lines()[0], QString("6.0 N  firmness 28.5 kPa"));
    c.thickness = 0.012;  // thinner than the finger pad is wide: the skin over the chest wall
    g.set_contact(c);
    QCOMPARE(g.lines()[0], QString("6.0 N  firmness 28.5 kPa (thin tissue)"));
    c.thickness = 0.05;
    g.set_contact(c);
    QCOMPARE(g.lines()[1], QString("deep: depth 25.0 mm (50 % of 50 mm)"));
    QCOMPARE(g.alert(), palpa::ui::ForceGauge::Alert::None);
    c.force = 18.0;
    c.at_force_bound = true;
    g.set_contact(c);
    QVERIFY2(g.lines()[0].contains("held at 18 N: the safety limit is 20 N"), qPrintable(g.text()));
    QCOMPARE(g.alert(), palpa::ui::ForceGauge::Alert::Bound);
    c.at_force_bound = false;
    c.frame_gap = 0.25;  // a busy computer: the window's frames come late
    g.set_contact(c);
    QVERIFY2(g.lines()[0].contains("computer busy: the window is 250 ms late"), qPrintable(g.text()));
    QCOMPARE(g.alert(), palpa::ui::ForceGauge::Alert::Late);
    c.at_force_bound = true;
    c.loop = palpa::live::LoopState::Stalled;
    g.set_contact(c);
    QVERIFY2(g.lines()[0].contains("haptic loop stalled"), qPrintable(g.text()));
    palpa::live::ContactInfo off;  // a fault: the engine sees no contact and 0 N
    off.loop = palpa::live::LoopState::Fault;
    g.set_contact(off);
    QVERIFY2(g.lines()[0].contains("device fault") && !g.lines()[0].contains("no contact"), qPrintable(g.text()));
    QVERIFY(palpa::ui::ForceGauge::alert_colour(g.alert()) != QColor(Qt::black));
    c = palpa::live::ContactInfo{};
    c.body = 0;
    c.force = 0.4;
    c.depth = 3e-4;
    c.thickness = 4e-4;
    c.fraction = 0.75;
    c.level = palpa::live::PressureLevel::Deep;
    g.set_contact(c);
    QVERIFY2(g.lines()[1].contains("at the rim") && !g.lines()[1].contains("%"), qPrintable(g.text()));
    const auto box = g.layout();
    QVERIFY(!box.marker.intersects(box.bar));
    QVERIFY(!box.marker.intersects(box.force_line));
    QVERIFY(box.depth_line.bottom() <= g.height());
  }

  void commandLineHelpVersionAndBadCase() {
    const Run help = run_palpa({"--help"});
    QCOMPARE(help.code, 0);
    QVERIFY(help.out.contains("--screenshot"));
    QVERIFY(help.out.contains("--case"));
    const Run version = run_palpa({"--version"});
    QCOMPARE(version.code, 0);
    QCOMPARE(version.out.trimmed(), QString("palpa ") + palpa::kVersion);

    QTemporaryDir dir;
    const QString bad = dir.filePath("bad.json");
    {
      QFile f(bad);
      QVERIFY(f.open(QIODevice::WriteOnly));
      f.write("{\"format\": \"palpa-case\",\n  \"bodies\": [\n");
    }
    const Run r = run_palpa({"--case", bad});
    QCOMPARE(r.code, 2);
    const QStringList lines = r.err.trimmed().split('\n');
    QCOMPARE(lines.size(), 1);
    QVERIFY2(lines[0].startsWith(bad + ": line "), qPrintable(lines[0]));
    // A session file's problem reads the same way: the file first.
    const QString existing = dir.filePath("taken.palpa");
    {
      QFile f(existing);
      QVERIFY(f.open(QIODevice::WriteOnly));
    }
    const Run taken = run_palpa({"--session", existing});
    QCOMPARE(taken.code, 2);
    QCOMPARE(taken.err.trimmed(), existing + ": file: exists (a session is never overwritten)");
    const Run mode = run_palpa({"--mode", "nonsense"});
    QCOMPARE(mode.code, 2);
    // Numbers: NaN, infinities and seeds beyond 2^64 - 1 are refused in one line naming the option.
    const std::pair<QStringList, QString> numbers[] = {
        {{"--bench", "--seconds", "nan"}, "--seconds"},  {{"--bench", "--seconds", "inf"}, "--seconds"},
        {{"--bench", "--max-bodies", "0"}, "--max-bodies"}, {{"--seed", "18446744073709551616"}, "--seed"},
        {{"--seed", "-3"}, "--seed"},
    };
    for (const auto& [arguments, option] : numbers) {
      const Run n = run_palpa(arguments);
      QCOMPARE(n.code, 2);
      const QStringList said = n.err.trimmed().split('\n');
      QCOMPARE(said.size(), 1);
      QVERIFY2(said[0].startsWith("palpa: error: " + option), qPrintable(said[0]));
    }
  }
};

int main(int argc, char** argv) {
  // VTK's OpenGL wants its surface format on every Qt GL surface: before QApplication.
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  TraineeWindowTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "trainee_window_test.moc"
