// read() and write_force() run in the haptic thread: the drivers (SpaceMouse, Falcon,
// replay) and the fallback around them must not allocate there. Counting operator new of
// this binary only.
#include <gtest/gtest.h>

#include <memory>

#include "../core/support/counting_allocator.hpp"
#include "fake_transports.hpp"
#include "palpa/device/falcon_device.hpp"
#include "palpa/device/replay_device.hpp"
#include "palpa/device/spacemouse_device.hpp"
#include "palpa/engine/fallback_device.hpp"
#include "unplug_devices.hpp"

namespace palpa::device {
namespace {


TEST(DeviceRealTime, SpaceMouseReadAndWriteAllocateNothingInEitherMode) {
  for (const auto mode : {SpaceMouseMode::Position, SpaceMouseMode::Rate}) {
    SpaceMouseOptions options;
    options.mode = mode;
    SpaceMouseDevice device(std::make_unique<test::FakeHid>(std::vector<std::vector<std::uint8_t>>{
                                {0x01, 0x5E, 0x01, 0x10, 0x00, 0xA2, 0xFE}, {0x03, 0x01}}),
                            ReportLayout::Split, "SpaceNavigator", options);
    device.poll(0);
    device.poll(0);
    engine::DevicePose pose;
    const long before = palpa::test::allocations();
    double sum = 0.0;
    for (int k = 0; k < 2000; ++k) {
      device.read(k * 0.001, pose);
      device.write_force(Vec3(0, 0, 0.001 * k));
      sum += pose.position.norm();
    }
    EXPECT_EQ(palpa::test::allocations() - before, 0);
    EXPECT_GT(sum, 0.0);
  }
}

TEST(DeviceRealTime, FalconReadAndWriteAllocateNothing) {
  // Boot the fake first: the device then finds the firmware running (no file needed).
  const std::vector<std::uint8_t> firmware(256, 0x5A);
  auto fake = std::make_unique<test::FakeFalcon>(firmware.size());
  falcon::boot(*fake, firmware, "falcon:1-1");
  fake->encoder = {100, -200, 300};
  auto* raw = fake.get();
  FalconDevice device(std::move(fake), "falcon:1-1");
  EXPECT_EQ(device.connect(), 0);
  for (int k = 0; k < 4; ++k) device.exchange();  // homed
  ASSERT_TRUE(device.homed());
  engine::DevicePose pose;
  ASSERT_EQ(device.read(0.0, pose), engine::DeviceStatus::Ok);
  Vec3 previous = pose.position;
  long allocated = 0;
  int moves = 0;
  for (int k = 1; k <= 2000; ++k) {
    // The grip moves and the I/O side exchanges a packet (the fake firmware allocates, so
    // only read() and write_force() are counted): read() solves the forward kinematics of
    // a new reading every tick.
    raw->encoder[0] = static_cast<std::int16_t>(100 + k % 50);
    ASSERT_TRUE(device.exchange());
    const long before = palpa::test::allocations();
    const auto status = device.read(k * 0.001, pose);
    device.write_force(Vec3(0.001 * (k % 100), 0, 2.0));
    allocated += palpa::test::allocations() - before;
    ASSERT_EQ(status, engine::DeviceStatus::Ok) << k;
    if (pose.position != previous) ++moves;
    previous = pose.position;
  }
  EXPECT_EQ(allocated, 0);
  EXPECT_EQ(moves, 2000) << "every reading moved the probe: read() saw each new encoder count";
  // Encoders no arm can produce: the misses are counted and the Error raised in the haptic
  // thread, without a word allocated (fault_message() words it later, elsewhere).
  raw->encoder = {3000, -3000, 3000};
  ASSERT_TRUE(device.exchange());
  const long before = palpa::test::allocations();
  engine::DeviceStatus status = engine::DeviceStatus::Ok;
  for (int k = 0; k < 60 && status == engine::DeviceStatus::Ok; ++k) {
    status = device.read(3.0 + k * 0.001, pose);
    device.write_force(Vec3(0, 0, 2.0));
  }
  EXPECT_EQ(palpa::test::allocations() - before, 0);
  EXPECT_EQ(status, engine::DeviceStatus::Error);
  EXPECT_FALSE(device.fault_message().empty());
}

TEST(DeviceRealTime, ReplayAndTheFallbackSwitchAllocateNothing) {
  session::Session s;
  for (int k = 0; k < 100; ++k) {
    engine::Sample sample;
    sample.t = 0.001 * k;
    sample.position = {0.001 * k, 0.0, 0.0};
    s.samples.push_back(sample);
  }
  ReplayDevice replay(s, "r.palpa");
  test::UnpluggedAt primary(Vec3(0, 0, 1), 0.05);
  engine::VirtualDevice mouse(0.02);
  engine::FallbackDevice fallback(&primary, mouse, 0.01);
  mouse.set_target(Vec3(0, 0, 1));
  fallback.resume();  // before the switch: the virtual device takes over as soon as the hold ends
  engine::DevicePose pose;
  const long before = palpa::test::allocations();
  for (int k = 0; k < 200; ++k) {
    replay.read(k * 0.001, pose);
    replay.write_force(Vec3(0, 0, 1));
    fallback.read(k * 0.001, pose);  // primary, switch, hold, virtual device
    fallback.write_force(Vec3(0, 0, 1));
  }
  EXPECT_EQ(palpa::test::allocations() - before, 0);
  EXPECT_TRUE(fallback.on_fallback());
}

}  // namespace
}  // namespace palpa::device
