// Discovery (with fake enumerations: what this machine lists is only the virtual device)
// and the replay device.
#include <gtest/gtest.h>

#include "palpa/device/device_error.hpp"
#include "palpa/device/registry.hpp"
#include "palpa/device/replay_device.hpp"
#include "palpa/engine/virtual_device.hpp"

namespace palpa::device {
namespace {

Enumerators nothing_attached(const std::string& hid_note = {}, const std::string& usb_note = {}) {
  Enumerators e;
  e.hid = [hid_note] { return HidEnumeration{{}, hid_note}; };
  e.usb = [usb_note](std::uint16_t, std::uint16_t) { return UsbEnumeration{{}, usb_note}; };
  return e;
}

TEST(DeviceRegistry, WithNothingAttachedOnlyTheVirtualDeviceIsListed) {
  const auto listing = list_devices(nothing_attached());
  ASSERT_EQ(listing.devices.size(), 1u);
  EXPECT_EQ(listing.devices[0].id, "virtual");
  EXPECT_EQ(listing.devices[0].name, "virtual (mouse)");
  EXPECT_TRUE(listing.notes.empty());
  const auto noted = list_devices(nothing_attached("", "no USB device list: /dev/bus/usb is absent (a container?)"));
  ASSERT_EQ(noted.devices.size(), 1u);
  ASSERT_EQ(noted.notes.size(), 1u);
  EXPECT_EQ(noted.notes[0], "Falcon: no USB device list: /dev/bus/usb is absent (a container?)");
}

TEST(DeviceRegistry, ListsSpaceMiceAndFalconsWithStableIds) {
  Enumerators e;
  e.hid = [] {
    HidEnumeration h;
    // A SpaceMouse Pro, a receiver's keyboard interface (not the axes), a plain mouse.
    h.devices.push_back({"/dev/hidraw3", 0x046D, 0xC62B, "", "SpaceMouse Pro", 0, 0x01, 0x08});
    h.devices.push_back({"/dev/hidraw4", 0x256F, 0xC652, "AB12", "Receiver", 1, 0x01, 0x06});
    h.devices.push_back({"/dev/hidraw5", 0x256F, 0xC652, "AB12", "Receiver", 2, 0x01, 0x08});
    h.devices.push_back({"/dev/hidraw6", 0x046D, 0xC077, "", "USB Optical Mouse", 0, 0x01, 0x02});
    return h;
  };
  e.usb = [](std::uint16_t vendor, std::uint16_t product) {
    UsbEnumeration u;
    EXPECT_EQ(vendor, 0x0403);
    EXPECT_EQ(product, 0xCB48);
    u.devices.push_back({1, 7, "1-4.2", vendor, product});
    return u;
  };
  const auto listing = list_devices(e);
  ASSERT_EQ(listing.devices.size(), 4u);
  EXPECT_EQ(listing.devices[1].id, "spacemouse:046d:c62b");
  EXPECT_EQ(listing.devices[1].name, "SpaceMouse Pro");
  EXPECT_EQ(listing.devices[1].detail, "/dev/hidraw3");
  EXPECT_FALSE(listing.devices[1].force_output);
  EXPECT_EQ(listing.devices[2].id, "spacemouse:256f:c652:AB12");
  EXPECT_EQ(listing.devices[2].detail, "/dev/hidraw5");
  EXPECT_EQ(listing.devices[3].id, "falcon:1-4.2");
  EXPECT_EQ(listing.devices[3].detail, "USB 1-4.2");
  EXPECT_TRUE(listing.devices[3].force_output);
}

TEST(DeviceRegistry, TwoIdenticalSpaceMiceWithoutSerialsAreBothListedApart) {
  Enumerators e = nothing_attached();
  e.hid = [] {
    HidEnumeration h;
    // Two SpaceNavigators (no serial numbers) on the same interface number, and a third
    // device seen twice through two interfaces (a backend without usages).
    h.devices.push_back({"/dev/hidraw3", 0x046D, 0xC626, "", "SpaceNavigator", 0, 0, 0});
    h.devices.push_back({"/dev/hidraw7", 0x046D, 0xC626, "", "SpaceNavigator", 0, 0, 0});
    h.devices.push_back({"/dev/hidraw8", 0x046D, 0xC62B, "", "SpaceMouse Pro", 0, 0, 0});
    h.devices.push_back({"/dev/hidraw9", 0x046D, 0xC62B, "", "SpaceMouse Pro", 1, 0, 0});
    return h;
  };
  const auto listing = list_devices(e);
  ASSERT_EQ(listing.devices.size(), 4u);
  EXPECT_EQ(listing.devices[1].id, "spacemouse:046d:c626:hidraw3");
  EXPECT_EQ(listing.devices[1].detail, "/dev/hidraw3");
  EXPECT_EQ(listing.devices[2].id, "spacemouse:046d:c626:hidraw7");
  EXPECT_EQ(listing.devices[2].detail, "/dev/hidraw7");
  EXPECT_EQ(listing.devices[3].id, "spacemouse:046d:c62b");  // one device: no suffix
  EXPECT_EQ(listing.devices[3].detail, "/dev/hidraw8");
  ASSERT_EQ(listing.notes.size(), 1u);
  EXPECT_EQ(listing.notes[0], "SpaceMouse: identical models without serial numbers are told apart by their "
                              "/dev/hidraw node (the id may change when they are plugged in again)");
}

TEST(DeviceRegistry, OpeningSaysWhatIsWrong) {
  auto device = open_device("virtual", {}, nothing_attached());
  ASSERT_TRUE(device);
  EXPECT_EQ(device->capabilities().name, "virtual (mouse)");
  const auto message = [](const std::string& id, const Enumerators& e) {
    try {
      open_device(id, {}, e);
    } catch (const DeviceError& error) {
      return std::string(error.what());
    }
    return std::string("opened");
  };
  EXPECT_EQ(message("spacemouse", nothing_attached()),
            "spacemouse: open: not attached (palpa-cli devices lists what is attached)");
  EXPECT_EQ(message("falcon:1-4", nothing_attached("", "no USB device list: /dev/bus/usb is absent (a container?)")),
            "falcon:1-4: open: not attached; Falcon: no USB device list: /dev/bus/usb is absent (a container?) "
            "(palpa-cli devices lists what is attached)");
  EXPECT_EQ(message("phantom", nothing_attached()),
            "phantom: id: unknown device (virtual, spacemouse[:VID:PID[:SERIAL]], falcon[:PORT] or replay:SESSION; "
            "palpa-cli devices lists what is attached)");
  EXPECT_EQ(message("replay:", nothing_attached()), "replay:: id: replay needs a session file: replay:SESSION");
}

session::Session recorded() {
  session::Session s;
  s.info.device = "Novint Falcon";
  for (int k = 0; k < 5; ++k) {
    engine::Sample sample;
    sample.t = 10.0 + 0.001 * k;
    sample.position = {0.01 * k, 0.02, 0.03};
    sample.buttons = static_cast<std::uint32_t>(k);
    if (k == 3) {  // a fault tick, recorded at the origin by an older engine
      sample.fault = true;
      sample.position = {0.0, 0.0, 0.0};
    }
    s.samples.push_back(sample);
  }
  return s;
}

TEST(ReplayDevice, PlaysThePathAtTheRecordedTimesThenEnds) {
  ReplayDevice replay(recorded(), "old.palpa");
  EXPECT_EQ(replay.capabilities().name, "replay of Novint Falcon");
  EXPECT_NEAR(replay.duration(), 0.004, 1e-12);
  engine::DevicePose pose;
  ASSERT_EQ(replay.read(0.0, pose), engine::DeviceStatus::Ok);
  EXPECT_EQ(pose.position, palpa::Vec3(0.0, 0.02, 0.03));
  ASSERT_EQ(replay.read(0.0015, pose), engine::DeviceStatus::Ok);  // the sample standing at t
  EXPECT_EQ(pose.position, palpa::Vec3(0.01, 0.02, 0.03));
  EXPECT_EQ(pose.buttons, 1u);
  ASSERT_EQ(replay.read(0.0031, pose), engine::DeviceStatus::Ok);
  EXPECT_EQ(pose.position, palpa::Vec3(0.02, 0.02, 0.03));  // the fault tick keeps the last good position
  EXPECT_TRUE(replay.fault_message().empty());
  EXPECT_EQ(replay.read(0.0039, pose), engine::DeviceStatus::Ok);
  EXPECT_EQ(pose.buttons, 3u);
  EXPECT_EQ(replay.read(0.0044, pose), engine::DeviceStatus::Ok);  // within half a tick of the last sample
  EXPECT_EQ(replay.read(0.0046, pose), engine::DeviceStatus::Disconnected);  // past the last sample (10.004 s)
  EXPECT_EQ(replay.fault_message(), "replay:old.palpa: the replay ended");
  // Jumping back (a restarted engine) finds its place again.
  ASSERT_EQ(replay.read(0.001, pose), engine::DeviceStatus::Ok);
  EXPECT_EQ(pose.position, palpa::Vec3(0.01, 0.02, 0.03));
  EXPECT_THROW(ReplayDevice(session::Session{}, "empty.palpa"), DeviceError);
}

TEST(ReplayDevice, TheLastTickPlaysDespiteRounding) {
  // Times recorded by adding the period (10.0 + 0.001 + ...) and the engine's k / 1000 differ
  // by ~1e-15: at k = 4, 10.0 + 0.004 is past the recorded 4th time.
  session::Session s;
  double t = 10.0;
  for (int k = 0; k < 5; ++k, t += 0.001) {
    engine::Sample sample;
    sample.t = t;
    sample.position = {0.01 * k, 0.0, 0.0};
    s.samples.push_back(sample);
  }
  ASSERT_GT(s.samples.front().t + 4 / 1000.0, s.samples.back().t) << "the rounding this test is about";
  ReplayDevice replay(s, "rounded.palpa");
  engine::DevicePose pose;
  ASSERT_EQ(replay.read(4 / 1000.0, pose), engine::DeviceStatus::Ok);
  EXPECT_EQ(pose.position, palpa::Vec3(0.04, 0.0, 0.0));
  ASSERT_EQ(replay.read(replay.duration(), pose), engine::DeviceStatus::Ok);
  EXPECT_EQ(pose.position, palpa::Vec3(0.04, 0.0, 0.0));
  EXPECT_TRUE(replay.fault_message().empty());
  EXPECT_EQ(replay.read(5 / 1000.0, pose), engine::DeviceStatus::Disconnected);
  // One sample: it plays at t = 0 and ends after.
  session::Session one;
  one.samples.push_back(s.samples.front());
  ReplayDevice single(one, "one.palpa");
  EXPECT_EQ(single.read(0.0, pose), engine::DeviceStatus::Ok);
  EXPECT_EQ(single.read(0.001, pose), engine::DeviceStatus::Disconnected);
}

}  // namespace
}  // namespace palpa::device
