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
  const double span = samples.back().t - samples.front().t;
  EXPECT_NEAR(static_cast<double>(samples.size()) / span, 1000.0, 150.0);
  const auto& stats = loop.stats();
  EXPECT_EQ(stats.ticks(), samples.size());
  EXPECT_NEAR(stats.mean_period(), 1e-3, 2e-4);
  EXPECT_GT(stats.compute_percentile(0.5), 0.0);
  EXPECT_LT(stats.compute_percentile(0.5), 1e-3);  // a tick fits its period with room to spare
}

}  // namespace
}  // namespace palpa::engine
