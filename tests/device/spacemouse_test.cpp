// SpaceMouse: report parsing from recorded report bytes (both layouts), and the device's
// position and rate control, dead zone and unplugging, fed by a fake HID transport.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <thread>

#include "fake_transports.hpp"
#include "palpa/device/device_ids.hpp"
#include "palpa/device/spacemouse_device.hpp"
#include "palpa/device/spacemouse_report.hpp"

namespace palpa::device {
namespace {

using Bytes = std::vector<std::uint8_t>;

ReportOutcome parse(ReportLayout layout, const Bytes& report, SpaceMouseState& state) {
  return parse_report(layout, report.data(), report.size(), state);
}

TEST(SpaceMouseReport, LayoutsFollowTheVendorExceptTheCompact) {
  EXPECT_EQ(report_layout(0x046D, 0xC626), ReportLayout::Split);
  EXPECT_EQ(report_layout(0x046D, 0xC62B), ReportLayout::Split);
  EXPECT_EQ(report_layout(0x256F, 0xC635), ReportLayout::Split);  // the Compact keeps the split
  for (const std::uint16_t product : std::array<std::uint16_t, 4>{0xC62E, 0xC631, 0xC632, 0xC652}) {
    EXPECT_EQ(report_layout(0x256F, product), ReportLayout::SixAxis) << std::hex << product;
  }
  ASSERT_NE(find_spacemouse(0x046D, 0xC62B), nullptr);
  EXPECT_STREQ(find_spacemouse(0x046D, 0xC62B)->model, "SpaceMouse Pro");
  EXPECT_EQ(find_spacemouse(0x046D, 0xC52B), nullptr);  // a Logitech receiver is not a SpaceMouse
}

TEST(SpaceMouseReport, SplitLayoutTranslationRotationAndButtons) {
  SpaceMouseState state;
  // A SpaceNavigator pushed right, pulled toward the user and pressed down hard:
  // X = 0x000C = 12, Y = 0xFFF4 = -12, Z = 0x015E = 350 (little-endian int16).
  auto out = parse(ReportLayout::Split, {0x01, 0x0C, 0x00, 0xF4, 0xFF, 0x5E, 0x01}, state);
  EXPECT_EQ(out.kind, ReportKind::Translation);
  EXPECT_EQ(state.axes[0], 12);
  EXPECT_EQ(state.axes[1], -12);
  EXPECT_EQ(state.axes[2], 350);
  // Twisted: Rx = 0xFEA2 = -350, Ry = 0x0001 = 1, Rz = 0x8000 = -32768 (the sign bit alone).
  out = parse(ReportLayout::Split, {0x02, 0xA2, 0xFE, 0x01, 0x00, 0x00, 0x80}, state);
  EXPECT_EQ(out.kind, ReportKind::Rotation);
  EXPECT_EQ(state.axes[3], -350);
  EXPECT_EQ(state.axes[4], 1);
  EXPECT_EQ(state.axes[5], -32768);
  EXPECT_EQ(state.axes[0], 12);  // the translation stays what report 1 said
  // Buttons 1 and 2 (SpaceNavigator: two buttons, one byte), then a SpaceMouse Pro's
  // four-byte mask with bits 0, 12 and 31.
  out = parse(ReportLayout::Split, {0x03, 0x03}, state);
  EXPECT_EQ(out.kind, ReportKind::Buttons);
  EXPECT_EQ(state.buttons, 0x3u);
  out = parse(ReportLayout::Split, {0x03, 0x01, 0x10, 0x00, 0x80, 0x00, 0x00}, state);
  EXPECT_EQ(state.buttons, 0x80001001u);
  out = parse(ReportLayout::Split, {0x03, 0x00}, state);
  EXPECT_EQ(state.buttons, 0u);
}

TEST(SpaceMouseReport, SixAxisLayoutCarriesEverythingInReportOne) {
  SpaceMouseState state;
  // SpaceMouse Wireless: X=-1 (0xFFFF), Y=256 (0x0100), Z=-256 (0xFF00), Rx=100, Ry=-100, Rz=0.
  const auto out = parse(ReportLayout::SixAxis,
                         {0x01, 0xFF, 0xFF, 0x00, 0x01, 0x00, 0xFF, 0x64, 0x00, 0x9C, 0xFF, 0x00, 0x00}, state);
  EXPECT_EQ(out.kind, ReportKind::SixAxes);
  const std::array<std::int16_t, 6> expected{-1, 256, -256, 100, -100, 0};
  EXPECT_EQ(state.axes, expected);
}

TEST(SpaceMouseReport, ShortAndUnknownReportsAreRejectedOrIgnoredWithAReason) {
  SpaceMouseState state;
  state.axes = {1, 2, 3, 4, 5, 6};
  const auto before = state.axes;
  auto out = parse(ReportLayout::Split, {0x01, 0x0C, 0x00, 0xF4, 0xFF}, state);
  EXPECT_EQ(out.kind, ReportKind::Bad);
  EXPECT_STREQ(out.message.data(), "report 1 has 5 bytes, translation needs 7");
  // A split-layout translation report is too short for the six-axis layout.
  out = parse(ReportLayout::SixAxis, {0x01, 0x0C, 0x00, 0xF4, 0xFF, 0x5E, 0x01}, state);
  EXPECT_STREQ(out.message.data(), "report 1 has 7 bytes, the six-axis layout needs 13");
  out = parse(ReportLayout::Split, {0x02, 0x01}, state);
  EXPECT_STREQ(out.message.data(), "report 2 has 2 bytes, rotation needs 7");
  out = parse(ReportLayout::Split, {0x03}, state);
  EXPECT_STREQ(out.message.data(), "report 3 has 1 bytes, a button mask needs 2");
  out = parse(ReportLayout::Split, {}, state);
  EXPECT_EQ(out.kind, ReportKind::Bad);
  EXPECT_STREQ(out.message.data(), "empty report");
  EXPECT_EQ(state.axes, before);  // nothing half-read
  // The wireless models' battery report (id 0x17) is not for the probe.
  out = parse(ReportLayout::SixAxis, {0x17, 0x5A}, state);
  EXPECT_EQ(out.kind, ReportKind::Other);
  EXPECT_EQ(state.axes, before);
}

std::unique_ptr<SpaceMouseDevice> make(std::vector<Bytes> reports, const SpaceMouseOptions& options,
                                       bool unplug_at_end = false) {
  auto device = std::make_unique<SpaceMouseDevice>(std::make_unique<test::FakeHid>(std::move(reports), unplug_at_end),
                                                   ReportLayout::Split, "SpaceNavigator", options);
  device->place_workspace(palpa::Vec3(0.1, 0.2, 0.3), 1.0);
  return device;
}

TEST(SpaceMouseDevice, PositionControlMapsTheDeflectionPastTheDeadZoneIntoTheWorkspace) {
  SpaceMouseOptions options;
  options.mode = SpaceMouseMode::Position;
  options.dead_zone = 50;
  options.full_scale = 350.0;
  options.workspace_radius = 0.06;
  // X = 200 (past the dead zone: (200 - 50) / 300 = 0.5), Y = 30 (inside it), Z = 350 (full, pushed down).
  auto device = make({{0x01, 0xC8, 0x00, 0x1E, 0x00, 0x5E, 0x01}, {0x03, 0x02}}, options);
  engine::DevicePose pose;
  ASSERT_EQ(device->read(0.0, pose), engine::DeviceStatus::Ok);
  EXPECT_EQ(pose.position, palpa::Vec3(0.1, 0.2, 0.3));  // nothing read yet: the centre
  ASSERT_TRUE(device->poll(0));
  ASSERT_TRUE(device->poll(0));
  ASSERT_EQ(device->read(0.001, pose), engine::DeviceStatus::Ok);
  EXPECT_NEAR(pose.position.x(), 0.1 + 0.06 * 0.5, 1e-15);
  EXPECT_NEAR(pose.position.y(), 0.2, 1e-15);
  EXPECT_NEAR(pose.position.z(), 0.3 - 0.06, 1e-15);  // pushing the cap down lowers the probe
  EXPECT_EQ(pose.buttons, 0x2u);
  EXPECT_FALSE(device->capabilities().force_output);
  EXPECT_EQ(device->write_force(palpa::Vec3(0, 0, 2.5)), engine::DeviceStatus::Ok);
  EXPECT_EQ(device->last_force(), palpa::Vec3(0, 0, 2.5));  // shown, not felt
}

TEST(SpaceMouseDevice, RateControlIntegratesAVelocityAndStaysInTheWorkspace) {
  SpaceMouseOptions options;
  options.mode = SpaceMouseMode::Rate;
  options.dead_zone = 0;
  options.full_scale = 350.0;
  options.max_speed = 0.05;
  options.workspace_radius = 0.06;
  // Full deflection to the right (X = 350): 0.05 m/s.
  auto device = make({{0x01, 0x5E, 0x01, 0x00, 0x00, 0x00, 0x00}}, options);
  ASSERT_TRUE(device->poll(0));
  engine::DevicePose pose;
  device->read(0.0, pose);
  for (int k = 1; k <= 1000; ++k) device->read(0.001 * k, pose);
  EXPECT_NEAR(pose.position.x(), 0.1 + 0.05, 1e-12);  // 1 s at 0.05 m/s
  for (int k = 1001; k <= 3000; ++k) device->read(0.001 * k, pose);
  EXPECT_NEAR(pose.position.x(), 0.1 + 0.06, 1e-12);  // held at the workspace's edge
  EXPECT_NEAR(pose.position.y(), 0.2, 1e-15);
}

TEST(SpaceMouseDevice, OddReportsAreCountedAndAnUnplugIsDisconnectedWithAMessage) {
  auto device = make({{0x01, 0x0C}, {0x01, 0x0C, 0x00, 0x00, 0x00, 0x00, 0x00}}, {}, true);
  EXPECT_TRUE(device->poll(0));
  EXPECT_EQ(device->bad_reports(), 1u);
  EXPECT_EQ(device->last_bad_report(), "SpaceNavigator: report 1 has 2 bytes, translation needs 7");
  EXPECT_TRUE(device->poll(0));
  engine::DevicePose pose;
  EXPECT_EQ(device->read(0.0, pose), engine::DeviceStatus::Ok);
  EXPECT_TRUE(device->fault_message().empty());
  EXPECT_FALSE(device->poll(0));  // the cable is pulled
  EXPECT_EQ(device->read(0.001, pose), engine::DeviceStatus::Disconnected);
  EXPECT_EQ(device->fault_message(), "SpaceNavigator: read failed (unplugged?): No such device");
}

TEST(SpaceMouseDevice, TheIoThreadDeliversReportsAndStops) {
  SpaceMouseOptions options;
  options.mode = SpaceMouseMode::Position;
  options.dead_zone = 0;
  options.full_scale = 350.0;
  options.workspace_radius = 0.06;
  {
    // X = 350, full deflection right: the I/O thread's report reaches read() as the
    // workspace centre plus the radius. (A bounded wait; nothing is timed.)
    auto device = make({{0x01, 0x5E, 0x01, 0x00, 0x00, 0x00, 0x00}}, options);
    engine::DevicePose pose;
    ASSERT_EQ(device->read(0.0, pose), engine::DeviceStatus::Ok);
    ASSERT_EQ(pose.position, palpa::Vec3(0.1, 0.2, 0.3));  // nothing read yet
    device->start();
    for (int k = 0; k < 10000 && pose.position.x() == 0.1; ++k) {
      ASSERT_EQ(device->read(0.0, pose), engine::DeviceStatus::Ok);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    device->stop();  // returns: the thread is told to stop and joined
    EXPECT_NEAR(pose.position.x(), 0.1 + 0.06, 1e-15) << "the report reached read()";
    EXPECT_NEAR(pose.position.y(), 0.2, 1e-15);
    EXPECT_NEAR(pose.position.z(), 0.3, 1e-15);
  }
  auto device = make({{0x01, 0x5E, 0x01, 0x00, 0x00, 0x00, 0x00}}, options, true);
  device->start();
  engine::DevicePose pose;
  // The fake unplugs after its one report: the thread ends by itself; wait for it.
  for (int k = 0; k < 2000 && device->read(0.0, pose) == engine::DeviceStatus::Ok; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  device->stop();
  EXPECT_EQ(device->read(0.0, pose), engine::DeviceStatus::Disconnected);
}

}  // namespace
}  // namespace palpa::device
