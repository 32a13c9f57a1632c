// The haptic thread's query must not allocate: Scene::probe is run with a counting global
// operator new (this test binary only) and must not touch it.
#include <gtest/gtest.h>


#include <atomic>
#include <chrono>
#include <cstdlib>
#include <memory>
#include <new>
#include <thread>

#include "palpa/deform/deformed_body.hpp"
#include "palpa/engine/drawn_scene.hpp"
#include "palpa/engine/engine.hpp"
#include "palpa/engine/realtime_loop.hpp"
#include "palpa/engine/virtual_device.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/scene/scene.hpp"
#include "../support/counting_allocator.hpp"


namespace palpa::scene {
namespace {

// The default case (tissue and tumour in Pa) pressed by the flat pad or the rounded finger.
Scene default_scene(mat::Indenter indenter) {
  auto file = io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json");
  file.indenter = indenter;
  return Scene::build(file, "default.json");
}

class QueryAllocation : public ::testing::TestWithParam<mat::Indenter> {};

TEST_P(QueryAllocation, AQueryAllocatesNothingWarmOrColdWithShearAndTumours) {
  const auto scene = default_scene(GetParam());
  ASSERT_FALSE(scene.body(0).tumours.empty());
  auto state = scene.make_state();
  ProbeOptions fast;
  ProbeOptions bisect;
  bisect.method = FootPointMethod::Bisect;
  const long before = palpa::test::allocations();
  double checksum = 0.0;
  int under_skeleton = 0;  // presses read along the column (docs/model.md)
  for (int k = 0; k < 2000; ++k) {
    // In and out of the body (cold starts after leaving its box), over the tumour, far away.
    const double t = 0.01 * k;
    const Vec3 q(0.06 * std::sin(t), 0.07 * std::cos(0.7 * t), 0.03 + 0.04 * std::sin(2.3 * t));
    const auto r = scene.probe(k % 50 == 0 ? Vec3(5.0, 5.0, 5.0) : q, state, k % 7 == 0 ? bisect : fast);
    checksum += r.force.total.norm();
    under_skeleton += r.body >= 0 && r.contact.depth > r.contact.radius ? 1 : 0;
  }
  EXPECT_EQ(palpa::test::allocations() - before, 0);
  EXPECT_GT(under_skeleton, 50);  // the column's search ran too
  EXPECT_GT(checksum, 0.0);  // some queries were in contact

  // The counter does see allocations: a fresh state allocates.
  const long control = palpa::test::allocations();
  const auto fresh = scene.make_state();
  EXPECT_GT(palpa::test::allocations(), control);
  EXPECT_EQ(fresh.warm.size(), scene.size());
}

INSTANTIATE_TEST_SUITE_P(ProbeRealTime, QueryAllocation, ::testing::Values(mat::Indenter::Pad, mat::Indenter::Finger),
                         [](const auto& param_info) { return param_info.param == mat::Indenter::Pad ? "Pad" : "Finger"; });

TEST(ProbeRealTime, PressAndSpringStepsAllocateNothingInEitherScheme) {
  const auto scene = Scene::build(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"), "default.json");
  for (const bool dynamics : {true, false}) {
    deform::DeformOptions opts;
    opts.dynamics = dynamics;
    deform::DeformedBody drawn(scene.body(0).body, opts);
    auto state = scene.make_state();
    ProbeOptions options;
    options.remember_side = true;
    drawn.step(1e-3);  // sizes the per-step tables for this dt before counting
    const long before = palpa::test::allocations();
    int presses = 0;
    for (int k = 0; k < 3000; ++k) {
      const double t = 0.002 * k;
      const Vec3 q(0.04 * std::sin(t), 0.05 * std::cos(0.7 * t), 0.035 + 0.03 * std::sin(3.1 * t));
      const auto r = scene.probe(q, state, options);
      if (r.body == 0) {
        drawn.press(r.contact, q);
        ++presses;
      } else {
        drawn.release();
      }
      drawn.step(1e-3);
    }
    EXPECT_EQ(palpa::test::allocations() - before, 0) << (dynamics ? "with dynamics" : "without dynamics");
    EXPECT_GT(presses, 100);
  }
}

TEST(ProbeRealTime, TheEngineTickAllocatesNothing) {
  const auto scene = Scene::build(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"), "default.json");
  engine::VirtualDevice device(0.02);
  engine::Engine eng(scene, device);
  eng.tick(0.0);  // sizes the spring tables for the tick length
  const long before = palpa::test::allocations();
  int contacts = 0;
  for (int k = 1; k < 4000; ++k) {
    const double t = k * 1e-3;
    device.set_target(Vec3(0.04 * std::sin(t), 0.05 * std::cos(0.7 * t), 0.035 + 0.03 * std::sin(3.1 * t)));
    const auto s = eng.tick(t, false, k > 3500);  // the last half second paused: ramp to zero
    contacts += s.body >= 0 ? 1 : 0;
  }
  EXPECT_EQ(palpa::test::allocations() - before, 0);
  EXPECT_GT(contacts, 100);
}

TEST(ProbeRealTime, TheDrawnBodiesFollowTheTicksAllocatingNothing) {
  // The display half: the refined drawn nets pressed, released and springing back.
  const auto scene = Scene::build(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"), "default.json");
  engine::VirtualDevice device(0.02);
  engine::Engine eng(scene, device);
  engine::DrawnScene drawn(eng);
  ASSERT_GT(drawn.drawn(0).top().rows(), scene.body(0).body.top().rows()) << "refined for display";
  eng.tick(0.0);
  drawn.follow(eng.last_touch());  // sizes the spring tables for the tick length
  const long before = palpa::test::allocations();
  int awake = 0;
  for (int k = 1; k < 4000; ++k) {
    const double t = k * 1e-3;
    device.set_target(Vec3(0.04 * std::sin(t), 0.05 * std::cos(0.7 * t), 0.035 + 0.03 * std::sin(3.1 * t)));
    eng.tick(t);
    drawn.follow(eng.last_touch(), k % 500 == 0 ? 30 : 1);  // now and then after lost touches
    awake += drawn.drawn(0).awake() ? 1 : 0;
  }
  EXPECT_EQ(palpa::test::allocations() - before, 0);
  EXPECT_GT(awake, 100);
}

TEST(ProbeRealTime, TheRunningHapticAndDisplayThreadsAllocateNothing) {
  // Counted while both of RealtimeLoop's threads run and this thread only moves the target:
  // any allocation in that time is theirs.
  const auto scene = Scene::build(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"), "default.json");
  engine::VirtualDevice device(0.01);
  engine::Engine eng(scene, device);
  auto loop = std::make_unique<engine::RealtimeLoop>(eng);
  device.set_target(Vec3(0.0, 0.0, 0.08));
  loop->start();
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // first ticks size their tables
  const long before = palpa::test::allocations();
  for (int k = 0; k < 60; ++k) {
    const double t = 0.01 * k;
    device.set_target(Vec3(0.03 * std::sin(3 * t), 0.02 * std::cos(2 * t), 0.036 - 0.008 * std::sin(7 * t)));
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const long during = palpa::test::allocations() - before;
  loop->stop();
  EXPECT_EQ(during, 0);
  loop->update_snapshot();
  EXPECT_GT(loop->snapshot().tick, 500u) << "the loop ticked all along";
}

}  // namespace
}  // namespace palpa::scene
