#include "palpa/device/falcon_link.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <iterator>

#include <fmt/format.h>

#include "palpa/device/device_error.hpp"
#include "palpa/device/falcon_packet.hpp"

namespace palpa::device::falcon {

UsbStatus FtdiSerial::control(std::uint8_t request, std::uint16_t value, unsigned timeout_ms) {
  if (request == ftdi::kReset && value == ftdi::kPurgeRx) carry_begin_ = carry_end_ = 0;  // stale input goes too
  return usb_->control_out(request, value, 0, timeout_ms);
}

UsbStatus FtdiSerial::write(const std::uint8_t* data, std::size_t size, unsigned timeout_ms) {
  std::size_t done = 0;
  while (done < size) {
    std::size_t written = 0;
    const UsbStatus status = usb_->bulk_write(data + done, size - done, written, timeout_ms);
    if (status != UsbStatus::Ok) return status;
    if (written == 0) return UsbStatus::Timeout;
    done += written;
  }
  return UsbStatus::Ok;
}

UsbStatus FtdiSerial::read(std::uint8_t* data, std::size_t capacity, std::size_t& got, unsigned timeout_ms) {
  got = 0;
  if (carry_begin_ == carry_end_) {
    std::size_t n = 0;
    const UsbStatus status = usb_->bulk_read(carry_.data(), carry_.size(), n, timeout_ms);
    if (status != UsbStatus::Ok) return status;
    // The first two bytes of every packet are the modem status, not data.
    carry_begin_ = 2;
    carry_end_ = n > 2 ? n : 2;
  }
  got = std::min(carry_end_ - carry_begin_, capacity);
  std::memcpy(data, carry_.data() + carry_begin_, got);
  carry_begin_ += got;
  return UsbStatus::Ok;
}

UsbStatus FtdiSerial::read_exactly(std::uint8_t* data, std::size_t size, std::size_t& got, unsigned timeout_ms) {
  got = 0;
  // An FTDI chip answers an empty read every latency period: give up after a few in a row.
  int empty = 0;
  while (got < size) {
    std::size_t n = 0;
    const UsbStatus status = read(data + got, size - got, n, timeout_ms);
    if (status != UsbStatus::Ok) return status;
    if (n == 0 && ++empty > 64) return UsbStatus::Timeout;
    if (n > 0) empty = 0;
    got += n;
  }
  return UsbStatus::Ok;
}

UsbStatus FtdiSerial::enter_firmware_mode() {
  for (const auto& [request, value] : std::array<std::pair<std::uint8_t, std::uint16_t>, 4>{{
           {ftdi::kLatencyTimer, 1},
           {ftdi::kBaudRate, ftdi::kBaudFirmware},
           {ftdi::kReset, ftdi::kPurgeRx},
           {ftdi::kReset, ftdi::kPurgeTx},
       }}) {
    const UsbStatus status = control(request, value);
    if (status != UsbStatus::Ok) return status;
  }
  return UsbStatus::Ok;
}

std::vector<std::uint8_t> read_firmware(const std::filesystem::path& path, const std::string& device_id) {
  const std::string hint =
      " (Palpa cannot ship the Falcon's firmware: give the file from Novint's driver package, e.g. "
      "test_firmware.bin or nVent_firmware.bin, with --falcon-firmware; see docs/devices.md)";
  if (path.empty()) throw DeviceError(device_id, "firmware", "no firmware file given" + hint);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw DeviceError(device_id, "firmware", path.string() + " is not a file" + hint);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DeviceError(device_id, "firmware", path.string() + " cannot be read");
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.empty()) throw DeviceError(device_id, "firmware", path.string() + " is empty");
  return bytes;
}

namespace {

// Each step of the boot sequence returns an empty string on success, else why it failed,
// and throws for what no retry can mend (unplugged, no permission).
class BootStep {
 public:
  BootStep(FtdiSerial& serial, const std::string& device_id, const BootOptions& options)
      : serial_(serial), device_id_(device_id), options_(options) {}

  // The FTDI chip at 9600 baud 8N1, buffers purged, then DTR high: the boot loader listens.
  std::string serial_setup() {
    for (const auto& [request, value] : std::array<std::pair<std::uint8_t, std::uint16_t>, 8>{{
             {ftdi::kReset, ftdi::kPurgeRx},
             {ftdi::kReset, ftdi::kPurgeTx},
             {ftdi::kLatencyTimer, 16},
             {ftdi::kBaudRate, ftdi::kBaud9600},
             {ftdi::kLineProperties, ftdi::kLine8N1},
             {ftdi::kFlowControl, 0},
             {ftdi::kModemControl, ftdi::kRtsLow},
             {ftdi::kModemControl, ftdi::kDtrLow},
         }}) {
      if (auto why = check(serial_.control(request, value), "serial setup"); !why.empty()) return why;
    }
    return check(serial_.control(ftdi::kModemControl, ftdi::kDtrHigh), "DTR");
  }

  // Hello to the boot loader until it answers 0x0A 0x44 0x2C 0x0D.
  std::string hello() {
    static constexpr std::array<std::uint8_t, 3> kHello{0x0A, 0x43, 0x0D};
    static constexpr std::array<std::uint8_t, 4> kReply{0x0A, 0x44, 0x2C, 0x0D};
    for (int k = 0; k < options_.check_tries; ++k) {
      UsbStatus status = serial_.write(kHello.data(), kHello.size(), options_.timeout_ms);
      fatal(status, "boot loader hello");
      if (status != UsbStatus::Ok) continue;
      std::array<std::uint8_t, 8> reply{};
      std::size_t got = 0;
      status = serial_.read_exactly(reply.data(), 4, got, options_.timeout_ms);
      fatal(status, "boot loader hello");
      if (got == 4 && reply[0] == 0x00) {  // the 5-byte form: a 0x00 first
        std::size_t more = 0;
        serial_.read_exactly(reply.data() + 4, 1, more, options_.timeout_ms);
        got += more;
      }
      if (got >= 4 && std::equal(kReply.begin(), kReply.end(), reply.begin() + static_cast<std::ptrdiff_t>(got - 4)))
        return {};
    }
    return "the boot loader did not answer its hello (is the Falcon powered?)";
  }

  // DTR low and the loader's baud rate; the loader echoes an 'A'.
  std::string loader_check() {
    UsbStatus status = serial_.control(ftdi::kModemControl, ftdi::kDtrLow);
    fatal(status, "DTR");
    if (status == UsbStatus::Ok) status = serial_.control(ftdi::kBaudRate, ftdi::kBaudLoader);
    if (auto why = check(status, "loader baud rate"); !why.empty()) return why;
    const std::uint8_t a = 'A';
    std::uint8_t echo = 0;
    std::size_t got = 0;
    status = serial_.write(&a, 1, options_.timeout_ms);
    if (status == UsbStatus::Ok) status = serial_.read_exactly(&echo, 1, got, options_.timeout_ms);
    fatal(status, "loader check");
    if (status != UsbStatus::Ok || echo != 'A') return "the boot loader did not echo 'A'";
    return {};
  }

  // The firmware in blocks, each echoed back and compared.
  std::string upload(const std::vector<std::uint8_t>& firmware) {
    std::array<std::uint8_t, kFirmwareBlock> back{};
    const std::size_t blocks = (firmware.size() + kFirmwareBlock - 1) / kFirmwareBlock;
    for (std::size_t block = 0; block < blocks; ++block) {
      const std::size_t offset = block * kFirmwareBlock;
      const std::size_t size = std::min(kFirmwareBlock, firmware.size() - offset);
      std::size_t got = 0;
      UsbStatus status = serial_.write(firmware.data() + offset, size, options_.timeout_ms);
      if (status == UsbStatus::Ok) status = serial_.read_exactly(back.data(), size, got, options_.timeout_ms);
      const std::string where = fmt::format("firmware block {} of {}", block + 1, blocks);
      fatal(status, "firmware upload");
      if (status != UsbStatus::Ok) return failed(status, where);
      if (!std::equal(back.begin(), back.begin() + static_cast<std::ptrdiff_t>(size),
                      firmware.begin() + static_cast<std::ptrdiff_t>(offset)))
        return where + " echoed wrong bytes";
    }
    return check(serial_.enter_firmware_mode(), "firmware mode");
  }

 private:
  void fatal(UsbStatus status, const char* step) const {
    if (status == UsbStatus::NoDevice || status == UsbStatus::Access)
      throw DeviceError(device_id_, "boot", failed(status, step));
  }
  static std::string failed(UsbStatus status, const std::string& step) {
    return fmt::format("{}: {}", step, to_string(status));
  }
  std::string check(UsbStatus status, const char* step) const {
    fatal(status, step);
    return status == UsbStatus::Ok ? std::string() : failed(status, step);
  }

  FtdiSerial& serial_;
  const std::string& device_id_;
  const BootOptions& options_;
};

// One pass of the boot sequence. Returns an empty string on success, else why it failed;
// throws for what no retry can mend (unplugged, no permission).
std::string boot_once(FtdiSerial& serial, const std::vector<std::uint8_t>& firmware, const std::string& device_id,
                      const BootOptions& options) {
  BootStep step(serial, device_id, options);
  if (auto why = step.serial_setup(); !why.empty()) return why;
  if (auto why = step.hello(); !why.empty()) return why;
  if (auto why = step.loader_check(); !why.empty()) return why;
  return step.upload(firmware);
}

}  // namespace

int boot(UsbTransport& usb, const std::vector<std::uint8_t>& firmware, const std::string& device_id,
         const BootOptions& options) {
  FtdiSerial serial(usb);
  std::string why;
  const int attempts = std::max(1, options.attempts);
  for (int attempt = 1; attempt <= attempts; ++attempt) {
    why = boot_once(serial, firmware, device_id, options);
    if (why.empty()) return attempt;
  }
  throw DeviceError(device_id, "firmware upload",
                    fmt::format("{} ({} attempts; firmware loading is known to be flaky: unplug the Falcon, plug it in "
                                "again and retry)",
                                why, attempts));
}

bool firmware_running(UsbTransport& usb, unsigned timeout_ms) {
  FtdiSerial serial(usb);
  if (serial.enter_firmware_mode() != UsbStatus::Ok) return false;
  Packet packet{};
  encode(Words{}, packet);
  if (serial.write(packet.data(), packet.size(), timeout_ms) != UsbStatus::Ok) return false;
  PacketReader reader;
  for (int k = 0; k < 8; ++k) {
    std::array<std::uint8_t, ftdi::kUsbPacket> bytes{};
    std::size_t got = 0;
    if (serial.read(bytes.data(), bytes.size(), got, timeout_ms) != UsbStatus::Ok) return false;
    reader.feed(bytes.data(), got);
    Words words;
    if (reader.next(words)) return true;
  }
  return false;
}

}  // namespace palpa::device::falcon
