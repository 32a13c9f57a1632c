// The haptic engine's tick, its devices and its force governor.
#include "palpa/engine/engine.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "palpa/engine/drawn_scene.hpp"
#include "palpa/engine/virtual_device.hpp"
#include "palpa/io/case_file.hpp"

namespace palpa::engine {
namespace {

const scene::Scene& default_scene() {
  static const auto scene = scene::Scene::build(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"), "default");
  return scene;
}

// Straight down over the tumour of the default case, 30 mm in, over 1 s; then back out.
Trajectory press_over_tumour() {
  Trajectory tr;
  for (int k = 0; k <= 20; ++k) {
    const double t = 0.1 * k;
    const double depth = k <= 10 ? 0.003 * k : 0.003 * (20 - k);
    tr.t.push_back(t);
    tr.position.emplace_back(0.0245, 0.02, 0.046 - depth);
  }
  return tr;
}

TEST(ForceGovernor, CapsAtTheSmallerOfDeviceAndConfiguredMaximum) {
  SafetyOptions o;
  o.max_force = 8.0;
  o.max_force_rate = 1e9;
  ForceGovernor device_caps(o, 3.3);  // a Phantom Omni
  EXPECT_NEAR(device_caps.govern(Vec3(0, 0, 50), 1e-3, false).norm(), 3.3, 1e-12);
  ForceGovernor config_caps(o, 12.0);
  const Vec3 f = config_caps.govern(Vec3(30, 0, 40), 1e-3, false);
  EXPECT_NEAR(f.norm(), 8.0, 1e-12);
  EXPECT_NEAR(f.x() / f.z(), 0.75, 1e-12);  // direction kept
}

TEST(ForceGovernor, LimitsTheRateOfChange) {
  SafetyOptions o;
  o.max_force_rate = 1000.0;  // N/s: 1 N per 1 ms tick
  ForceGovernor g(o, 30.0);
  Vec3 previous = Vec3::Zero();
  for (int k = 0; k < 20; ++k) {
    const Vec3 f = g.govern(Vec3(0, 0, 10), 1e-3, false);
    EXPECT_LE((f - previous).norm(), 1.0 + 1e-12);
    previous = f;
  }
  EXPECT_NEAR(previous.z(), 10.0, 1e-12);  // reached after 10 ticks and held
}

TEST(ForceGovernor, AFaultRampsToZeroWithinTheRampTimeAndNaNIsNeverPassedOn) {
  SafetyOptions o;
  o.max_force = 20.0;
  o.max_force_rate = 1e9;
  o.ramp_time = 0.05;
  ForceGovernor g(o, 20.0);
  (void)g.govern(Vec3(0, 0, 20), 1e-3, false);
  int ticks = 0;
  double previous = 20.0;
  while (g.govern(Vec3(0, 0, 20), 1e-3, true).norm() > 0.0) {
    const double now = g.last().norm();
    EXPECT_LT(now, previous);
    EXPECT_GE(previous - now, 20.0 / 50.0 - 1e-9);  // at least cap / ramp_time per second
    previous = now;
    ++ticks;
    ASSERT_LT(ticks, 1000);
  }
  EXPECT_LE(ticks, 50);  // 50 ms at 1 kHz
  ForceGovernor h(o, 20.0);
  EXPECT_EQ(h.govern(Vec3(std::nan(""), 0, 0), 1e-3, false), Vec3::Zero());
}

// Back from a fault the force rises no faster than the ramp (cap / ramp_time), not at the
// full rate limit, up to what is asked and no further; then the rate limit is back.
TEST(ForceGovernor, AfterAFaultTheForceComesBackAtTheRamp) {
  SafetyOptions o;  // 30 N cap, 5000 N/s, 50 ms ramp: 600 N/s back from a fault
  ForceGovernor g(o, 30.0);
  for (int k = 0; k < 10; ++k) (void)g.govern(Vec3(0, 0, 15), 1e-3, false);
  ASSERT_NEAR(g.last().z(), 15.0, 1e-12);
  for (int k = 0; k < 10; ++k) (void)g.govern(Vec3(0, 0, 15), 1e-3, true);
  ASSERT_EQ(g.last().norm(), 0.0);
  const double ramp_step = 30.0 / 0.05 * 1e-3;  // N per 1 ms tick
  double previous = 0.0;
  int ticks = 0;
  while (g.last() != Vec3(0, 0, 15)) {  // the last step lands on the request exactly
    const double now = g.govern(Vec3(0, 0, 15), 1e-3, false).z();
    EXPECT_LE(now - previous, ramp_step + 1e-12);
    EXPECT_LE(now, 15.0 + 1e-12);
    previous = now;
    ASSERT_LT(++ticks, 1000);
  }
  EXPECT_NEAR(ticks, 25, 1);  // 15 N at 0.6 N per tick
  // Recovered: the normal rate limit (5 N per tick) again.
  EXPECT_NEAR(g.govern(Vec3(0, 0, 25), 1e-3, false).z(), 20.0, 1e-12);
}

TEST(VirtualDevice, FollowsItsTargetSmoothlyWithoutOvershoot) {
  VirtualDevice d(0.03);
  DevicePose pose;
  d.set_target(Vec3(0, 0, 0));
  d.read(0.0, pose);
  d.set_target(Vec3(0.01, 0, 0));
  double previous = 0.0;
  for (int k = 1; k <= 100; ++k) {
    d.read(k * 1e-3, pose);
    EXPECT_GE(pose.position.x(), previous - 1e-15);  // monotone: critically damped
    EXPECT_LE(pose.position.x(), 0.01 + 1e-15);      // no overshoot
    previous = pose.position.x();
  }
  EXPECT_NEAR(pose.position.x(), 0.01, 0.01 * 0.02);  // settled to 2 % after 30 ms (well within 100 ms)
  VirtualDevice jump(0.0);
  jump.set_target(Vec3(1, 2, 3), 5);
  jump.read(0.0, pose);
  EXPECT_EQ(pose.position, Vec3(1, 2, 3));
  EXPECT_EQ(pose.buttons, 5u);
}

TEST(ScriptedDevice, InterpolatesLinearlyAndHoldsTheEnds) {
  Trajectory tr;
  tr.t = {0.0, 1.0, 3.0};
  tr.position = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 2, 0)};
  ScriptedDevice d(tr);
  DevicePose pose;
  for (const auto& [t, x, y] : {std::tuple{-1.0, 0.0, 0.0}, {0.25, 0.25, 0.0}, {2.0, 1.0, 1.0}, {5.0, 1.0, 2.0},
                                {0.5, 0.5, 0.0}}) {  // the last one goes back in time
    d.read(t, pose);
    EXPECT_NEAR(pose.position.x(), x, 1e-15) << t;
    EXPECT_NEAR(pose.position.y(), y, 1e-15) << t;
    EXPECT_EQ(tr.at(t), pose.position) << t;
  }
}

TEST(Engine, ForceIsTheContactForceAndTheDrawnSurfaceFollowsTheProbe) {
  const auto& scene = default_scene();
  ScriptedDevice device(press_over_tumour());
  EngineOptions options;
  options.safety.max_force_rate = 1e9;  // let the requested force through unchanged
  Engine engine(scene, device, options);
  DrawnScene drawn(engine);
  auto state = scene.make_state();
  scene::ProbeOptions probe;
  probe.remember_side = true;
  int contacts = 0;
  for (int k = 0; k <= 2000; ++k) {
    const double t = k * 1e-3;
    const Sample s = engine.tick(t);
    drawn.follow(engine.last_touch());
    const Vec3 q(s.position[0], s.position[1], s.position[2]);
    const auto r = scene.probe(q, state, probe);
    ASSERT_EQ(s.body, r.body) << t;
    EXPECT_LE((Vec3(s.force[0], s.force[1], s.force[2]) - r.force.total).norm(), 1e-12) << t;
    if (s.body >= 0) {
      ++contacts;
      // The drawn top contour under the probe is on the probe.
      std::array<double, 3> p{};
      drawn.drawn(0).top().evaluate(s.u, s.v, p);
      EXPECT_LT((Vec3(p[0], p[1], p[2]) - q).norm(), 1e-9) << t;
    }
  }
  EXPECT_GT(contacts, 1000);
}

TEST(Engine, FastRunsAreDeterministic) {
  const auto& scene = default_scene();
  std::vector<Sample> a;
  std::vector<Sample> b;
  for (auto* out : {&a, &b}) {
    ScriptedDevice device(press_over_tumour());
    Engine engine(scene, device);
    run_fast(engine, 2.0, [&](const Sample& s) { out->push_back(s); });
  }
  ASSERT_EQ(a.size(), 2001u);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].force, b[k].force);
    EXPECT_EQ(a[k].depth, b[k].depth);
  }
}

class FailingDevice final : public Device {
 public:
  explicit FailingDevice(Trajectory tr) : inner_(std::move(tr)) {}
  const DeviceCapabilities& capabilities() const override { return inner_.capabilities(); }
  DeviceStatus read(double t, DevicePose& pose) noexcept override {
    inner_.read(t, pose);
    return t >= fail_at_ ? DeviceStatus::Error : DeviceStatus::Ok;
  }
  DeviceStatus write_force(const Vec3& f) noexcept override { return inner_.write_force(f); }
  double fail_at_ = 0.8;

 private:
  ScriptedDevice inner_;
};

TEST(Engine, ADeviceErrorOrAPauseRampsTheForceToZero) {
  const auto& scene = default_scene();
  for (const bool pause : {false, true}) {
    FailingDevice device(press_over_tumour());
    if (pause) device.fail_at_ = 1e9;
    Engine engine(scene, device);
    double at_fault = 0.0;
    double after = -1.0;
    for (int k = 0; k <= 1000; ++k) {
      const double t = k * 1e-3;
      const Sample s = engine.tick(t, false, pause && t >= 0.8);
      if (k == 799) at_fault = Vec3(s.force[0], s.force[1], s.force[2]).norm();
      if (t >= 0.8) {
        EXPECT_TRUE(s.fault);
      }
      if (k == 800 + 50) after = Vec3(s.force[0], s.force[1], s.force[2]).norm();  // ramp_time 50 ms
    }
    EXPECT_GT(at_fault, 1.0) << "pressing when the fault comes";
    EXPECT_EQ(after, 0.0) << (pause ? "pause" : "device error");
  }
}

TEST(Engine, WithoutDynamicsAReleasedBodyIsAtRestAtOnce) {
  const auto& scene = default_scene();
  ScriptedDevice device(press_over_tumour());
  EngineOptions options;
  options.dynamics = false;
  Engine engine(scene, device, options);
  DrawnScene drawn(engine);
  int pressed = 0;
  for (int k = 0; k <= 2000; ++k) {  // ends outside the body
    engine.tick(k * 1e-3);
    drawn.follow(engine.last_touch());
    pressed += drawn.drawn(0).awake() ? 1 : 0;
  }
  EXPECT_GT(pressed, 100);
  EXPECT_EQ(drawn.drawn(0).max_displacement(), 0.0);
  EXPECT_FALSE(drawn.drawn(0).awake());
}

}  // namespace
}  // namespace palpa::engine

namespace palpa::engine {
namespace {

class NaNDevice final : public Device {
 public:
  const DeviceCapabilities& capabilities() const override { return inner_.capabilities(); }
  DeviceStatus read(double t, DevicePose& pose) noexcept override {
    inner_.read(t, pose);
    if (t >= 0.5) pose.position.x() = std::nan("");
    return DeviceStatus::Ok;  // the driver does not notice
  }
  DeviceStatus write_force(const Vec3& f) noexcept override { return inner_.write_force(f); }
  VirtualDevice inner_{0.0};
};

TEST(Engine, ANonFinitePoseIsAFaultNotAPosition) {
  NaNDevice device;
  device.inner_.set_target(Vec3(0.0245, 0.02, 0.030));
  Engine engine(default_scene(), device);
  Sample s;
  for (int k = 0; k <= 600; ++k) s = engine.tick(k * 1e-3);
  EXPECT_TRUE(s.fault);
  EXPECT_EQ(s.body, -1);
  EXPECT_EQ(s.force, (std::array<double, 3>{}));  // ramped to zero within 50 ms of the first NaN
  for (double x : s.position) EXPECT_TRUE(std::isfinite(x));
}

TEST(Engine, ALateTickCannotLetTheForceJump) {
  VirtualDevice device(0.0);
  EngineOptions options;
  options.safety.max_force_rate = 1000.0;  // 1 N per 1 ms tick
  Engine engine(default_scene(), device, options);
  device.set_target(Vec3(0.0245, 0.02, 0.06));  // above the body
  engine.tick(0.0);
  device.set_target(Vec3(0.0245, 0.02, 0.025));  // deep in, at once
  const Sample late = engine.tick(0.015);          // 15 ms late (under the 20 ms watchdog)
  const double f = std::sqrt(late.force[0] * late.force[0] + late.force[1] * late.force[1] + late.force[2] * late.force[2]);
  EXPECT_LE(f, 1.0 + 1e-12);  // one nominal period's worth of the rate limit, not 15
}

}  // namespace
}  // namespace palpa::engine
