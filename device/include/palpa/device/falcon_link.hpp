#pragma once
// The Falcon's serial link: an FTDI USB-serial chip driven by vendor control requests
// (the request numbers of the FTDI "SIO" protocol, as libftdi and libnifalcon's
// FalconCommLibUSB use them), and the boot sequence of docs/devices.md, "Protocol notes":
//   9600 baud 8N1, latency 16 ms, no flow control, RTS low, DTR low then high;
//   send 0x0A 0x43 0x0D, expect 0x0A 0x44 0x2C 0x0D back (some hosts see a 0x00 first);
//   DTR low, ~140 kbaud, send 'A', expect 'A';
//   upload the firmware in 128-byte blocks, each echoed back byte for byte;
//   then 1,456,312 baud and a 1 ms latency timer for the 16-byte packets.
// Firmware loading is known to be flaky: a wrong echo or a silent boot loader restarts the
// whole sequence, up to BootOptions::attempts times.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "palpa/device/usb_transport.hpp"

namespace palpa::device::falcon {

namespace ftdi {
inline constexpr std::uint8_t kReset = 0, kModemControl = 1, kFlowControl = 2, kBaudRate = 3, kLineProperties = 4,
                              kLatencyTimer = 9;
inline constexpr std::uint16_t kPurgeRx = 1, kPurgeTx = 2;
inline constexpr std::uint16_t kDtrHigh = 0x0101, kDtrLow = 0x0100, kRtsLow = 0x0200;
inline constexpr std::uint16_t kLine8N1 = 0x0008;
/// Baud rate divisor words of the FTDI chip (3 MHz / divisor, eighths in the top bits).
inline constexpr std::uint16_t kBaud9600 = 0x4138;      ///< 312.5: 9600 baud
inline constexpr std::uint16_t kBaudLoader = 0x0015;    ///< 21: ~143 kbaud, the boot loader
inline constexpr std::uint16_t kBaudFirmware = 0x0002;  ///< the firmware's 1,456,312 baud
inline constexpr std::size_t kUsbPacket = 64;           ///< each bulk-in packet: 2 modem bytes + data
}  // namespace ftdi

inline constexpr std::size_t kFirmwareBlock = 128;

struct BootOptions {
  int attempts = 5;          ///< whole boot sequences before giving up
  int check_tries = 20;      ///< hellos to the boot loader per attempt
  unsigned timeout_ms = 1000;
};

/// Serial bytes over the FTDI chip: strips the modem-status bytes of every USB packet.
class FtdiSerial {
 public:
  explicit FtdiSerial(UsbTransport& usb) : usb_(&usb) {}
  UsbStatus control(std::uint8_t request, std::uint16_t value, unsigned timeout_ms = 1000);
  UsbStatus write(const std::uint8_t* data, std::size_t size, unsigned timeout_ms);
  /// Serial data: what is left of the last USB packet, else one new packet (possibly with
  /// no data: got = 0 and Ok). Bytes beyond `capacity` are kept for the next read.
  UsbStatus read(std::uint8_t* data, std::size_t capacity, std::size_t& got, unsigned timeout_ms);
  /// Reads until `size` bytes came, or a read times out or fails.
  UsbStatus read_exactly(std::uint8_t* data, std::size_t size, std::size_t& got, unsigned timeout_ms);
  /// Latency 1 ms, firmware baud rate, both FIFOs purged: the packets' mode.
  UsbStatus enter_firmware_mode();

 private:
  UsbTransport* usb_;
  std::array<std::uint8_t, ftdi::kUsbPacket> carry_{};  // data of the last packet not yet read
  std::size_t carry_begin_ = 0, carry_end_ = 0;
};

/// Reads the firmware file the user supplies (Novint's licence forbids shipping it).
/// Throws DeviceError naming `device_id`: not given, missing, unreadable, empty.
std::vector<std::uint8_t> read_firmware(const std::filesystem::path& path, const std::string& device_id);

/// Runs the boot sequence and uploads `firmware`, then enters firmware mode. Throws
/// DeviceError naming `device_id` with the step that failed (unplugged, permission, no
/// answer from the boot loader, a wrong echo in block k after all attempts).
/// Returns the number of attempts it took.
int boot(UsbTransport& usb, const std::vector<std::uint8_t>& firmware, const std::string& device_id,
         const BootOptions& options = {});

/// In firmware mode: does the firmware answer a packet? (It keeps running while the Falcon
/// stays powered, so a second program start needs no upload.)
bool firmware_running(UsbTransport& usb, unsigned timeout_ms = 100);

}  // namespace palpa::device::falcon
