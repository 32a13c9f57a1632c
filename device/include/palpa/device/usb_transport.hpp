#pragma once
// How the Falcon driver reaches its FTDI chip: vendor control requests and bulk transfers
// on endpoints 0x02 (out) and 0x81 (in). The real transport is libusb-1.0; tests use a fake
// that answers like the Falcon's boot loader and firmware.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace palpa::device {

enum class UsbStatus : std::uint8_t { Ok, Timeout, NoDevice, Access, Busy, Pipe, Overflow, Io, Other };

/// "ok", "timed out", "device unplugged", ... (static strings).
const char* to_string(UsbStatus status);

class UsbTransport {
 public:
  virtual ~UsbTransport() = default;
  /// A vendor request to the device (bmRequestType 0x40: host to device, no data).
  virtual UsbStatus control_out(std::uint8_t request, std::uint16_t value, std::uint16_t index,
                                unsigned timeout_ms) = 0;
  virtual UsbStatus bulk_write(const std::uint8_t* data, std::size_t size, std::size_t& written,
                               unsigned timeout_ms) = 0;
  /// Reads what the device has (FTDI: two modem-status bytes at the start of every 64-byte
  /// USB packet, then data), at most `capacity` bytes.
  virtual UsbStatus bulk_read(std::uint8_t* data, std::size_t capacity, std::size_t& got, unsigned timeout_ms) = 0;
};

struct UsbDeviceInfo {
  std::uint8_t bus = 0;
  std::uint8_t address = 0;
  std::string port_path;  ///< "1-4.2": bus and port numbers, stable while the cable stays in its port
  std::uint16_t vendor = 0;
  std::uint16_t product = 0;
};

struct UsbEnumeration {
  std::vector<UsbDeviceInfo> devices;
  std::string note;  ///< why the list may be incomplete (empty when nothing went wrong)
};

/// The attached USB devices with this vendor and product id (none, with a note, where
/// /dev/bus/usb is absent or unreadable).
UsbEnumeration enumerate_usb(std::uint16_t vendor, std::uint16_t product);
/// Opens the device at `port_path` and claims interface 0. Throws DeviceError naming
/// `device_id` (not found, permission denied with the udev hint, busy).
std::unique_ptr<UsbTransport> open_usb(const std::string& port_path, std::uint16_t vendor, std::uint16_t product,
                                       const std::string& device_id);

}  // namespace palpa::device
