// Level of detail by size on screen: the magnification of a box against hand-computed
// cameras; the uniform grid a loose tolerance allows (within the tolerance by its bound,
// the bound above what is measured, refused across a C0 knot); and DisplayMeshes drawing
// a body at a looser tolerance: re-tessellated without a new snapshot, and back to the
// very same mesh when the tolerance is restored.
#include "palpa/render/level_of_detail.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "palpa/io/case_file.hpp"
#include "palpa/live/display_meshes.hpp"
#include "palpa/render/tessellation.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/spline/bspline_surface.hpp"

namespace {

using palpa::render::pixels_per_metre;
using palpa::render::ViewForDetail;
using V = Eigen::Vector3d;

// A camera at the origin looking down -z, 60 degrees of vertical view, 600 px high.
ViewForDetail down_z() {
  ViewForDetail v;
  v.view_angle = std::numbers::pi / 3.0;
  v.viewport_height = 600.0;
  return v;
}

TEST(LevelOfDetail, MagnificationAtTheBoxsNearestDepth) {
  const auto v = down_z();
  const double tan30 = std::tan(std::numbers::pi / 6.0);
  // The box from z = -3 to -2 m: nearest depth 2 m, so 600 / (2 * 2 * tan 30) px per metre.
  EXPECT_NEAR(pixels_per_metre(v, V(-0.5, -0.5, -3.0), V(0.5, 0.5, -2.0)), 600.0 / (4.0 * tan30), 1e-9);
  // Sideways offsets do not change the depth (the projection's depth is along the axis).
  EXPECT_NEAR(pixels_per_metre(v, V(1.0, 1.0, -3.0), V(1.5, 2.0, -2.0)), 600.0 / (4.0 * tan30), 1e-9);
  // A box round the eye or behind it counts as at the near distance: the most detail.
  EXPECT_NEAR(pixels_per_metre(v, V(-1, -1, -1), V(1, 1, 1)), 600.0 / (2.0 * v.near * tan30), 1e-6);
  EXPECT_NEAR(pixels_per_metre(v, V(-1, -1, 2), V(1, 1, 3)), 600.0 / (2.0 * v.near * tan30), 1e-6);
  // Parallel projection: the view's height over twice the scale, wherever the box is.
  ViewForDetail p = v;
  p.parallel = true;
  p.parallel_scale = 0.25;
  EXPECT_NEAR(pixels_per_metre(p, V(0, 0, -9), V(1, 1, -8)), 1200.0, 1e-9);
}

TEST(LevelOfDetail, NearestCornerForAnyViewDirection) {
  // Property: for random directions and boxes, the depth used is the smallest of the eight
  // corners' depths (brute force), floored at the near distance.
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> size(0.01, 0.5);
  for (int trial = 0; trial < 500; ++trial) {
    ViewForDetail v = down_z();
    v.eye = V(n(rng), n(rng), n(rng));
    v.direction = V(n(rng), n(rng), n(rng)).normalized();
    const V lo(n(rng), n(rng), n(rng));
    const V hi = lo + V(size(rng), size(rng), size(rng));
    double depth = std::numeric_limits<double>::infinity();
    for (int c = 0; c < 8; ++c) {
      const V corner((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
      depth = std::min(depth, (corner - v.eye).dot(v.direction));
    }
    depth = std::max(depth, v.near);
    const double expected = v.viewport_height / (2.0 * depth * std::tan(0.5 * v.view_angle));
    ASSERT_NEAR(pixels_per_metre(v, lo, hi), expected, 1e-9 * expected) << "trial " << trial;
  }
}

// A bicubic surface 10 cm square, bent like a dome (z = -8 (x^2 + y^2) m), over the given
// interior knots in both directions.
palpa::spline::BSplineSurface dome(const std::vector<double>& interior) {
  std::vector<double> knots = {0, 0, 0, 0};
  knots.insert(knots.end(), interior.begin(), interior.end());
  knots.insert(knots.end(), {1, 1, 1, 1});
  const std::size_t n = knots.size() - 4;
  // Greville abscissae: x and y linear in u and v.
  const auto greville = [&](std::size_t i) { return 0.1 * (knots[i + 1] + knots[i + 2] + knots[i + 3]) / 3.0 - 0.05; };
  std::vector<double> ctrl;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      const double x = greville(i), y = greville(j);
      ctrl.insert(ctrl.end(), {x, y, -8.0 * (x * x + y * y)});
    }
  const int size = static_cast<int>(n);
  return palpa::spline::BSplineSurface(3, 3, knots, knots, size, size, 3, ctrl);
}

TEST(LevelOfDetail, AUniformGridWhenItIsCheaperWithinTheTolerance) {
  // Many knots (a display net refined to short spans): through the knots at least one
  // segment per span; a loose tolerance needs far fewer.
  std::vector<double> interior;
  for (int k = 1; k < 40; ++k) interior.push_back(k / 40.0);
  const auto s = dome(interior);
  for (const double tol : {1e-4, 1e-3, 4e-3, 1.6e-2}) {
    palpa::render::TessellationOptions knots_only{.tolerance = tol};
    palpa::render::TessellationOptions either = knots_only;
    either.uniform_if_cheaper = true;
    palpa::render::Mesh a, b;
    palpa::render::tessellate(s, knots_only, false, a);
    palpa::render::tessellate(s, either, false, b);
    EXPECT_GE(a.rows, 41);  // every knot a grid line
    EXPECT_LE(b.rows * b.cols, a.rows * a.cols) << tol;
    EXPECT_LE(b.error_bound, tol * (1.0 + 1e-12)) << tol;
    // The bound holds: the measured deviation is no larger.
    EXPECT_LE(palpa::render::max_parametric_deviation(b, s, 6), b.error_bound * (1.0 + 1e-9) + 1e-12) << tol;
    if (tol >= 1e-3) {
      EXPECT_LT(b.rows, 20) << tol;  // uniform, and much coarser
      EXPECT_EQ(b.rows, b.cols);
    }
  }
}

TEST(LevelOfDetail, AKnotWhereTheSurfaceIsOnlyC0KeepsTheKnotLines) {
  // A triple knot at 0.5: a cubic may have a crease there, which no uniform cell may
  // straddle under one bound.
  const auto s = dome({0.25, 0.5, 0.5, 0.5, 0.75});
  palpa::render::TessellationOptions o{.tolerance = 1.6e-2};
  o.uniform_if_cheaper = true;
  palpa::render::Mesh m;
  palpa::render::tessellate(s, o, false, m);
  EXPECT_TRUE(std::find(m.us.begin(), m.us.end(), 0.5) != m.us.end());
  EXPECT_TRUE(std::find(m.vs.begin(), m.vs.end(), 0.5) != m.vs.end());
}

palpa::scene::Scene default_scene() {
  return palpa::scene::Scene::build(palpa::io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"), "default.json");
}

TEST(DisplayMeshesDetail, ALooserToleranceStaysWithinItAndIsUndone) {
  const auto scene = default_scene();
  palpa::live::DisplayMeshes meshes(scene);
  const auto full = meshes.top(0);
  const double base = palpa::render::TessellationOptions{}.tolerance;
  const palpa::engine::SceneSnapshot none;  // no new snapshot: the tolerance alone re-tessellates

  std::size_t last_cells = static_cast<std::size_t>(full.rows) * static_cast<std::size_t>(full.cols);
  for (const double tol : {1e-3, 3e-3, 1e-2}) {
    meshes.set_tolerance(0, tol);
    EXPECT_EQ(meshes.tolerance(0), tol);
    ASSERT_EQ(meshes.update(none), 1u) << tol;
    EXPECT_TRUE(meshes.changed(0));
    for (const auto* m : {&meshes.top(0), &meshes.bottom(0)}) EXPECT_LE(m->error_bound, tol * (1.0 + 1e-12)) << tol;
    // The measured deviation never exceeds the bound the grid was chosen by.
    EXPECT_LE(meshes.deviation(0), std::max(meshes.top(0).error_bound, meshes.bottom(0).error_bound) * (1.0 + 1e-9) + 1e-9);
    const auto cells = static_cast<std::size_t>(meshes.top(0).rows) * static_cast<std::size_t>(meshes.top(0).cols);
    EXPECT_LT(cells, last_cells) << tol;  // looser is coarser
    last_cells = cells;
    EXPECT_EQ(meshes.update(none), 0u);  // nothing changed since
  }
  // Restored (or asked finer than the options allow), the very same mesh comes back.
  meshes.set_tolerance(0, base / 10.0);
  EXPECT_EQ(meshes.tolerance(0), base);
  ASSERT_EQ(meshes.update(none), 1u);
  EXPECT_EQ(meshes.top(0).rows, full.rows);
  EXPECT_EQ(meshes.top(0).cols, full.cols);
  EXPECT_EQ(meshes.top(0).positions, full.positions);
  EXPECT_EQ(meshes.top(0).triangles, full.triangles);
  meshes.set_tolerance(0, std::numeric_limits<double>::infinity());  // not a tolerance: ignored
  EXPECT_EQ(meshes.tolerance(0), base);
}

TEST(DisplayMeshesDetail, AnInvisibleBodyTakesItsNewDetailWhenSeenAgain) {
  const auto scene = default_scene();
  palpa::live::DisplayMeshes meshes(scene);
  const palpa::engine::SceneSnapshot none;
  const int rows = meshes.top(0).rows;
  meshes.set_visible(0, false);
  meshes.set_tolerance(0, 1e-2);
  EXPECT_EQ(meshes.update(none), 0u);
  EXPECT_EQ(meshes.top(0).rows, rows);
  meshes.set_visible(0, true);
  EXPECT_EQ(meshes.update(none), 1u);
  EXPECT_LT(meshes.top(0).rows, rows);
}

}  // namespace
