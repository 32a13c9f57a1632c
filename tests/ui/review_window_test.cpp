// Review mode (QtTest under Xvfb): the window replays data/sessions/expert.palpa; scrubbing
// puts the fingertip on the sample standing at that time, play advances time, the metrics
// table agrees with palpa-cli's score card, Export writes the report; the command line
// rejects a bad session with one line and exit 2, and --screenshot draws the scene.
#include <QApplication>
#include <QComboBox>
#include <QFile>
#include <QLabel>
#include <QProcess>
#include <QPushButton>
#include <QSlider>
#include <QSurfaceFormat>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QVTKOpenGLNativeWidget.h>
#include <QtTest>
#include <cmath>
#include <memory>

#include "palpa/score/score.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/ui/review_window.hpp"

namespace {

const std::string kExpert = PALPA_SOURCE_DIR "/data/sessions/expert.palpa";
const std::string kSloppy = PALPA_SOURCE_DIR "/data/sessions/sloppy.palpa";

std::unique_ptr<palpa::ui::ReviewWindow> open_review(const std::string& file) {
  auto session = palpa::session::read_session(file);
  auto score = palpa::score::score_session(session, file);
  return std::make_unique<palpa::ui::ReviewWindow>(std::move(session), std::move(score), file);
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

// The probe path's colour (amber): neither the background, the skin nor the panel has it.
int path_pixels(const QImage& image) {
  int count = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const QColor c = image.pixelColor(x, y);
      if (c.red() > 180 && c.green() > 120 && c.blue() < 90 && c.red() - c.green() < 90) ++count;
    }
  }
  return count;
}

}  // namespace

class ReviewWindowTest : public QObject {
  Q_OBJECT
 private slots:
  void scrubbingPutsTheFingertipOnTheSampleAtThatTime() {
    auto w = open_review(kExpert);
    w->show();
    const auto& samples = w->session().samples;
    QVERIFY(samples.size() > 1000);
    const auto span = w->span();
    for (int value : {0, 2500, 6180, 9999, palpa::ui::ReviewWindow::kSliderSteps}) {
      w->scrubber()->setValue(value);
      const double t = span.start + (span.end - span.start) * value / palpa::ui::ReviewWindow::kSliderSteps;
      QVERIFY(std::abs(w->time() - t) < 1e-9);
      // Independent truth: a linear scan for the last sample at or before t.
      std::size_t expected = 0;
      for (std::size_t i = 0; i < samples.size(); ++i) {
        if (samples[i].t <= t) expected = i;
      }
      QCOMPARE(w->current_sample(), expected);
      const auto& s = samples[expected];
      const auto c = w->fingertip_centre();
      QVERIFY(std::abs(c[0] - s.position[0]) < 1e-12);
      QVERIFY(std::abs(c[1] - s.position[1]) < 1e-12);
      QVERIFY(std::abs(c[2] - (s.position[2] + palpa::ui::ReviewWindow::kFingertipRadius)) < 1e-12);
      const double force = std::sqrt(s.force[0] * s.force[0] + s.force[1] * s.force[1] + s.force[2] * s.force[2]);
      QVERIFY2(w->readout()->text().contains(QString("|F| = %1 N").arg(force, 0, 'f', 2)),
               qPrintable(w->readout()->text()));
    }
  }

  void marksStandAsPlacedAtTheirTimes() {
    auto w = open_review(kExpert);
    const auto& events = w->session().events;
    const auto end_marks = palpa::session::standing_marks(events);
    QVERIFY(!end_marks.empty());
    w->set_time(w->span().end);
    QCOMPARE(w->marks_shown(), end_marks.size());
    // Just before the first mark was placed, none stands; at its time it does.
    const double first = end_marks.front().t;
    w->set_time(first - 1e-6);
    QCOMPARE(w->marks_shown(), palpa::session::marks_at(events, first - 1e-6).size());
    QVERIFY(w->marks_shown() < end_marks.size() || first - 1e-6 < w->span().start);
    w->set_time(first);
    QVERIFY(w->marks_shown() >= 1);
  }

  void playAdvancesTimeAndPauseStopsIt() {
    auto w = open_review(kExpert);
    w->show();
    w->speed_box()->setCurrentIndex(w->speed_box()->findData(8.0));
    QCOMPARE(w->speed(), 8.0);
    const double t0 = w->time();
    QTest::mouseClick(w->play_button(), Qt::LeftButton);
    QVERIFY(w->playing());
    QTest::qWait(400);
    const double t1 = w->time();
    // At 8x, 0.4 s of wall time is about 3.2 s of session; at least a second under load.
    QVERIFY2(t1 > t0 + 1.0, qPrintable(QString::number(t1 - t0)));
    QVERIFY(w->scrubber()->value() > 0);
    QTest::mouseClick(w->play_button(), Qt::LeftButton);
    QVERIFY(!w->playing());
    const double paused = w->time();
    QTest::qWait(100);
    QCOMPARE(w->time(), paused);
  }

  void metricsTableAgreesWithTheScoreCard() {
    // data/sessions/*.score.txt: expert PASSED, sloppy NOT PASSED (palpa-cli score).
    auto expert = open_review(kExpert);
    QCOMPARE(expert->metrics_table()->item(0, 0)->text(), QString("Result"));
    QCOMPARE(expert->metrics_table()->item(0, 1)->text(), QString("PASSED"));
    QCOMPARE(expert->metrics_table()->item(2, 1)->text(), QString("100 %"));  // sensitivity
    auto sloppy = open_review(kSloppy);
    QCOMPARE(sloppy->metrics_table()->item(0, 1)->text(), QString("FAILED"));
    QCOMPARE(sloppy->metrics_table()->item(3, 1)->text(), QString("3"));  // false positives
  }

  void exportWritesTheReport() {
    auto w = open_review(kExpert);
    QTemporaryDir dir;
    const auto out = std::filesystem::path(dir.path().toStdString()) / "reports";
    QVERIFY(w->export_report(out));
    QFile html(QString::fromStdString((out / "expert.html").string()));
    QVERIFY(html.open(QIODevice::ReadOnly));
    const QByteArray page = html.readAll();
    QVERIFY(page.contains("<html"));
    QVERIFY(page.contains("PASS"));
    QVERIFY(QFile::exists(QString::fromStdString((out / "expert.json").string())));
    QVERIFY(QFile::exists(QString::fromStdString((out / "expert.xapi.json").string())));
    // A folder that cannot be made: false, no crash.
    QVERIFY(!w->export_report("/proc/palpa-no-such-dir"));
  }

  void commandLineRejectsBadSessions() {
    QTemporaryDir dir;
    const QString bad = dir.filePath("bad.palpa");
    {
      QFile f(bad);
      QVERIFY(f.open(QIODevice::WriteOnly));
      f.write("SQLite format 3\0 but not really", 32);
    }
    for (const QString& file : {bad, dir.filePath("missing.palpa")}) {
      const Run r = run_palpa({"--mode", "review", "--session", file});
      QCOMPARE(r.code, 2);
      const QStringList lines = r.err.trimmed().split('\n');
      QCOMPARE(lines.size(), 1);
      QVERIFY2(lines[0].contains(file + ": "), qPrintable(lines[0]));
    }
    QCOMPARE(run_palpa({"--mode", "review"}).code, 2);  // no --session
  }

  void screenshotDrawsTheReplay() {
    QTemporaryDir dir;
    const QString png = dir.filePath("review.png");
    const Run r = run_palpa({"--mode", "review", "--session", QString::fromStdString(kExpert), "--screenshot", png});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QImage image(png);
    QVERIFY(!image.isNull());
    QCOMPARE(image.size(), QSize(1200, 760));
    const int path = path_pixels(image);
    QVERIFY2(path > 5000, qPrintable(QString::number(path)));
  }
};

int main(int argc, char** argv) {
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  ReviewWindowTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "review_window_test.moc"
