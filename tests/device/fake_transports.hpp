#pragma once
// Fake transports that behave like the hardware, for the device tests: a HID device that
// plays recorded reports, and a Falcon (FTDI chip, boot loader and firmware) on a fake USB
// bus. Both can be "unplugged".
#include <algorithm>
#include <atomic>
#include <cstring>
#include <deque>
#include <utility>
#include <vector>

#include "palpa/device/falcon_link.hpp"
#include "palpa/device/falcon_packet.hpp"
#include "palpa/device/hid_transport.hpp"
#include "palpa/device/usb_transport.hpp"

namespace palpa::device::test {

/// Plays reports in order; then answers "nothing in time" (0), or -1 once unplugged.
class FakeHid final : public HidTransport {
 public:
  explicit FakeHid(std::vector<std::vector<std::uint8_t>> reports, bool unplug_at_end = false)
      : reports_(reports.begin(), reports.end()), unplug_at_end_(unplug_at_end) {}
  int read(std::uint8_t* buffer, std::size_t capacity, int /*timeout_ms*/) override {
    if (reports_.empty()) return unplug_at_end_ ? -1 : 0;
    const auto report = reports_.front();
    reports_.pop_front();
    const std::size_t n = std::min(capacity, report.size());
    std::memcpy(buffer, report.data(), n);
    return static_cast<int>(n);
  }
  std::string error() const override { return "No such device"; }

 private:
  std::deque<std::vector<std::uint8_t>> reports_;
  bool unplug_at_end_;
};

/// The Falcon behind its FTDI chip: the boot loader answers the hello and 'A', echoes
/// the firmware (a chosen block corrupted on the first attempts), and once in firmware
/// mode with the whole firmware received answers every 16-byte command with a report.
class FakeFalcon final : public UsbTransport {
 public:
  enum class Mode { Off, BootLoader, Loader, Firmware };

  explicit FakeFalcon(std::size_t firmware_size) : firmware_size_(firmware_size) {}

  // What the test sets.
  std::array<std::int16_t, 3> encoder{};
  std::uint8_t buttons = 0;
  int homing_packets = 3;          ///< commands in homing mode before the axes report homed
  int corrupt_block = -1;          ///< this block's echo has one byte flipped...
  int corrupt_attempts = 0;        ///< ...on this many boot attempts
  bool five_byte_hello = false;    ///< answer the hello as macOS sees it (0x00 first)
  bool unplugged = false;
  bool no_permission = false;      ///< the udev rules are missing
  UsbStatus fail_reads = UsbStatus::Ok;  ///< every read fails with this (Ok: no failure)
  std::atomic<bool> silent{false};  ///< the firmware stops answering (may be set while the I/O thread runs)

  // What the test reads.
  std::vector<std::pair<std::uint8_t, std::uint16_t>> controls;
  std::vector<std::uint8_t> firmware_received;
  int boot_attempts = 0;
  falcon::Words last_command;
  std::vector<std::uint8_t> last_packet;  ///< the last firmware command as sent, byte for byte
  int commands = 0;
  Mode mode = Mode::Off;

  UsbStatus control_out(std::uint8_t request, std::uint16_t value, std::uint16_t /*index*/, unsigned) override {
    if (unplugged) return UsbStatus::NoDevice;
    if (no_permission) return UsbStatus::Access;
    controls.emplace_back(request, value);
    namespace f = falcon::ftdi;
    if (request == f::kBaudRate) baud_ = value;
    if (request == f::kReset && value == f::kPurgeRx) pending_.clear();
    if (request == f::kModemControl && value == f::kDtrHigh && baud_ == f::kBaud9600) {
      mode = Mode::BootLoader;  // DTR raised at 9600 baud resets the Falcon into its boot loader
      ++boot_attempts;
      firmware_received.clear();
      homed_after_ = homing_packets;
    }
    if (request == f::kBaudRate && value == f::kBaudFirmware && mode == Mode::Loader) {
      mode = firmware_received.size() == firmware_size_ ? Mode::Firmware : Mode::Off;
    }
    return UsbStatus::Ok;
  }

  UsbStatus bulk_write(const std::uint8_t* data, std::size_t size, std::size_t& written, unsigned) override {
    written = 0;
    if (unplugged) return UsbStatus::NoDevice;
    written = size;
    const std::vector<std::uint8_t> bytes(data, data + size);
    switch (mode) {
      case Mode::Off: break;
      case Mode::BootLoader:
        if (bytes == std::vector<std::uint8_t>{0x0A, 0x43, 0x0D}) {
          if (five_byte_hello) queue({0x00});
          queue({0x0A, 0x44, 0x2C, 0x0D});
        } else if (bytes == std::vector<std::uint8_t>{'A'} && baud_ == falcon::ftdi::kBaudLoader) {
          queue({'A'});
          mode = Mode::Loader;
        }
        break;
      case Mode::Loader: {
        const auto block = static_cast<int>(firmware_received.size() / falcon::kFirmwareBlock);
        firmware_received.insert(firmware_received.end(), bytes.begin(), bytes.end());
        auto echo = bytes;
        if (block == corrupt_block && boot_attempts <= corrupt_attempts) echo[echo.size() / 2] ^= 0x5A;
        queue(echo);
        break;
      }
      case Mode::Firmware: {
        if (size != falcon::kPacketSize || falcon::decode(data, last_command) != nullptr) break;
        ++commands;
        if (silent) break;
        last_packet.assign(data, data + size);
        // The firmware's homing-mode bit as libnifalcon sends it (formatInput: byte 13 |= 0x01
        // before the 0x41 offset), written as the literal: the fake must not share a wrong
        // constant with the driver.
        if (((data[13] - 0x41) & 0x01) != 0 && homed_after_ > 0) --homed_after_;
        falcon::Words report;
        report.value = encoder;
        report.flags = static_cast<std::uint8_t>(buttons | (homed_after_ == 0 ? falcon::kHomedMask : 0));
        falcon::Packet packet{};
        falcon::encode(report, packet);
        queue(std::vector<std::uint8_t>(packet.begin(), packet.end()));
        break;
      }
    }
    return UsbStatus::Ok;
  }

  UsbStatus bulk_read(std::uint8_t* data, std::size_t capacity, std::size_t& got, unsigned) override {
    got = 0;
    if (unplugged) return UsbStatus::NoDevice;
    if (fail_reads != UsbStatus::Ok) return fail_reads;
    // FTDI: two modem-status bytes, then up to 62 data bytes per USB packet.
    data[0] = 0x31;
    data[1] = 0x60;
    const std::size_t n = std::min({pending_.size(), capacity - 2, std::size_t{62}});
    std::copy(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(n), data + 2);
    pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(n));
    got = n + 2;
    return UsbStatus::Ok;
  }

  /// Queues bytes as if the device had sent them (tests of the stream framing).
  void queue(const std::vector<std::uint8_t>& bytes) { pending_.insert(pending_.end(), bytes.begin(), bytes.end()); }

 private:
  std::size_t firmware_size_;
  std::uint16_t baud_ = 0;
  int homed_after_ = 3;
  std::deque<std::uint8_t> pending_;
};

}  // namespace palpa::device::test
