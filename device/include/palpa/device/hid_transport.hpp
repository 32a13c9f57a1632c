#pragma once
// How the SpaceMouse driver reaches a HID device: read one input report at a time, with a
// timeout. The real transport is hidapi (hidraw backend); tests use a fake that plays
// recorded report bytes.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace palpa::device {

class HidTransport {
 public:
  virtual ~HidTransport() = default;
  /// Reads one input report into `buffer` (report id first), waiting at most timeout_ms.
  /// Returns its size, 0 when none came in time, -1 when the device failed or is gone
  /// (error() says why).
  virtual int read(std::uint8_t* buffer, std::size_t capacity, int timeout_ms) = 0;
  virtual std::string error() const = 0;
};

struct HidDeviceInfo {
  std::string path;  ///< e.g. /dev/hidraw3
  std::uint16_t vendor = 0;
  std::uint16_t product = 0;
  std::string serial;
  std::string product_name;
  int interface_number = -1;
  std::uint16_t usage_page = 0;  ///< 0x01 Generic Desktop, usage 0x08: multi-axis controller
  std::uint16_t usage = 0;
};

struct HidEnumeration {
  std::vector<HidDeviceInfo> devices;
  std::string note;  ///< why the list may be incomplete (empty when nothing went wrong)
};

/// Every HID device hidapi can see (none, with a note, where hidraw is absent).
HidEnumeration enumerate_hid();
/// Opens a device by its path. Throws DeviceError naming `device_id`.
std::unique_ptr<HidTransport> open_hid(const std::string& path, const std::string& device_id);

}  // namespace palpa::device
