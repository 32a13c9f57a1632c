// The trainee window's level of detail, as drawn: Table 1's 35 bodies, each about 20 px
// wide in the trainee's view, are drawn with a small share of the triangles a full-detail
// grid has, within a pixel of their surfaces and with a picture that differs from the
// full-detail one in a handful of pixels; close up, a body gets its full grid back.
#include <QCheckBox>
#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cstdlib>
#include <memory>

#include <vtkCamera.h>
#include <vtkRenderer.h>

#include "palpa/io/case_file.hpp"
#include "palpa/live/live_exercise.hpp"
#include "palpa/scene/table1_scenes.hpp"
#include "palpa/ui/trainee_window.hpp"
#include "palpa/ui/vtk_view.hpp"

class LevelOfDetailTest : public QObject {
  Q_OBJECT

  // A session in `dir`, the haptic loop without real-time priority.
  static palpa::live::LiveOptions options(const QTemporaryDir& dir, const QString& file) {
    palpa::live::LiveOptions o;
    o.trainee = "ui-test";
    o.session_path = dir.filePath(file).toStdString();
    o.realtime.request_fifo = false;
    return o;
  }

  // Two frames: the level of detail is fitted at the start of a frame, so the second draws it.
  static QImage draw(palpa::ui::TraineeWindow& w) {
    w.frame();
    w.frame();
    QTest::qWait(100);  // the view's native window shows the new frame
    return w.view()->frame().convertToFormat(QImage::Format_RGB32);
  }

  // Pixels whose colour differs by more than `levels` in some channel.
  static int differing(const QImage& a, const QImage& b, int levels) {
    int n = 0;
    for (int y = 0; y < a.height(); ++y)
      for (int x = 0; x < a.width(); ++x) {
        const QRgb p = a.pixel(x, y), q = b.pixel(x, y);
        const int d = std::max({std::abs(qRed(p) - qRed(q)), std::abs(qGreen(p) - qGreen(q)), std::abs(qBlue(p) - qBlue(q))});
        if (d > levels) ++n;
      }
    return n;
  }

 private slots:
  void smallBodiesAreDrawnCoarserWithinAPixel() {
    QTemporaryDir dir;
    const auto o = options(dir, "lod.palpa");
    const auto& spec = palpa::scene::table1_scenes().back();
    QCOMPARE(spec.bodies, 35);
    // Not started: the bodies at rest, the same picture at every draw.
    palpa::ui::TraineeWindow window(
        std::make_unique<palpa::live::LiveExercise>(palpa::scene::make_table1_case(spec), "table1", o), "Table 1", false);
    window.set_frame_interval(-1);  // this test draws the frames
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));

    window.set_detail_pixels(0.0);
    draw(window);
    const std::size_t full_triangles = window.last_frame().triangles;
    const int full_rows = window.exercise().meshes().top(0).rows;
    const double full_px = window.drawn_deviation_px();

    window.set_detail_pixels(palpa::ui::TraineeWindow::kDetailPixels);
    draw(window);
    const std::size_t triangles = window.last_frame().triangles;
    const double px = window.drawn_deviation_px();
    qInfo("35 bodies in view: %zu triangles at full detail (%.3f px from the surfaces), %zu at %.1f px "
          "(%.2f px)", full_triangles, full_px, triangles, palpa::ui::TraineeWindow::kDetailPixels, px);
    QCOMPARE(window.last_frame().bodies_drawn, std::size_t{35});
    QVERIFY(triangles * 4 <= full_triangles);
    QVERIFY(px <= 1.0);

    // Close on body 0 it is large on screen: the tolerance's grid again (as close as that grid
    // is: about a pixel at this magnification), the others culled.
    window.look_at_body(0);
    draw(window);
    QCOMPARE(window.exercise().meshes().top(0).rows, full_rows);
    QVERIFY(window.last_frame().bodies_drawn < 35);
  }

  void aDomeFarAwayLooksTheSameWithFewerTriangles() {
    QTemporaryDir dir;
    const auto o = options(dir, "lod-dome.palpa");
    const std::string breast = PALPA_SOURCE_DIR "/data/cases/default.json";
    palpa::ui::TraineeWindow window(
        std::make_unique<palpa::live::LiveExercise>(palpa::io::load_case(breast), breast, o), "default.json", false);
    window.set_frame_interval(-1);
    // The body itself: the coverage overlay's dots off, as its checkbox turns them off.
    auto* overlay = window.findChild<QCheckBox*>("coverageOverlay");
    QVERIFY(overlay);
    overlay->setChecked(false);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    auto* camera = window.renderer()->GetActiveCamera();
    camera->Elevation(-40.0);  // at a slant: its curved side and silhouette in view
    const auto compare = [&](double cell, std::size_t& triangles) {
      window.set_detail_pixels(cell);
      const QImage image = draw(window);
      triangles = window.last_frame().triangles;
      return image;
    };
    std::size_t full_triangles = 0, triangles = 0;
    for (int halving = 0; halving <= 4; ++halving) {  // 1 to 1/16 of the body's size on screen
      if (halving > 0) camera->Dolly(0.5);
      window.renderer()->ResetCameraClippingRange();
      const QImage full = compare(0.0, full_triangles);
      const QImage coarse = compare(palpa::ui::TraineeWindow::kDetailPixels, triangles);
      const double px = window.drawn_deviation_px();
      int body = 0;  // pixels not of the background
      for (int y = 0; y < full.height(); ++y)
        for (int x = 0; x < full.width(); ++x) body += full.pixel(x, y) != full.pixel(0, 0) ? 1 : 0;
      const int any = differing(full, coarse, 0), changed = differing(full, coarse, 24);
      qInfo("1/%d the size: %zu -> %zu triangles, %.2f px from the surface; of %d body pixels %d differ, %d by more "
            "than 24 levels", 1 << halving, full_triangles, triangles, px, body, any, changed);
      QVERIFY(px <= 1.0);
      // A sub-pixel shift of the silhouette may flip an edge pixel between skin and
      // background: a few, at most 1 in 200 of the body's pixels.
      QVERIFY(changed <= 2 + body / 200);
      if (halving == 4) {
        QVERIFY(triangles * 8 <= full_triangles);
        // The comparison can tell a grid too coarse: a 10 px tolerance shows.
        std::size_t rough = 0;
        const QImage too_coarse = compare(10.0, rough);
        const int rough_changed = differing(full, too_coarse, 24);
        qInfo("at 10 px: %zu triangles, %d pixels differ by more than 24 levels", rough, rough_changed);
        QVERIFY(rough_changed > 2 + body / 200);
      }
    }
  }
};

int run_level_of_detail_tests(int argc, char** argv) {
  LevelOfDetailTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "level_of_detail_test.moc"
