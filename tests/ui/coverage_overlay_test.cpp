// The coverage overlay's dots thinned for the view (ui::CoverageOverlay::fit_to_view): seen
// from afar, fewer dots are drawn and the ones drawn lie at least kMinSpacing pixels apart
// on screen; seen from close, every dot of the exam region is drawn.
#include <QtTest>
#include <algorithm>
#include <cmath>

#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include "palpa/io/case_file.hpp"
#include "palpa/live/live_coverage.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/ui/coverage_overlay.hpp"

class CoverageOverlayTest : public QObject {
  Q_OBJECT

  // px between `a` and its nearest other dot, on screen.
  static double nearest_on_screen(vtkRenderer& r, const std::vector<palpa::Vec3>& dots, std::size_t a) {
    const auto screen = [&r](const palpa::Vec3& p) {
      double d[3];
      r.SetWorldPoint(p.x(), p.y(), p.z(), 1.0);
      r.WorldToDisplay();
      r.GetDisplayPoint(d);
      return std::array<double, 2>{d[0], d[1]};
    };
    const auto pa = screen(dots[a]);
    double best = 1e9;
    for (std::size_t b = 0; b < dots.size(); ++b) {
      if (b == a) continue;
      const auto pb = screen(dots[b]);
      best = std::min(best, std::hypot(pa[0] - pb[0], pa[1] - pb[1]));
    }
    return best;
  }

 private slots:
  void fromAfarFewerDotsLieFartherApart() {
    const auto file = palpa::io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json");
    const auto scene = palpa::scene::Scene::build(file, "default.json");
    palpa::live::LiveCoverage coverage(scene, palpa::io::Thresholds{});
    vtkNew<vtkRenderWindow> window;
    window->SetOffScreenRendering(1);
    window->SetSize(800, 600);
    vtkNew<vtkRenderer> renderer;
    window->AddRenderer(renderer);
    auto* camera = renderer->GetActiveCamera();
    camera->SetPosition(0.0, 0.0, 0.25);  // 25 cm above the breast: it fills the view
    camera->SetFocalPoint(0.0, 0.0, 0.0);
    camera->SetViewUp(0.0, 1.0, 0.0);
    palpa::ui::CoverageOverlay overlay(coverage, renderer, palpa::Vec3(0.0, 0.0, 0.25));
    overlay.fit_to_view();
    const auto close = overlay.shown_dots();
    camera->SetPosition(0.0, 0.0, 2.5);  // ten times farther
    QVERIFY(overlay.fit_to_view());
    const auto far = overlay.shown_dots();
    std::vector<double> gaps;
    for (std::size_t k = 0; k < far.size(); k += 7) gaps.push_back(nearest_on_screen(*renderer, far, k));
    std::nth_element(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2), gaps.end());
    qInfo("dots drawn: %zu from 25 cm, %zu from 2.5 m (median gap %.1f px there)", close.size(), far.size(), gaps[gaps.size() / 2]);
    QVERIFY(far.size() * 4 <= close.size());
    QVERIFY(gaps[gaps.size() / 2] >= palpa::ui::CoverageOverlay::kMinSpacing - 0.5);
    camera->SetPosition(0.0, 0.0, 0.25);
    QVERIFY(overlay.fit_to_view());
    QCOMPARE(overlay.shown_dots().size(), close.size());
    QVERIFY(!overlay.fit_to_view());  // the camera did not move: nothing to do
  }
};

int run_coverage_overlay_tests(int argc, char** argv) {
  CoverageOverlayTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "coverage_overlay_test.moc"
