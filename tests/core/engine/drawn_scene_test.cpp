// The drawn bodies following the haptic tick's touches (DrawnScene), in a fast run and on
// the real-time loop's display thread.
#include "palpa/engine/drawn_scene.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "palpa/engine/realtime_loop.hpp"
#include "palpa/engine/virtual_device.hpp"
#include "palpa/io/case_file.hpp"

namespace palpa::engine {
namespace {

const scene::Scene& default_scene() {
  static const auto scene = scene::Scene::build(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"), "default");
  return scene;
}

// Presses into the default case's body, slides, then jumps well clear of it within a tick
// (the whole dent is left to spring back).
Trajectory press_slide_lift() {
  Trajectory tr;
  tr.t = {0.0, 0.2, 0.5, 0.8, 0.801, 1.5};
  tr.position = {Vec3(0.0, 0.0, 0.08), Vec3(0.0, 0.0, 0.035), Vec3(0.02, 0.01, 0.033), Vec3(0.02, 0.01, 0.034),
                 Vec3(0.02, 0.01, 0.08), Vec3(0.02, 0.01, 0.08)};
  return tr;
}

// Bit for bit the same drawn control points.
void expect_same(const DrawnScene& a, const DrawnScene& b) {
  ASSERT_EQ(a.body_count(), b.body_count());
  for (std::size_t k = 0; k < a.body_count(); ++k) {
    EXPECT_EQ(a.drawn(k).top().control(), b.drawn(k).top().control()) << "body " << k;
    EXPECT_EQ(a.drawn(k).bottom().control(), b.drawn(k).bottom().control()) << "body " << k;
    EXPECT_EQ(a.drawn(k).skeleton().control(), b.drawn(k).skeleton().control()) << "body " << k;
  }
}

TEST(DrawnScene, CatchingUpOnLostTouchesIsTheSpringsTimeThatPassed) {
  // The display thread lost the touches of 10 ticks after the lift (the dent settles in about
  // 30): following the next one with 11 periods must leave the bodies where following all 11
  // would have.
  ScriptedDevice device(press_slide_lift());
  Engine engine(default_scene(), device);
  DrawnScene every(engine);
  DrawnScene skipping(engine);
  int k = 0;
  bool touched = false;
  for (; k <= 1500; ++k) {  // until the tick the finger leaves the body
    engine.tick(k * 1e-3);
    every.follow(engine.last_touch());
    skipping.follow(engine.last_touch());
    touched = touched || engine.last_touch().sample.body == 0;
    if (touched && engine.last_touch().sample.body < 0) break;
  }
  ++k;
  ASSERT_TRUE(every.drawn(0).awake()) << "the dent is still springing back";
  for (int lost = 1; lost <= 10; ++lost, ++k) {
    engine.tick(k * 1e-3);
    every.follow(engine.last_touch());
  }
  engine.tick(k * 1e-3);
  every.follow(engine.last_touch());
  skipping.follow(engine.last_touch(), 11);
  EXPECT_GT(every.drawn(0).max_displacement(), 0.0);
  expect_same(every, skipping);
}

TEST(DrawnScene, ADynamicsSwitchReachesTheBodiesWithTheNextTouch) {
  ScriptedDevice device(press_slide_lift());
  Engine engine(default_scene(), device);
  DrawnScene drawn(engine);
  for (int k = 0; k <= 850; ++k) {  // pressed until 0.8 s, lifted at once
    engine.tick(k * 1e-3);
    Touch touch = engine.last_touch();
    if (k == 850) touch.dynamics = false;  // as Engine::set_dynamics(false) writes it
    drawn.follow(touch);
  }
  EXPECT_EQ(drawn.drawn(0).max_displacement(), 0.0) << "without dynamics a released body is at rest at once";
}

// The drawn top contour of a snapshot, as a surface: the rest net's knots, the snapshot's points.
spline::BSplineSurface top_of(const DrawnScene& drawn, const SceneSnapshot& s, std::size_t body) {
  const auto& rest = drawn.drawn(body).rest_top();
  return {rest.degree_u(), rest.degree_v(), rest.knots_u(), rest.knots_v(), rest.rows(), rest.cols(), rest.dim(),
          s.bodies[body].top};
}

TEST(RealtimeLoop, EverySnapshotDrawsTheDentOfItsOwnTick) {
  // The display thread draws the touches behind the haptic thread: each snapshot must still
  // be one tick's state, the probe on the drawn top contour at that tick's (u, v).
  VirtualDevice device(0.01);
  Engine engine(default_scene(), device);
  const DrawnScene sizes(engine);  // for the rest knots
  RealtimeLoop loop(engine);
  loop.start();
  int pressed = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < 600; ++k) {
    const double t = 0.001 * k;
    device.set_target(Vec3(0.03 * std::sin(8 * t), 0.01, 0.036 - 0.006 * std::sin(5 * t)));
    if (loop.update_snapshot()) {
      const auto& s = loop.snapshot();
      if (s.body == 0 && s.depth > 0.0) {
        ++pressed;
        std::array<double, 3> p{};
        top_of(sizes, s, 0).evaluate(s.u, s.v, p);
        EXPECT_LT(std::hypot(p[0] - s.probe[0], p[1] - s.probe[1], p[2] - s.probe[2]), 1e-9) << "tick " << s.tick;
      }
    }
    std::this_thread::sleep_until(start + std::chrono::microseconds(1000 * (k + 1)));
  }
  loop.stop();
  EXPECT_GT(pressed, 10);
  EXPECT_EQ(loop.dropped_touches(), 0u);
}

TEST(RealtimeLoop, TheLastSnapshotAfterStopShowsTheLastTick) {
  VirtualDevice device(0.0);
  device.set_target(Vec3(0.0245, 0.02, 0.030));  // pressed in and held
  Engine engine(default_scene(), device);
  RealtimeLoop loop(engine);
  loop.start();
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  loop.stop();
  Sample s;
  std::uint64_t ticks = 0;
  while (loop.pop_sample(s)) ++ticks;
  loop.update_snapshot();
  EXPECT_EQ(loop.snapshot().tick, ticks) << "every tick was drawn before stop() returned";
  EXPECT_EQ(loop.snapshot().t, s.t);
}

}  // namespace
}  // namespace palpa::engine
