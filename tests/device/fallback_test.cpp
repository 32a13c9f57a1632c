// Unplugging mid-session: the FallbackDevice under the engine (deterministic ticks) and
// under the live exercise (real haptic loop, session read back).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <random>
#include <thread>

#include "palpa/engine/engine.hpp"
#include "palpa/engine/fallback_device.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/live/live_exercise.hpp"
#include "unplug_devices.hpp"

namespace palpa::device {
namespace {

const std::string kDefaultCase = PALPA_SOURCE_DIR "/data/cases/default.json";

// 12 mm into the default case's body, over its tumour (as the engine tests press).
const Vec3 kPressed(0.0245, 0.02, 0.046 - 0.012);

TEST(FallbackDevice, AnUnplugRampsTheForceToZeroHoldsThePoseThenTheVirtualDeviceTakesOver) {
  const auto scene = scene::Scene::build(io::load_case(kDefaultCase), "default");
  test::UnpluggedAt primary(kPressed, 0.5);
  engine::VirtualDevice mouse(0.0);
  engine::FallbackDevice fallback(&primary, mouse, 0.1);
  engine::EngineOptions options;
  engine::Engine eng(scene, fallback, options);
  EXPECT_EQ(fallback.active_name(), "test SpaceMouse");

  double force_before = 0.0;
  double zero_at = -1.0;
  int k = 0;
  for (; k <= 800; ++k) {  // 0.8 s, nobody resumes: the fallback holds
    const double t = k / 1000.0;
    const auto s = eng.tick(t);
    const double force = Vec3(s.force[0], s.force[1], s.force[2]).norm();
    if (t < 0.5) {
      EXPECT_FALSE(s.fault);
      force_before = force;
    } else {
      EXPECT_TRUE(s.fault) << t;
      EXPECT_EQ(Vec3(s.position[0], s.position[1], s.position[2]), kPressed) << "held at the last pose";
      if (force == 0.0 && zero_at < 0.0) zero_at = t;
    }
  }
  EXPECT_GT(force_before, 1.0) << "pressing when the cable is pulled";
  ASSERT_GT(zero_at, 0.0) << "the force reached zero";
  EXPECT_LE(zero_at, 0.5 + options.safety.ramp_time + 0.002);
  EXPECT_EQ(primary.last_force_, Vec3::Zero()) << "the last force the primary got is none";
  ASSERT_TRUE(fallback.switched());
  EXPECT_EQ(fallback.switch_status(), engine::DeviceStatus::Disconnected);
  EXPECT_DOUBLE_EQ(fallback.switched_at(), 0.5);
  EXPECT_EQ(fallback.last_position(), kPressed);
  EXPECT_EQ(fallback.fault_message(), "test SpaceMouse: cable pulled");
  EXPECT_FALSE(fallback.on_fallback());

  // The GUI points the mouse's device at the last pose and lets it take over.
  mouse.set_target(fallback.last_position());
  fallback.resume();
  const auto s = eng.tick(++k / 1000.0);
  EXPECT_FALSE(s.fault);
  EXPECT_TRUE(fallback.on_fallback());
  EXPECT_EQ(fallback.active_name(), "virtual (mouse)");
  EXPECT_EQ(Vec3(s.position[0], s.position[1], s.position[2]), kPressed) << "no jump";
  // Force comes back through the rate limit (no jolt), to the mouse's device now.
  EXPECT_LE(Vec3(s.force[0], s.force[1], s.force[2]).norm(), options.safety.max_force_rate / 1000.0 + 1e-12);
  EXPECT_EQ(mouse.last_force(), Vec3(s.force[0], s.force[1], s.force[2]));
}

TEST(FallbackDevice, TheHoldLastsAtLeastTheHoldTimeEvenWhenResumedAtOnce) {
  test::UnpluggedAt primary(Vec3(0, 0, 1), 0.010);
  engine::VirtualDevice mouse(0.0);
  engine::FallbackDevice fallback(&primary, mouse, 0.1);
  engine::DevicePose pose;
  EXPECT_EQ(fallback.read(0.0, pose), engine::DeviceStatus::Ok);
  EXPECT_EQ(fallback.read(0.010, pose), engine::DeviceStatus::Disconnected);
  mouse.set_target(fallback.last_position());
  fallback.resume();
  EXPECT_EQ(fallback.read(0.109, pose), engine::DeviceStatus::Disconnected);
  EXPECT_EQ(pose.position, Vec3(0, 0, 1));
  EXPECT_EQ(fallback.read(0.110, pose), engine::DeviceStatus::Ok);
  EXPECT_EQ(pose.position, Vec3(0, 0, 1));
  // Without a primary the virtual device is the device from the start.
  engine::FallbackDevice plain(nullptr, mouse);
  EXPECT_TRUE(plain.on_fallback());
  EXPECT_EQ(plain.read(0.0, pose), engine::DeviceStatus::Ok);
}

class ScratchDir {
 public:
  ScratchDir() {
    std::random_device entropy;
    path_ = std::filesystem::temp_directory_path() / ("palpa-device-" + std::to_string(entropy()));
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

bool run_until(live::LiveExercise& live, const std::function<bool()>& done, double seconds = 10.0) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    live.update();
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

TEST(LiveExerciseUnplug, TheSessionGoesOnWithTheMouseAndReadsBackComplete) {
  ScratchDir dir;
  live::LiveOptions o;
  o.trainee = "t1";
  o.seed = 7;
  o.session_path = dir / "unplug.palpa";
  o.realtime.request_fifo = false;
  auto primary = std::make_shared<test::UnpluggedAt>(Vec3::Zero(), 0.3);
  o.device = primary;
  live::LiveExercise live(io::load_case(kDefaultCase), kDefaultCase, o);
  // Placed over the first body: the middle of its rest box, at its top.
  const auto& bounds = live.scene().body(0).bounds;
  EXPECT_NEAR(primary->placed_.z(), bounds.hi.z(), 1e-12);
  EXPECT_NEAR(primary->placed_.x(), 0.5 * (bounds.lo.x() + bounds.hi.x()), 1e-12);
  EXPECT_EQ(live.device_name(), "test SpaceMouse");
  live.start();
  ASSERT_TRUE(run_until(live, [&] { return live.device_switched(); }));
  EXPECT_EQ(live.device_message(),
            "test SpaceMouse disconnected: using the mouse (test SpaceMouse: cable pulled)");
  // The trainee goes on with the mouse: the probe follows it from where the device left it.
  ASSERT_TRUE(run_until(live, [&] { return live.device_name() == "virtual (mouse)"; }));
  const Vec3 target = primary->placed_ + Vec3(0.0, 0.0, 0.02);
  live.set_probe_target(target);
  ASSERT_TRUE(run_until(live, [&] {
    const auto& p = live.snapshot().probe;
    return (Vec3(p[0], p[1], p[2]) - target).norm() < 1e-4;
  }));
  live.finish();

  const auto s = session::read_session(o.session_path);
  EXPECT_TRUE(s.complete);
  EXPECT_EQ(s.info.device, "test SpaceMouse");
  bool zero_after = false, ok_after = false;
  for (const auto& sample : s.samples) {
    if (sample.t < 0.3) {
      EXPECT_FALSE(sample.fault) << sample.t;
    } else if (sample.fault && sample.force == std::array<double, 3>{0, 0, 0}) {
      zero_after = true;
    } else if (!sample.fault && sample.t > 0.4) {
      ok_after = true;
    }
  }
  EXPECT_TRUE(zero_after) << "the force went to zero after the unplug";
  EXPECT_TRUE(ok_after) << "the session went on with the virtual device";
  std::vector<std::string> kinds;
  for (const auto& e : s.events) kinds.emplace_back(session::to_string(e.kind));
  EXPECT_EQ(kinds, (std::vector<std::string>{"start", "pause", "resume", "end"}));
  // The haptic time of the unplug: the first tick at or after 0.3 s that saw it. A loaded
  // machine (ctest -j2 beside the GUI tests) can delay that tick's detection by a few ticks.
  EXPECT_GE(s.events[1].t, 0.3 - 0.0015);
  EXPECT_LE(s.events[1].t, 0.3 + 0.005);
  EXPECT_EQ(s.events[1].note.rfind("device: test SpaceMouse disconnected: using the mouse", 0), 0u) << s.events[1].note;
  EXPECT_EQ(s.events[2].note, "device: continuing with virtual (mouse)");
  EXPECT_NE(s.events[3].note.find("(device: test SpaceMouse disconnected"), std::string::npos) << s.events[3].note;
}

}  // namespace
}  // namespace palpa::device
