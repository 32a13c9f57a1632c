#pragma once
// Discovery: what can be a probe here, each with a stable id, and opening one by its id.
//   virtual                      the mouse-driven virtual device (always there)
//   spacemouse:VVVV:PPPP[:SERIAL] a SpaceMouse (first of that model when no serial is given);
//                                two identical ones without serials: :hidrawN in its place
//   spacemouse                   the first SpaceMouse found
//   falcon:BUS-PORT[.PORT...]    a Novint Falcon in that USB port, e.g. falcon:1-4.2
//   falcon                       the first Falcon found
//   replay:SESSION               a recorded session played back
// Listing never throws: where /dev/bus/usb or /dev/hidraw* is absent or unreadable it says
// so in a note and lists what it can (at least the virtual device). Hot-plug: listing is
// cheap, call it again; an open device that is unplugged reports Disconnected.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "palpa/device/falcon_device.hpp"
#include "palpa/device/hid_transport.hpp"
#include "palpa/device/spacemouse_device.hpp"
#include "palpa/device/usb_transport.hpp"
#include "palpa/engine/device.hpp"

namespace palpa::device {

struct DeviceEntry {
  std::string id;      ///< stable: the same device in the same port keeps it
  std::string kind;    ///< "virtual", "spacemouse", "falcon"
  std::string name;    ///< the model
  bool force_output = false;
  std::string detail;  ///< where it is (/dev/hidraw3, USB 1-4.2), empty for the virtual device
};

struct DeviceListing {
  std::vector<DeviceEntry> devices;  ///< the virtual device first
  std::vector<std::string> notes;    ///< why the list may be incomplete
};

/// Where listing looks; the defaults are hidapi and libusb, tests give fakes.
struct Enumerators {
  std::function<HidEnumeration()> hid = enumerate_hid;
  std::function<UsbEnumeration(std::uint16_t, std::uint16_t)> usb = enumerate_usb;
};

DeviceListing list_devices(const Enumerators& enumerators = {});

struct OpenOptions {
  double virtual_settling = 0.03;  ///< s, for "virtual"
  SpaceMouseOptions spacemouse{};
  FalconOptions falcon{};
  double homing_timeout = 60.0;    ///< s to wait for the Falcon's homing (0: do not wait)
  /// Progress lines for the user while opening ("Falcon: uploading firmware", "move the grip
  /// all the way out and back in"); may be empty.
  std::function<void(const std::string&)> progress;
};

/// Opens the device with this id, started and ready (a Falcon booted and homed). Throws
/// DeviceError: an unknown id, a device not attached, no permission, a failed boot; and
/// session::SessionError for a replay of an unreadable session.
std::unique_ptr<engine::Device> open_device(const std::string& id, const OpenOptions& options = {},
                                            const Enumerators& enumerators = {});

}  // namespace palpa::device
