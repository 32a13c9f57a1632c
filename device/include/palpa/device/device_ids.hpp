#pragma once
// The USB ids of the devices Palpa drives itself. packaging/udev/70-palpa.rules must grant
// access to every one of them (tests/device/test_udev_rules.py reads this file and checks).
#include <array>
#include <cstdint>

namespace palpa::device {

struct UsbId {
  std::uint16_t vendor = 0;
  std::uint16_t product = 0;
  const char* model = "";
};

/// 3Dconnexion SpaceMouse family (HID; docs/devices.md, "Protocol notes").
/// Logitech-era models (vendor 0x046D) split translation and rotation over reports 1 and 2;
/// the 3Dconnexion-era wireless models (vendor 0x256F) put all six axes in report 1,
/// except the Compact, which keeps the split.
inline constexpr std::array<UsbId, 7> kSpaceMouseIds{{
    {0x046D, 0xC626, "SpaceNavigator"},
    {0x046D, 0xC62B, "SpaceMouse Pro"},
    {0x256F, 0xC62E, "SpaceMouse Wireless"},
    {0x256F, 0xC631, "SpaceMouse Pro Wireless"},
    {0x256F, 0xC632, "SpaceMouse Pro Wireless (receiver)"},
    {0x256F, 0xC635, "SpaceMouse Compact"},
    {0x256F, 0xC652, "3Dconnexion Universal Receiver"},
}};

/// Novint Falcon: an FTDI USB-serial chip (not HID), driven over libusb.
inline constexpr UsbId kFalconId{0x0403, 0xCB48, "Novint Falcon"};

/// The SpaceMouse model for an id, or null when it is not one.
const UsbId* find_spacemouse(std::uint16_t vendor, std::uint16_t product);

}  // namespace palpa::device
