// The haptic thread: paced ticks, samples handed over, statistics, and the force ramping
// to zero on pause and on stop.
#include "palpa/engine/realtime_loop.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <vector>

#include "palpa/engine/virtual_device.hpp"
#include "palpa/io/case_file.hpp"

namespace palpa::engine {
namespace {

double norm(const std::array<double, 3>& f) { return std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]); }

TEST(RealtimeLoop, TicksAtItsRateHandsOverEverySampleAndRampsToZeroOnStop) {
  const auto scene = scene::Scene::build(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"), "default");
  VirtualDevice device(0.0);
  device.set_target(Vec3(0.0245, 0.02, 0.030));  // pressing 16 mm into the default case
  Engine engine(scene, device);
  RealtimeLoop loop(engine);
  const std::string scheduling = loop.start();
  EXPECT_NE(scheduling.find("SCHED_FIFO"), std::string::npos) << scheduling;  // granted or refused, never silent
  std::vector<Sample> samples;
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(400);
  Sample s;
  while (std::chrono::steady_clock::now() < until) {
    while (loop.pop_sample(s)) samples.push_back(s);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  loop.pause(true);  // pause: the force ramps to zero while the probe stays in
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  while (loop.pop_sample(s)) samples.push_back(s);
  ASSERT_FALSE(samples.empty());
  EXPECT_EQ(norm(samples.back().force), 0.0);
  EXPECT_TRUE(samples.back().fault);
  EXPECT_EQ(samples.back().body, 0);
  loop.pause(false);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  loop.stop();
  while (loop.pop_sample(s)) samples.push_back(s);
  EXPECT_EQ(norm(samples.back().force), 0.0) << "stop ramps the force to zero before the thread ends";

  // Pressing before the pause: a real force was sent.
  double peak = 0.0;
  for (const auto& x : samples) peak = std::max(peak, norm(x.force));
  EXPECT_GT(peak, 1.0);
  // Every tick arrived, in order, about once per millisecond.
  for (std::size_t k = 1; k < samples.size(); ++k) ASSERT_GT(samples[k].t, samples[k - 1].t);
  EXPECT_EQ(loop.dropped_samples(), 0u);
  const auto& stats = loop.stats();
  EXPECT_EQ(stats.ticks(), samples.size());
  EXPECT_GT(stats.compute_percentile(0.5), 0.0);
  // The pace itself is only promised with real-time priority: without it a loaded machine
  // may preempt the thread for longer than a period.
  if (loop.realtime_priority()) {
    const double span = samples.back().t - samples.front().t;
    EXPECT_NEAR(static_cast<double>(samples.size()) / span, 1000.0, 150.0);
    EXPECT_NEAR(stats.mean_period(), 1e-3, 2e-4);
    EXPECT_LT(stats.compute_percentile(0.5), 1e-3);  // a tick fits its period with room to spare
  }
}

}  // namespace
}  // namespace palpa::engine

namespace palpa::engine {
namespace {

TEST(RealtimeLoop, TheGuiReadsWholeSnapshotsWhileTheBodyDeformsAndCommandsArrive) {
  const auto scene = scene::Scene::build(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"), "default");
  VirtualDevice device(0.01);
  Engine engine(scene, device);
  RealtimeLoop loop(engine);
  loop.start();
  std::uint64_t last_tick = 0;
  int snapshots = 0;
  int deformed = 0;
  const double rest_sum = [&] {
    double sum = 0.0;
    for (double x : scene.body(0).body.top().control()) sum += x;
    for (double x : scene.body(0).body.bottom().control()) sum += x;
    return sum;
  }();
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < 400; ++k) {  // the "GUI": 0.4 s of moving the mouse and reading
    const double t = 0.001 * k;
    device.set_target(Vec3(0.02 * std::sin(20 * t), 0.01, 0.035 - 0.01 * std::sin(10 * t)));
    if (k == 150) {
      EXPECT_TRUE(loop.send({Command::Kind::Shear, false}));
    }
    if (k == 250) {
      EXPECT_TRUE(loop.send({Command::Kind::Pause, false}));
    }
    if (loop.update_snapshot()) {
      const auto& s = loop.snapshot();
      ++snapshots;
      // Whole: the contents add up to what the haptic thread summed when it wrote them.
      EXPECT_EQ(s.contents_sum(), s.checksum) << "torn snapshot at tick " << s.tick;
      EXPECT_GT(s.tick, last_tick);
      last_tick = s.tick;
      if (std::abs(s.checksum - rest_sum) > 1e-9) ++deformed;
    }
    std::this_thread::sleep_until(start + std::chrono::microseconds(1000 * (k + 1)));
  }
  loop.stop();
  EXPECT_GT(snapshots, 20);  // about 125 per second were published
  EXPECT_GT(deformed, 5);    // and they show the body pressed in
  EXPECT_FALSE(engine.options().shear);  // the command reached the engine
}

// A device that stalls once (as a blocked driver would, or a loaded machine): a stall is not
// a fault. The tick after it is marked overrun, computes the force afresh where the probe
// is, and the force is held, not ramped to zero and back.
class StallingDevice final : public Device {
 public:
  const DeviceCapabilities& capabilities() const override { return inner_.capabilities(); }
  DeviceStatus read(double t, DevicePose& pose) noexcept override {
    if (t > 0.15 && !stalled_) {
      stalled_ = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(60));
    }
    return inner_.read(t, pose);
  }
  DeviceStatus write_force(const Vec3& f) noexcept override { return inner_.write_force(f); }
  VirtualDevice inner_{0.0};
  bool stalled_ = false;
};

TEST(RealtimeLoop, AStallIsMarkedAndHoldsTheForce) {
  const auto scene = scene::Scene::build(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"), "default");
  StallingDevice device;
  device.inner_.set_target(Vec3(0.0245, 0.02, 0.030));
  Engine engine(scene, device);
  RealtimeLoop loop(engine);
  loop.start();
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  loop.update_snapshot();
  const auto events = loop.snapshot().events;
  loop.stop();
  std::vector<Sample> samples;
  Sample s;
  while (loop.pop_sample(s)) samples.push_back(s);
  ASSERT_FALSE(samples.empty());
  // The tick after the stall: the one after the largest gap in time.
  std::size_t after = 1;
  for (std::size_t k = 1; k < samples.size(); ++k) {
    if (samples[k].t - samples[k - 1].t > samples[after].t - samples[after - 1].t) after = k;
  }
  ASSERT_GE(samples[after].t - samples[after - 1].t, 0.05) << "the 60 ms stall shows as a gap";
  ASSERT_GE(after, 2u);
  ASSERT_LT(after + 5, samples.size());
  EXPECT_TRUE(samples[after].overrun) << "the tick after a 60 ms stall is marked";
  EXPECT_FALSE(samples[after].fault) << "a stall is not a device fault";
  const double held = norm(samples[after - 2].force);
  EXPECT_GT(held, 1.0);
  for (std::size_t k = after; k < after + 5; ++k) EXPECT_NEAR(norm(samples[k].force), held, 0.05 * held) << k;
  EXPECT_NEAR(events.last_stall, samples[after].t, 1e-9) << "the snapshot tells the GUI";
  EXPECT_LT(events.last_device_fault, 0.0);
  EXPECT_GE(loop.stats().missed(), 1u);  // and the statistics say a deadline was missed
}

}  // namespace
}  // namespace palpa::engine
