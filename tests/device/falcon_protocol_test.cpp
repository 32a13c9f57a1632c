// Novint Falcon protocol against a fake USB transport that answers like the Falcon's FTDI
// chip, boot loader and firmware: packet framing both ways, the boot sequence with its
// firmware echo and retries, encoders in, torques out, homing, unplugging and errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <utility>

#include "fake_transports.hpp"
#include "palpa/device/device_error.hpp"
#include "palpa/device/falcon_device.hpp"
#include "palpa/device/falcon_link.hpp"
#include "palpa/device/falcon_packet.hpp"

namespace palpa::device {
namespace {

using namespace falcon;
using test::FakeFalcon;

std::string text(const Packet& p) { return std::string(p.begin(), p.end()); }

TEST(FalconPacket, EncodesNibblesLeastSignificantFirstOffsetByA) {
  Words w;
  w.value = {0, 1447, -1447};
  w.flags = kHomingMode | kLedRed;
  Packet p{};
  encode(w, p);
  // 1447 = 0x05A7: nibbles 7, A, 5, 0 -> 'H' 'K' 'F' 'A'; -1447 = 0xFA59: 9, 5, A, F -> 'J' 'F' 'K' 'P'
  // (the example in libnifalcon's firmware notes); flags: homing 0x01 and red 0x08
  // (libnifalcon formatInput() and FalconFirmware.h) = 0x09 -> 0x4A 'J'.
  EXPECT_EQ(text(p), "<AAAAHKFAJFKPJA>");
  EXPECT_EQ(p[13], 0x01 + 0x08 + 0x41);
  // Each flag alone, as the bytes libnifalcon puts in byte 13.
  const std::pair<std::uint8_t, std::uint8_t> bits[] = {{kHomingMode, 0x01 + 0x41}, {kLedGreen, 0x02 + 0x41},
                                                        {kLedBlue, 0x04 + 0x41}, {kLedRed, 0x08 + 0x41}};
  for (const auto& [flag, byte] : bits) {
    Words one;
    one.flags = flag;
    encode(one, p);
    EXPECT_EQ(p[13], byte) << int(flag);
  }
  encode(w, p);
  Words back;
  ASSERT_EQ(decode(p.data(), back), nullptr);
  EXPECT_EQ(back.value, w.value);
  EXPECT_EQ(back.flags, w.flags);
  // The extremes of a 16-bit word survive the round trip.
  w.value = {32767, -32768, -1};
  w.flags = 0x7F;
  encode(w, p);
  ASSERT_EQ(decode(p.data(), back), nullptr);
  EXPECT_EQ(back.value, w.value);
  EXPECT_EQ(back.flags, 0x7F);
}

TEST(FalconPacket, MalformedPacketsAreRefusedWithTheReason) {
  const std::string good = "<AAAAHKFAJFKPSA>";
  Words w;
  std::string bad = good;
  bad[0] = 'x';
  EXPECT_STREQ(decode(reinterpret_cast<const std::uint8_t*>(bad.data()), w), "no '<' at byte 0");
  bad = good;
  bad[15] = 'A';
  EXPECT_STREQ(decode(reinterpret_cast<const std::uint8_t*>(bad.data()), w), "no '>' at byte 15");
  bad = good;
  bad[5] = '9';
  EXPECT_STREQ(decode(reinterpret_cast<const std::uint8_t*>(bad.data()), w), "a word byte is not a nibble ('A'..'P')");
}

TEST(FalconPacket, TheReaderReassemblesSplitPacketsAndSkipsGarbage) {
  PacketReader reader;
  Packet a{}, b{};
  Words wa, wb;
  wa.value = {1, 2, 3};
  wb.value = {-4, 5, -6};
  wb.flags = 0x15;
  encode(wa, a);
  encode(wb, b);
  std::vector<std::uint8_t> stream{'x', 'y'};                          // garbage before
  stream.insert(stream.end(), a.begin(), a.end());
  stream.insert(stream.end(), {'<', 'A', 'A'});                       // a frame cut short...
  stream.insert(stream.end(), b.begin(), b.end());                    // ...then a good one
  Words out;
  reader.feed(stream.data(), 10);  // a packet straddles two reads
  EXPECT_FALSE(reader.next(out));
  reader.feed(stream.data() + 10, stream.size() - 10);
  ASSERT_TRUE(reader.next(out));
  EXPECT_EQ(out.value, wa.value);
  ASSERT_TRUE(reader.next(out));
  EXPECT_EQ(out.value, wb.value);
  EXPECT_EQ(out.flags, 0x15);
  EXPECT_FALSE(reader.next(out));
  EXPECT_EQ(reader.bad_packets(), 1u);   // the frame cut short
  EXPECT_EQ(reader.skipped_bytes(), 5u);  // 'x', 'y' and its three bytes
}

TEST(UsbTransport, BusyNamesTheOtherPalpaWindowToo) {
  // A second Palpa window holding the Falcon is the usual culprit, not another program.
  EXPECT_STREQ(to_string(UsbStatus::Busy), "busy (held by another program or another Palpa window)");
}

std::vector<std::uint8_t> firmware_bytes(std::size_t n) {
  std::vector<std::uint8_t> bytes(n);
  for (std::size_t k = 0; k < n; ++k) bytes[k] = static_cast<std::uint8_t>((k * 37 + 11) & 0xFF);
  return bytes;
}

TEST(FalconBoot, RunsTheSequenceAndUploadsTheFirmwareBlockByBlock) {
  const auto firmware = firmware_bytes(300);  // two whole blocks and a partial one
  FakeFalcon falcon_fake(firmware.size());
  EXPECT_EQ(boot(falcon_fake, firmware, "falcon:1-4"), 1);
  EXPECT_EQ(falcon_fake.mode, FakeFalcon::Mode::Firmware);
  EXPECT_EQ(falcon_fake.firmware_received, firmware);
  namespace f = ftdi;
  const std::vector<std::pair<std::uint8_t, std::uint16_t>> expected{
      {f::kReset, f::kPurgeRx},      {f::kReset, f::kPurgeTx},       {f::kLatencyTimer, 16},
      {f::kBaudRate, 0x4138},        {f::kLineProperties, 0x0008},   {f::kFlowControl, 0},
      {f::kModemControl, 0x0200},    {f::kModemControl, 0x0100},     {f::kModemControl, 0x0101},
      {f::kModemControl, 0x0100},    {f::kBaudRate, 0x0015},         {f::kLatencyTimer, 1},
      {f::kBaudRate, 0x0002},        {f::kReset, f::kPurgeRx},       {f::kReset, f::kPurgeTx}};
  EXPECT_EQ(falcon_fake.controls, expected);
  EXPECT_TRUE(firmware_running(falcon_fake));
}

TEST(FalconBoot, AcceptsTheFiveByteHello) {
  const auto firmware = firmware_bytes(128);
  FakeFalcon falcon_fake(firmware.size());
  falcon_fake.five_byte_hello = true;
  EXPECT_EQ(boot(falcon_fake, firmware, "falcon:1-4"), 1);
}

TEST(FalconBoot, OneCorruptedEchoRestartsTheSequence) {
  const auto firmware = firmware_bytes(1000);
  FakeFalcon falcon_fake(firmware.size());
  falcon_fake.corrupt_block = 3;
  falcon_fake.corrupt_attempts = 1;
  EXPECT_EQ(boot(falcon_fake, firmware, "falcon:1-4"), 2);
  EXPECT_EQ(falcon_fake.boot_attempts, 2);
  EXPECT_EQ(falcon_fake.mode, FakeFalcon::Mode::Firmware);
  EXPECT_EQ(falcon_fake.firmware_received, firmware);
}

TEST(FalconBoot, GivesUpAfterTheAttemptsWithAClearMessage) {
  const auto firmware = firmware_bytes(1000);
  FakeFalcon falcon_fake(firmware.size());
  falcon_fake.corrupt_block = 3;
  falcon_fake.corrupt_attempts = 100;
  BootOptions options;
  options.attempts = 3;
  try {
    boot(falcon_fake, firmware, "falcon:1-4", options);
    FAIL() << "booted with a corrupted echo";
  } catch (const DeviceError& e) {
    EXPECT_STREQ(e.what(),
                 "falcon:1-4: firmware upload: firmware block 4 of 8 echoed wrong bytes (3 attempts; firmware loading "
                 "is known to be flaky: unplug the Falcon, plug it in again and retry)");
  }
  EXPECT_EQ(falcon_fake.boot_attempts, 3);
}

TEST(FalconBoot, UnpluggedAndMissingFirmwareAreClearErrors) {
  const auto firmware = firmware_bytes(128);
  FakeFalcon falcon_fake(firmware.size());
  falcon_fake.unplugged = true;
  try {
    boot(falcon_fake, firmware, "falcon:1-4");
    FAIL();
  } catch (const DeviceError& e) {
    EXPECT_STREQ(e.what(), "falcon:1-4: boot: serial setup: device unplugged");
  }
  FakeFalcon locked(firmware.size());
  locked.no_permission = true;
  try {
    boot(locked, firmware, "falcon:1-4");
    FAIL();
  } catch (const DeviceError& e) {
    EXPECT_STREQ(e.what(), "falcon:1-4: boot: serial setup: permission denied (install "
                           "packaging/udev/70-palpa.rules, see docs/devices.md)");
  }
  try {
    read_firmware("/nonexistent/test_firmware.bin", "falcon:1-4");
    FAIL();
  } catch (const DeviceError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("falcon:1-4: firmware: /nonexistent/test_firmware.bin is not a file (Palpa "
                                          "cannot ship the Falcon's firmware",
                                          0),
              0u)
        << e.what();
  }
  // No file and no firmware running: the device says what to give it.
  FalconDevice device(std::make_unique<FakeFalcon>(128), "falcon:1-4");
  try {
    device.connect();
    FAIL();
  } catch (const DeviceError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("falcon:1-4: firmware: no firmware file given", 0), 0u) << e.what();
  }
}

// A Falcon booted from a firmware file in a temporary folder, its fake kept for the test.
struct BootedFalcon {
  FakeFalcon* fake = nullptr;
  std::unique_ptr<FalconDevice> device;
};

BootedFalcon booted(FalconOptions options = {}) {
  const auto firmware = firmware_bytes(200);
  // One file per process: ctest runs these tests in parallel processes, and one that
  // removes a shared file under another's connect() fails that one.
  const auto path = std::filesystem::temp_directory_path() /
                    ("palpa_falcon_test_firmware_" + std::to_string(::getpid()) + ".bin");
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(firmware.data()), static_cast<std::streamsize>(firmware.size()));
  }
  auto fake = std::make_unique<FakeFalcon>(firmware.size());
  BootedFalcon b;
  b.fake = fake.get();
  options.firmware = path;
  b.device = std::make_unique<FalconDevice>(std::move(fake), "falcon:1-4", options);
  b.device->connect();
  std::filesystem::remove(path);
  return b;
}

TEST(FalconDevice, HomesFirstThenReadsEncodersAsAPositionAndSendsTorques) {
  auto b = booted();
  auto& device = *b.device;
  device.place_workspace(palpa::Vec3(0.5, 0.5, 0.5), 1.0);
  // Encoders for a grip 1 cm right, 2 cm up and 1 cm toward the user of the workspace centre.
  const Kinematics kin;
  const Vec3 grip = Kinematics::workspace_center() + Vec3(0.01, 0.02, 0.01);
  const auto angles = kin.inverse(grip);
  ASSERT_TRUE(angles);
  for (int k = 0; k < 3; ++k) {
    // Whole encoder counts: the position is the kinematics of the rounded counts.
    const double per_count = encoder_to_angle(1) - encoder_to_angle(0);
    b.fake->encoder[static_cast<std::size_t>(k)] =
        static_cast<std::int16_t>(std::lround(((*angles)[k] - encoder_to_angle(0)) / per_count));
  }
  b.fake->buttons = 0x05;
  // Homing: three exchanges in homing mode (red LED), no torque asked for.
  device.write_force(palpa::Vec3(0, 0, 5));
  for (int k = 0; k < 3; ++k) {
    EXPECT_FALSE(device.homed());
    ASSERT_TRUE(device.exchange());
    ASSERT_EQ(b.fake->last_packet.size(), kPacketSize);
    EXPECT_EQ(b.fake->last_packet[13], 0x01 + 0x08 + 0x41) << "homing mode (0x01) and the red LED (0x08)";
    EXPECT_EQ(b.fake->last_command.value, (std::array<std::int16_t, 3>{0, 0, 0}));
  }
  EXPECT_TRUE(device.homed());
  engine::DevicePose pose;
  ASSERT_EQ(device.read(0.0, pose), engine::DeviceStatus::Ok);
  const Angles counted(encoder_to_angle(b.fake->encoder[0]), encoder_to_angle(b.fake->encoder[1]),
                       encoder_to_angle(b.fake->encoder[2]));
  const Vec3 expected_device = *kin.forward(counted, Kinematics::workspace_center());
  EXPECT_LT((expected_device - grip).norm(), 2e-4);  // an encoder count is ~0.1 mm at the grip
  const palpa::Vec3 d = expected_device - Kinematics::workspace_center();
  // Scene: x right, y away from the user (the device's -z), z up (the device's y).
  EXPECT_NEAR((pose.position - palpa::Vec3(0.5 + d.x(), 0.5 - d.z(), 0.5 + d.y())).norm(), 0.0, 1e-12);
  EXPECT_EQ(pose.buttons, 0x05u);

  // 2 N up in the scene is 2 N along the device's y: torques J^T F, in firmware units.
  ASSERT_EQ(device.write_force(palpa::Vec3(0, 0, 2)), engine::DeviceStatus::Ok);
  const Vec3 tau = *kin.torques(expected_device, Vec3(0, 2, 0));
  ASSERT_TRUE(device.exchange());
  EXPECT_EQ(b.fake->last_packet[13], 0x02 + 0x41) << "the green LED (0x02), homing mode off";
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(b.fake->last_command.value[static_cast<std::size_t>(k)], std::lround(-10000.0 * tau[k])) << k;
  }
  EXPECT_EQ(device.commanded_torque(), b.fake->last_command.value);
  // 80 N is cut to the Falcon's 8 N; across the axis that needs more than the firmware's
  // 4096 on one motor, so all three are scaled by the same factor: the direction is kept.
  device.write_force(palpa::Vec3(0, 0, 80));
  const Vec3 units8 = -10000.0 * *kin.torques(expected_device, Vec3(0, 8, 0));
  ASSERT_GT(units8.cwiseAbs().maxCoeff(), kMaxTorqueUnits);
  const Vec3 scaled = units8 * (kMaxTorqueUnits / units8.cwiseAbs().maxCoeff());
  device.exchange();
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(b.fake->last_command.value[static_cast<std::size_t>(k)], std::lround(scaled[k])) << k;
  }
}

TEST(FalconDevice, UnpluggingIsDisconnectedAndAFailingLinkIsAnError) {
  {
    auto b = booted();
    ASSERT_TRUE(b.device->exchange());
    b.fake->unplugged = true;
    EXPECT_FALSE(b.device->exchange());
    engine::DevicePose pose;
    EXPECT_EQ(b.device->read(0.0, pose), engine::DeviceStatus::Disconnected);
    EXPECT_EQ(b.device->write_force(palpa::Vec3(0, 0, 1)), engine::DeviceStatus::Disconnected);
    EXPECT_EQ(b.device->fault_message(), "Novint Falcon (falcon:1-4): unplugged");
  }
  {
    auto b = booted();
    b.fake->fail_reads = UsbStatus::Io;
    EXPECT_TRUE(b.device->exchange());  // one failed transfer is forgiven...
    EXPECT_TRUE(b.device->exchange());
    EXPECT_FALSE(b.device->exchange());  // ...three in a row are not
    engine::DevicePose pose;
    EXPECT_EQ(b.device->read(0.0, pose), engine::DeviceStatus::Error);
    EXPECT_EQ(b.device->fault_message(), "Novint Falcon (falcon:1-4): USB transfer failed: input/output error");
  }
  {
    FalconOptions options;
    options.silent_exchanges = 5;
    auto b = booted(options);
    b.fake->silent = true;
    for (int k = 0; k < 4; ++k) EXPECT_TRUE(b.device->exchange());
    EXPECT_FALSE(b.device->exchange());
    EXPECT_EQ(b.device->fault_message(),
              "Novint Falcon (falcon:1-4): the firmware stopped answering (power lost? unplug and plug in again)");
  }
}

}  // namespace
}  // namespace palpa::device
