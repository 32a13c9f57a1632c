// A Falcon that fails: whatever way it goes (silent firmware, failing transfers, encoders no
// arm can produce, the I/O thread ending), the motors' last command is zero torque, and the
// fault has a reason. Homing: no kinematics on counts that mean nothing yet. A firmware that
// is running already is not uploaded again.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <thread>

#include "fake_transports.hpp"
#include "palpa/device/device_error.hpp"
#include "palpa/device/falcon_device.hpp"
#include "palpa/device/falcon_link.hpp"
#include "palpa/engine/fallback_device.hpp"
#include "palpa/engine/virtual_device.hpp"

namespace palpa::device {
namespace {

using engine::DeviceStatus;
using test::FakeFalcon;
using Torque = std::array<std::int16_t, 3>;
const Torque kZero{0, 0, 0};
const std::string kId = "falcon:1-1";

// Whole encoder counts of a grip position (device frame).
std::array<std::int16_t, 3> counts_at(const palpa::Vec3& grip) {
  const auto angles = falcon::Kinematics().inverse(grip);
  std::array<std::int16_t, 3> counts{};
  const double per_count = falcon::encoder_to_angle(1) - falcon::encoder_to_angle(0);
  for (std::size_t k = 0; k < 3; ++k) {
    counts[k] = static_cast<std::int16_t>(
        std::lround(((*angles)[static_cast<Eigen::Index>(k)] - falcon::encoder_to_angle(0)) / per_count));
  }
  return counts;
}

// A Falcon whose firmware is already running (booted on the fake directly): connect()
// finds it, no file needed.
struct RunningFalcon {
  FakeFalcon* fake = nullptr;
  std::unique_ptr<FalconDevice> device;
};

RunningFalcon running(FalconOptions options = {}, int homing_packets = 3) {
  const std::vector<std::uint8_t> firmware(256, 0x5A);
  auto fake = std::make_unique<FakeFalcon>(firmware.size());
  fake->homing_packets = homing_packets;
  falcon::boot(*fake, firmware, kId);
  fake->encoder = counts_at(falcon::Kinematics::workspace_center());
  RunningFalcon r;
  r.fake = fake.get();
  r.device = std::make_unique<FalconDevice>(std::move(fake), kId, options);
  EXPECT_EQ(r.device->connect(), 0);
  return r;
}

void home(RunningFalcon& r) {
  for (int k = 0; k < 4 && !r.device->homed(); ++k) ASSERT_TRUE(r.device->exchange());
  ASSERT_TRUE(r.device->homed());
}

// Thighs at 144, -74 and 144 degrees: no arm reaches that (checked in the test).
const std::array<std::int16_t, 3> kImpossible{3000, -3000, 3000};

bool forward_fails(const std::array<std::int16_t, 3>& counts, const palpa::Vec3& guess) {
  const falcon::Angles a(falcon::encoder_to_angle(counts[0]), falcon::encoder_to_angle(counts[1]),
                         falcon::encoder_to_angle(counts[2]));
  return !falcon::Kinematics().forward(a, guess).has_value();
}

// Presses 3 N through the fallback and checks the fake got a torque that is not zero.
void press(engine::FallbackDevice& fallback, RunningFalcon& r) {
  engine::DevicePose pose;
  ASSERT_EQ(fallback.read(0.0, pose), DeviceStatus::Ok);
  ASSERT_EQ(fallback.write_force(Vec3(0, 0, 3)), DeviceStatus::Ok);
  ASSERT_TRUE(r.device->exchange());
  ASSERT_NE(r.fake->last_command.value, kZero) << "pressing before the fault";
}

TEST(FalconFault, ASilentFirmwareBehindTheFallbackIsLeftWithZeroTorque) {
  FalconOptions options;
  options.silent_exchanges = 5;
  auto r = running(options);
  home(r);
  engine::VirtualDevice mouse(0.0);
  engine::FallbackDevice fallback(r.device.get(), mouse, 0.1);
  press(fallback, r);
  r.fake->silent = true;  // the firmware still hears commands but answers none
  int exchanges = 0;
  while (r.device->exchange() && exchanges < 100) ++exchanges;
  EXPECT_EQ(exchanges, 4);
  EXPECT_EQ(r.fake->last_command.value, kZero) << "the firmware's last command";
  engine::DevicePose pose;
  EXPECT_EQ(fallback.read(0.001, pose), DeviceStatus::Disconnected);  // holding, then the mouse
  EXPECT_EQ(fallback.switch_status(), DeviceStatus::Error);
  EXPECT_EQ(fallback.fault_message(),
            "Novint Falcon (falcon:1-1): the firmware stopped answering (power lost? unplug and plug in again)");
  // The fallback's zero reaches the command the I/O thread would send, and any later force
  // is refused as zero too.
  EXPECT_EQ(r.device->commanded_torque(), kZero);
  EXPECT_EQ(r.device->write_force(Vec3(0, 0, 5)), DeviceStatus::Error);
  EXPECT_EQ(r.device->commanded_torque(), kZero);
  EXPECT_FALSE(r.device->exchange());
  EXPECT_EQ(r.fake->last_command.value, kZero);
}

TEST(FalconFault, FailingTransfersLeaveZeroTorque) {
  auto r = running();
  home(r);
  engine::VirtualDevice mouse(0.0);
  engine::FallbackDevice fallback(r.device.get(), mouse, 0.1);
  press(fallback, r);
  r.fake->fail_reads = UsbStatus::Io;  // writes still arrive
  EXPECT_TRUE(r.device->exchange());
  EXPECT_TRUE(r.device->exchange());
  EXPECT_FALSE(r.device->exchange());
  EXPECT_EQ(r.fake->last_command.value, kZero);
  engine::DevicePose pose;
  EXPECT_EQ(fallback.read(0.001, pose), DeviceStatus::Disconnected);
  EXPECT_EQ(r.device->commanded_torque(), kZero);
}

// The I/O thread itself: once the firmware goes silent the thread ends, and the last thing
// it sent is a zero. (Waits are bounded; nothing is timed.)
TEST(FalconFault, TheIoThreadSendsZeroTorqueWhenItEnds) {
  FalconOptions options;
  options.silent_exchanges = 5;
  auto r = running(options);
  r.device->start();
  r.device->wait_homed(10.0);
  engine::VirtualDevice mouse(0.0);
  engine::FallbackDevice fallback(r.device.get(), mouse, 0.1);
  engine::DevicePose pose;
  ASSERT_EQ(fallback.read(0.0, pose), DeviceStatus::Ok);
  ASSERT_EQ(fallback.write_force(Vec3(0, 0, 3)), DeviceStatus::Ok);
  ASSERT_NE(r.device->commanded_torque(), kZero);
  // Two more packets back: the command was sent at least once after it was published.
  const auto seen = r.device->packets();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (r.device->packets() < seen + 2 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_GE(r.device->packets(), seen + 2);
  r.fake->silent = true;
  while (r.device->status() == DeviceStatus::Ok && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_EQ(r.device->status(), DeviceStatus::Error);
  r.device->stop();  // joins: the fake is ours again
  EXPECT_EQ(r.fake->last_command.value, kZero);
}

TEST(FalconFault, HomingHoldsTheCentreAndBadReadingsHoldTheLastPositionUntilARunOfThem) {
  FalconOptions options;
  options.bad_readings = 50;
  auto r = running(options);
  auto& device = *r.device;
  device.place_workspace(Vec3(0.5, 0.5, 0.5), 1.0);
  const Vec3 centre(0.5, 0.5, 0.5);
  engine::DevicePose pose;
  // Before homing the counts are relative to power-up: any values, the probe stays put.
  r.fake->encoder = kImpossible;
  ASSERT_TRUE(device.exchange());
  ASSERT_FALSE(device.homed());
  for (int k = 0; k < 100; ++k) {
    ASSERT_EQ(device.read(0.001 * k, pose), DeviceStatus::Ok) << k;
    EXPECT_EQ(pose.position, centre);
  }
  const palpa::Vec3 grip = falcon::Kinematics::workspace_center() + palpa::Vec3(0.01, 0.0, 0.0);
  r.fake->encoder = counts_at(grip);
  home(r);
  ASSERT_EQ(device.read(0.1, pose), DeviceStatus::Ok);
  const Vec3 good = pose.position;
  EXPECT_NEAR(good.x(), 0.51, 2e-4);  // 1 cm right
  ASSERT_TRUE(forward_fails(kImpossible, grip));
  ASSERT_TRUE(forward_fails(kImpossible, falcon::Kinematics::workspace_center()));

  // 49 bad reads, then a good reading: the count starts again.
  r.fake->encoder = kImpossible;
  ASSERT_TRUE(device.exchange());
  for (int k = 0; k < 49; ++k) {
    ASSERT_EQ(device.read(0.2 + 0.001 * k, pose), DeviceStatus::Ok) << k;
    EXPECT_EQ(pose.position, good);
  }
  r.fake->encoder = counts_at(grip);
  ASSERT_TRUE(device.exchange());
  ASSERT_EQ(device.read(0.3, pose), DeviceStatus::Ok);
  EXPECT_LT((pose.position - good).norm(), 1e-9);
  // Now 50 in a row: the 50th is an Error with its reason.
  r.fake->encoder = kImpossible;
  ASSERT_TRUE(device.exchange());
  const Vec3 held = pose.position;
  for (int k = 0; k < 49; ++k) {
    ASSERT_EQ(device.read(0.4 + 0.001 * k, pose), DeviceStatus::Ok) << k;
    EXPECT_EQ(pose.position, held);
  }
  EXPECT_TRUE(device.fault_message().empty());
  EXPECT_EQ(device.read(0.5, pose), DeviceStatus::Error);
  EXPECT_EQ(device.fault_message(),
            "Novint Falcon (falcon:1-1): the encoders read positions no arm can reach, 50 times in a row "
            "(a loose encoder cable? unplug and plug in again)");
  // The I/O thread's next exchange sends zero torque and ends.
  EXPECT_FALSE(device.exchange());
  EXPECT_EQ(r.fake->last_command.value, kZero);
}

TEST(FalconFault, HomingThatFailsSaysWhy) {
  {
    FalconOptions options;
    options.silent_exchanges = 5;
    auto r = running(options, 1000000);  // never homes
    r.fake->silent = true;               // before the thread starts
    r.device->start();
    try {
      r.device->wait_homed(10.0);
      FAIL() << "homed a silent Falcon";
    } catch (const DeviceError& e) {
      EXPECT_STREQ(e.what(), "falcon:1-1: homing: Novint Falcon (falcon:1-1): the firmware stopped answering "
                             "(power lost? unplug and plug in again)");
    }
  }
  {
    auto r = running({}, 1000000);
    r.device->start();
    try {
      r.device->wait_homed(0.0);
      FAIL() << "homed";
    } catch (const DeviceError& e) {
      EXPECT_STREQ(e.what(), "falcon:1-1: homing: not homed in time: move the grip all the way out and back in, then "
                             "try again");
    }
  }
}

TEST(FalconFirmware, ARunningFirmwareIsNotUploadedAgain) {
  const std::vector<std::uint8_t> firmware(256, 0x5A);
  std::random_device entropy;
  const auto path = std::filesystem::temp_directory_path() / ("palpa-firmware-" + std::to_string(entropy()) + ".bin");
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(firmware.data()), static_cast<std::streamsize>(firmware.size()));
  }
  FalconOptions options;
  options.firmware = path;
  auto fake = std::make_unique<FakeFalcon>(firmware.size());
  auto* raw = fake.get();
  FalconDevice first(std::move(fake), kId, options);
  EXPECT_EQ(first.connect(), 1);  // a Falcon just plugged in: one upload
  EXPECT_EQ(raw->boot_attempts, 1);
  raw->firmware_received.clear();
  // The next exercise connects again with the same file: the firmware answers, no upload.
  EXPECT_EQ(first.connect(), 0);
  EXPECT_EQ(raw->boot_attempts, 1);
  EXPECT_TRUE(raw->firmware_received.empty());
  EXPECT_EQ(raw->mode, FakeFalcon::Mode::Firmware);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace palpa::device
