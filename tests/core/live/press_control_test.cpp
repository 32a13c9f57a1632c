// The mouse's pressure (core/live/press_control): the dial's settings fall in the
// score's bands; the follower keeps the finger at the chosen share of the local thickness
// while it walks along the top contour (a jump across the body never cuts a chord
// through it), lifts off the body, crosses between bodies through the air, and in force
// mode sinks less over a stiff lump than beside it.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <string>

#include "palpa/contact/contact.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/live/press_control.hpp"

namespace palpa::live {
namespace {

scene::Scene load_scene(const std::string& name) {
  return scene::Scene::build(io::load_case(std::string(PALPA_SOURCE_DIR "/data/cases/") + name), name);
}

// An independent reading of a probe position: a fresh query, no memory.
scene::ProbeResult probe(const scene::Scene& s, const Vec3& q) {
  auto state = s.make_state();
  return s.probe(q, state, {});
}

std::optional<render::SurfacePick> pick_above(const render::TopContourPicker& picker, double x, double y) {
  return picker.pick(Vec3(x, y, 0.5), Vec3(0, 0, -1));
}

TEST(PressureDial, NineSettingsInTheScoresBands) {
  io::Thresholds th;  // light < 0.2, deep >= 0.5
  PressureDial dial(th, 0);
  double last = -1.0;
  for (int k = 0; k < PressureDial::kSettings; ++k) {
    dial.set_index(k);
    EXPECT_GT(dial.share(), last);
    last = dial.share();
    EXPECT_EQ(level_of(dial.share(), th), dial.level()) << k;
    EXPECT_EQ(dial.step_in_level(), k % 3 + 1);
  }
  dial.set_index(0);
  EXPECT_DOUBLE_EQ(dial.share(), 0.025);  // an eighth into the light band
  dial.set_index(4);
  EXPECT_DOUBLE_EQ(dial.share(), 0.35);  // the middle of medium
  dial.set_index(6);
  EXPECT_DOUBLE_EQ(dial.share(), 0.5 + 0.125 * 0.35);  // just deep
  dial.set_index(8);
  EXPECT_DOUBLE_EQ(dial.share(), 0.5 + 0.875 * 0.35);
  dial.step(5);
  EXPECT_EQ(dial.index(), 8);  // clamped
  dial.step(-20);
  EXPECT_EQ(dial.index(), 0);
  EXPECT_EQ(PressureDial(th, PressureDial::middle_of(PressureLevel::Deep)).level(), PressureLevel::Deep);
  EXPECT_STREQ(to_string(PressureLevel::Medium), "medium");
}

TEST(SurfaceFollower, PressesToTheShareAndWalksAlongTheSurface) {
  const auto s = load_scene("default.json");
  const render::TopContourPicker picker(s);
  SurfaceFollower f(s);
  EXPECT_FALSE(f.advance(0.016, 0.0).has_value());  // nothing before the first pick
  f.set_share(0.35);
  f.aim(pick_above(picker, -0.04, -0.05));
  std::optional<Vec3> target;
  for (int k = 0; k < 60; ++k) target = f.advance(0.016, 0.0);
  ASSERT_TRUE(target);
  auto r = probe(s, *target);
  ASSERT_EQ(r.body, 0);
  EXPECT_NEAR(r.contact.depth / (2.0 * r.contact.radius), 0.35, 1e-6);
  // A jump to the far side of the breast: every frame's target stays at the share under
  // the skin (a chord would sink towards the chest wall in the middle).
  f.aim(pick_above(picker, 0.045, 0.055));
  for (int frame = 0; frame < 100; ++frame) {  // 1.6 s: the walk takes about 0.4 s at 0.4 m/s
    target = f.advance(0.016, 0.0);
    r = probe(s, *target);
    ASSERT_EQ(r.body, 0) << "frame " << frame;
    EXPECT_NEAR(r.contact.depth / (2.0 * r.contact.radius), 0.35, 1e-6) << "frame " << frame;
  }
  const double travelled = (surface_frame(s.body(0).body, f.u(), f.v()).top - pick_above(picker, 0.045, 0.055)->point).norm();
  EXPECT_LT(travelled, 2e-3);
}

TEST(SurfaceFollower, LiftsOffTheBodyAndNeverPressesPastTheSupport) {
  const auto s = load_scene("default.json");
  const render::TopContourPicker picker(s);
  SurfaceFollower f(s);
  f.set_share(2.0);  // asks for more than the tissue: clamped below the support
  f.aim(pick_above(picker, 0.0, 0.0));
  Vec3 target;
  for (int k = 0; k < 60; ++k) target = *f.advance(0.016, 0.0);
  auto r = probe(s, target);
  EXPECT_NEAR(r.contact.depth / (2.0 * r.contact.radius), PressureDial::kMaxShare, 1e-6);
  EXPECT_EQ(r.contact.support_depth, 0.0);
  f.aim(std::nullopt);  // off the body
  for (int k = 0; k < 60; ++k) target = *f.advance(0.016, 0.0);
  r = probe(s, target);
  EXPECT_LT(r.body, 0);
  const auto frame = surface_frame(s.body(0).body, f.u(), f.v());
  EXPECT_NEAR((target - frame.top).dot(frame.normal), FollowerOptions{}.lift, 1e-9);
}

TEST(SurfaceFollower, CrossesBetweenBodiesThroughTheAir) {
  const auto s = load_scene("two-bodies.json");
  const render::TopContourPicker picker(s);
  SurfaceFollower f(s);
  f.set_share(0.6);
  f.aim(pick_above(picker, -0.06, 0.0));
  for (int k = 0; k < 60; ++k) f.advance(0.016, 0.0);
  EXPECT_EQ(f.body(), 0u);
  f.aim(pick_above(picker, 0.06, 0.0));
  bool lifted_between = false;
  for (int k = 0; k < 120; ++k) {
    const Vec3 target = *f.advance(0.016, 0.0);
    const auto r = probe(s, target);
    if (r.body >= 0) {
      // Inside either body only at the chosen share or less (no chord through a flank).
      EXPECT_LE(r.contact.depth / (2.0 * r.contact.radius), 0.6 + 1e-6) << k;
    } else if (f.body() == 0u) {
      lifted_between = true;
    }
  }
  EXPECT_TRUE(lifted_between);
  EXPECT_EQ(f.body(), 1u);
  const auto r = probe(s, *f.advance(0.016, 0.0));
  EXPECT_EQ(r.body, 1);
  EXPECT_NEAR(r.contact.depth / (2.0 * r.contact.radius), 0.6, 1e-6);
}

// Force mode, closed loop over the scene's own force: at equal force the finger sinks
// less over the tumour than over the same tissue beside it.
TEST(SurfaceFollower, ForceModeSinksLessOverAStiffLump) {
  const auto s = load_scene("default.json");
  const render::TopContourPicker picker(s);
  const auto& t = s.body(0).tumours.at(0);
  const auto settle = [&](double x, double y) {
    SurfaceFollower f(s);
    f.set_share(0.3);
    f.aim(pick_above(picker, x, y));
    f.set_force_target(8.0);
    double felt = 0.0;
    scene::ProbeResult r;
    for (int k = 0; k < 600; ++k) {
      r = probe(s, *f.advance(0.016, felt));
      felt = r.force.total.norm();
    }
    EXPECT_NEAR(felt, 8.0, 0.1) << "at " << x << ", " << y;
    return r.contact.depth;
  };
  const double over = settle(t.center[0], t.center[1]);
  const double beside = settle(-t.center[0], -t.center[1]);  // the mirror spot: same tissue, no tumour
  // At 8 N (about 25 mm of the default breast in kPa) the tumour makes the tissue about
  // 1.35 times firmer; the gland's strain stiffening makes force grow steeply with depth, so
  // that is about 10 % less sink.
  EXPECT_LT(over, 0.95 * beside) << "over " << over << " beside " << beside;
}

}  // namespace
}  // namespace palpa::live
