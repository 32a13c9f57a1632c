// Knot refinement (A5.4) changes the control net and never the surface; the drawn body,
// refined to fingertip-sized spans, keeps its dent under a sliding finger and leaves no
// trail beyond its own relaxation; the refined net still presses and steps without
// allocating (probe_alloc_test covers the engine tick as a whole).
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "palpa/deform/deformed_body.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/spline/interpolation.hpp"
#include "palpa/spline/knot_refinement.hpp"
#include "../support/test_grids.hpp"

namespace palpa {
namespace {


spline::BSplineSurface wavy_surface(int rows, int cols) {
  const auto samples = test::wavy_grid(rows, cols);
  const auto interpolator = spline::GridInterpolator::from_grid(samples, rows, cols, 7, {});
  return interpolator.interpolate(samples, 7);
}

TEST(KnotRefinement, InsertedKnotsLeaveTheSurfaceUnchanged) {
  const auto s = wavy_surface(7, 9);
  const std::vector<double> in_u{0.05, 0.2, 0.2, 0.5, 0.77};
  const std::vector<double> in_v{0.1, 0.33, 0.9};
  const auto r = spline::refine_knots(spline::refine_knots(s, spline::Direction::U, in_u), spline::Direction::V, in_v);
  EXPECT_EQ(r.rows(), s.rows() + 5);
  EXPECT_EQ(r.cols(), s.cols() + 3);
  EXPECT_EQ(r.knots_u().size(), s.knots_u().size() + 5);
  EXPECT_TRUE(std::is_sorted(r.knots_u().begin(), r.knots_u().end()));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::array<double, 7> a{}, b{};
  double worst = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const double u = k < 4 ? double(k / 2) : unit(rng), v = k < 4 ? double(k % 2) : unit(rng);
    s.evaluate(u, v, a);
    r.evaluate(u, v, b);
    for (std::size_t c = 0; c < 7; ++c) worst = std::max(worst, std::abs(a[c] - b[c]) / (1.0 + std::abs(a[c])));
  }
  EXPECT_LT(worst, 1e-12);
  // Derivatives too (the drawn normals and the tessellation's bounds use them).
  std::array<double, 9 * 7> da{}, db{};
  s.derivatives(0.31, 0.62, 2, da);
  r.derivatives(0.31, 0.62, 2, db);
  for (std::size_t c = 0; c < da.size(); ++c) EXPECT_NEAR(da[c], db[c], 1e-8 * (1.0 + std::abs(da[c])));
}

TEST(KnotRefinement, AKnotAtAnExistingKnotAndSplitSpans) {
  const auto s = wavy_surface(5, 5);
  // The interior knot of a 5-point cubic is 0.5: inserting it raises its multiplicity.
  const std::vector<double> at{s.knots_u()[4]};
  const auto r = spline::refine_knots(s, spline::Direction::U, at);
  std::array<double, 7> a{}, b{};
  s.evaluate(at[0], 0.3, a);
  r.evaluate(at[0], 0.3, b);
  for (std::size_t c = 0; c < 7; ++c) EXPECT_NEAR(a[c], b[c], 1e-13 * (1.0 + std::abs(a[c])));
  const std::vector<int> pieces{2, 3};
  const auto split = spline::split_spans({0, 0, 0, 0, 0.5, 1, 1, 1, 1}, pieces);
  ASSERT_EQ(split.size(), 3u);
  EXPECT_DOUBLE_EQ(split[0], 0.25);
  EXPECT_DOUBLE_EQ(split[1], 0.5 + 0.5 / 3);
  EXPECT_THROW(spline::refine_knots(s, spline::Direction::V, std::vector<double>{0.6, 0.2}), std::invalid_argument);
}

const scene::Scene& default_scene() {
  static const auto scene = scene::Scene::build(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"), "default");
  return scene;
}

TEST(DisplayRefinement, SpansAreFingertipSizedAndTheSurfaceIsTheRestOne) {
  const auto& body = default_scene().body(0).body;
  deform::DeformOptions o;
  o.display_span = 0.004;
  const auto net = deform::display_net(body, o);
  EXPECT_GT(net.top.rows(), 4 * body.top().rows() - 8);
  EXPECT_LE(net.top.rows(), o.max_display_points);
  std::array<double, 3> a{}, b{};
  for (double u = 0.0; u <= 1.0; u += 0.0625) {
    for (double v = 0.0; v <= 1.0; v += 0.0625) {
      body.top().evaluate(u, v, a);
      net.top.evaluate(u, v, b);
      for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-12);
    }
  }
  // No refined span is much longer than the target on the skin (chords at the midline).
  double longest = 0.0;
  for (std::size_t k = 0; k + 1 < net.top.knots_u().size(); ++k) {
    if (!(net.top.knots_u()[k + 1] > net.top.knots_u()[k])) continue;
    net.top.evaluate(net.top.knots_u()[k], 0.5, a);
    net.top.evaluate(net.top.knots_u()[k + 1], 0.5, b);
    longest = std::max(longest, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
  }
  EXPECT_LE(longest, 0.0041);
}

// The drawn top contour's deepest point below rest, searched on a fine grid near (x0, y0).
Vec3 deepest_point(const deform::DeformedBody& drawn, const Vec3& near) {
  const auto& sb = default_scene().body(0);
  const auto foot = sb.search.closest(sb.body.skeleton(), near);
  double deepest = -1.0;
  Vec3 at = Vec3::Zero();
  std::array<double, 3> now{}, rest{};
  for (int a = -40; a <= 40; ++a) {
    for (int b = -40; b <= 40; ++b) {
      const double u = std::clamp(foot.u + a * 0.002, 0.0, 1.0), v = std::clamp(foot.v + b * 0.002, 0.0, 1.0);
      drawn.top().evaluate(u, v, now);
      drawn.rest_top().evaluate(u, v, rest);
      const double sink = rest[2] - now[2];
      if (sink > deepest) {
        deepest = sink;
        at = Vec3(now[0], now[1], now[2]);
      }
    }
  }
  return at;
}

// A finger sliding at 50 mm/s across the breast at a medium press (a third of the local
// thickness), 1 kHz: every 20 ms the dent's deepest point is within 2 mm of the finger
// (in the plane of the skin) and, 0.1 s after the finger has left a spot, the skin there
// is back within 0.1 mm of rest.
TEST(DisplayRefinement, TheDentFollowsASlidingFingerAndLeavesNoTrail) {
  const auto& sb = default_scene().body(0);
  deform::DeformOptions o;
  o.display_span = 0.004;
  deform::DeformedBody drawn(sb.body, o);
  auto state = default_scene().make_state();
  scene::ProbeOptions probe;
  probe.remember_side = true;
  const double speed = 0.05, dt = 1e-3;
  double worst_lag = 0.0;
  Vec3 start_spot = Vec3::Zero();
  for (int k = 0; k <= 1600; ++k) {  // x from -40 mm to +40 mm at y = -10 mm
    const double x = -0.04 + speed * dt * k;
    const auto foot = sb.search.closest(sb.body.skeleton(), Vec3(x, -0.01, 0.05));
    const auto rest = contact::make_contact(sb.body, foot, foot.point);
    const Vec3 n = foot.su.cross(foot.sv).normalized();
    const Vec3 q = foot.point + (rest.radius - 0.35 * 2.0 * rest.radius) * n;
    const auto r = default_scene().probe(q, state, probe);
    ASSERT_EQ(r.body, 0);
    drawn.press(r.contact, q);
    drawn.step(dt);
    if (k == 200) start_spot = q;
    if (k % 20 == 0 && k >= 100) {
      const Vec3 deepest = deepest_point(drawn, q);
      const Vec3 d = deepest - q;
      const double lag = (d - d.dot(n) * n).norm();
      worst_lag = std::max(worst_lag, lag);
    }
  }
  std::printf("dent's deepest point from a finger sliding at 50 mm/s: at most %.3f mm\n", worst_lag * 1e3);
  EXPECT_LT(worst_lag, 0.002) << "the dent's deepest point trailed the finger by " << worst_lag * 1e3 << " mm";
  // The spot the finger crossed 1.4 s ago: back at rest (no crease left behind).
  const auto foot = sb.search.closest(sb.body.skeleton(), start_spot);
  std::array<double, 3> now{}, rest{};
  drawn.top().evaluate(foot.u, foot.v, now);
  drawn.rest_top().evaluate(foot.u, foot.v, rest);
  EXPECT_LT(std::hypot(now[0] - rest[0], now[1] - rest[1], now[2] - rest[2]), 1e-4);
  // The dent is fingertip-sized: 15 mm beside the finger the skin is within 0.5 mm of rest,
  // where the fitted net (17.5 x 16 mm spans) would still be pressed in by millimetres.
  const Vec3 beside = sb.search.closest(sb.body.skeleton(), Vec3(0.04, -0.025, 0.05)).point;
  const auto fb = sb.search.closest(sb.body.skeleton(), beside);
  drawn.top().evaluate(fb.u, fb.v, now);
  drawn.rest_top().evaluate(fb.u, fb.v, rest);
  EXPECT_LT(std::abs(now[2] - rest[2]), 5e-4);
}

}  // namespace
}  // namespace palpa
