// The HID transport over hidapi (hidraw backend: /dev/hidraw*, report id in byte 0).
#include "palpa/device/hid_transport.hpp"

#include <cwchar>
#include <mutex>

#include <hidapi.h>

#include "palpa/device/device_error.hpp"

namespace palpa::device {

namespace {

std::string narrow(const wchar_t* text) {
  std::string out;
  if (!text) return out;
  for (; *text; ++text) out += *text < 128 ? static_cast<char>(*text) : '?';
  return out;
}

// hid_init is not thread-safe and counts nothing: call it once per process.
bool hid_ready(std::string& why) {
  static std::once_flag once;
  static int result = -1;
  std::call_once(once, [] { result = hid_init(); });
  if (result != 0) why = "hidapi could not start: " + narrow(hid_error(nullptr));
  return result == 0;
}

class HidapiTransport final : public HidTransport {
 public:
  explicit HidapiTransport(hid_device* device) : device_(device) {}
  ~HidapiTransport() override { hid_close(device_); }
  HidapiTransport(const HidapiTransport&) = delete;
  HidapiTransport& operator=(const HidapiTransport&) = delete;
  int read(std::uint8_t* buffer, std::size_t capacity, int timeout_ms) override {
    return hid_read_timeout(device_, buffer, capacity, timeout_ms);
  }
  std::string error() const override {
    const std::string text = narrow(hid_error(device_));
    return text.empty() ? std::string("no reason given (the device was probably unplugged)") : text;
  }

 private:
  hid_device* device_;
};

}  // namespace

HidEnumeration enumerate_hid() {
  HidEnumeration out;
  if (!hid_ready(out.note)) return out;
  hid_device_info* list = hid_enumerate(0, 0);
  for (const hid_device_info* d = list; d; d = d->next) {
    HidDeviceInfo info;
    info.path = d->path ? d->path : "";
    info.vendor = d->vendor_id;
    info.product = d->product_id;
    info.serial = narrow(d->serial_number);
    info.product_name = narrow(d->product_string);
    info.interface_number = d->interface_number;
    info.usage_page = d->usage_page;
    info.usage = d->usage;
    out.devices.push_back(std::move(info));
  }
  hid_free_enumeration(list);
  if (!list) {
    // hidraw lists nothing rather than failing when no node exists or none is readable.
    out.note = "no HID devices visible (no /dev/hidraw* nodes, or none this user may read)";
  }
  return out;
}

std::unique_ptr<HidTransport> open_hid(const std::string& path, const std::string& device_id) {
  std::string why;
  if (!hid_ready(why)) throw DeviceError(device_id, "open", why);
  hid_device* device = hid_open_path(path.c_str());
  if (!device) {
    std::string reason = "cannot open ";
    reason += path;
    reason += ": ";
    reason += narrow(hid_error(nullptr));
    reason += " (permission? install packaging/udev/70-palpa.rules, see docs/devices.md)";
    throw DeviceError(device_id, "open", reason);
  }
  return std::make_unique<HidapiTransport>(device);
}

}  // namespace palpa::device
