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
#include <functional>
#include <memory>
#include <vtkCamera.h>
#include <vtkPoints.h>
#include <vtkRenderer.h>
#include <vtkPolyData.h>

#include "palpa/io/case_file.hpp"
#include "palpa/live/live_exercise.hpp"
#include "palpa/ui/force_gauge.hpp"
#include "palpa/ui/score_card.hpp"
#include "palpa/ui/trainee_window.hpp"
#include "palpa/ui/vtk_view.hpp"
#include "palpa/version.hpp"

namespace {

const std::string kDefaultCase = PALPA_SOURCE_DIR "/data/cases/default.json";

std::unique_ptr<palpa::live::LiveExercise> make_exercise(const QString& session) {
  palpa::live::LiveOptions o;
  o.trainee = "ui-test";
  o.seed = 11;
  o.session_path = session.toStdString();
  o.realtime.request_fifo = false;
  o.device_settling = 0.01;
  return std::make_unique<palpa::live::LiveExercise>(palpa::io::load_case(kDefaultCase), kDefaultCase, o);
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
    QVERIFY2(window.frame_rate() <= 6.0, qPrintable(QString::number(window.frame_rate())));
    auto* view = window.view();
    const QPoint centre = window.to_view(top_over_tumour(window.exercise()));
    QElapsedTimer clock;
    clock.start();
    for (int k = 0; clock.elapsed() < 2300; ++k) {
      move_pointer(view->input(), centre + QPoint((k % 40) - 20, ((k / 40) % 2) * 10));
      QTest::qWait(15);
    }
    qInfo("frames drawn: moving %.1f per second", window.frame_rate());
    QVERIFY2(window.frame_rate() >= 8.0, qPrintable(QString::number(window.frame_rate())));
  }

  void mousePalpationPressesTheTissue() {
    QTemporaryDir dir;
    palpa::ui::TraineeWindow window(make_exercise(dir.filePath("press.palpa")), "default.json");
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QTest::qWait(100);
    auto* view = window.view();
    vtkPoints* points = window.surfaces().top(0)->GetPoints();
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
      vtkPoints* now = window.surfaces().top(0)->GetPoints();
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
    QCOMPARE(image.size(), QSize(1200, 760));
    // The body covers a good part of the view (about a fifth of the window at the default
    // camera); an empty view has none of its colour.
    const int skin = skin_pixels(image);
    QVERIFY2(skin > image.width() * image.height() / 10, qPrintable(QString::number(skin)));
    QVERIFY(!QFile::exists(dir.filePath("trainee.palpa")));
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
    c.stiffness = 420.0;  // N/m
    g.set_contact(c);
    QCOMPARE(g.lines()[0], QString("6.0 N  stiffness 0.42 N/mm"));
    QCOMPARE(g.lines()[1], QString("deep: depth 25.0 mm (50 % of 50 mm)"));
    QCOMPARE(g.alert(), palpa::ui::ForceGauge::Alert::None);
    c.force = 18.0;
    c.at_force_bound = true;
    g.set_contact(c);
    QVERIFY2(g.lines()[0].contains("held at 18 N: the safety limit is 20 N"), qPrintable(g.text()));
    QCOMPARE(g.alert(), palpa::ui::ForceGauge::Alert::Bound);
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
