// The USB transport over libusb-1.0: one context per open device, interface 0 claimed,
// the kernel's serial driver detached while Palpa holds the device.
#include "palpa/device/usb_transport.hpp"

#include <cstdio>
#include <filesystem>

#include <fmt/format.h>
#include <libusb.h>

#include "palpa/device/device_error.hpp"

namespace palpa::device {

const char* to_string(UsbStatus status) {
  switch (status) {
    case UsbStatus::Ok: return "ok";
    case UsbStatus::Timeout: return "timed out";
    case UsbStatus::NoDevice: return "device unplugged";
    case UsbStatus::Access: return "permission denied (install packaging/udev/70-palpa.rules, see docs/devices.md)";
    case UsbStatus::Busy: return "busy (held by another program or another Palpa window)";
    case UsbStatus::Pipe: return "endpoint stalled";
    case UsbStatus::Overflow: return "the device sent more than asked";
    case UsbStatus::Io: return "input/output error";
    case UsbStatus::Other: break;
  }
  return "USB error";
}

namespace {

UsbStatus status_of(int code) {
  switch (code) {
    case LIBUSB_SUCCESS: return UsbStatus::Ok;
    case LIBUSB_ERROR_TIMEOUT: return UsbStatus::Timeout;
    case LIBUSB_ERROR_NO_DEVICE: return UsbStatus::NoDevice;
    case LIBUSB_ERROR_ACCESS: return UsbStatus::Access;
    case LIBUSB_ERROR_BUSY: return UsbStatus::Busy;
    case LIBUSB_ERROR_PIPE: return UsbStatus::Pipe;
    case LIBUSB_ERROR_OVERFLOW: return UsbStatus::Overflow;
    case LIBUSB_ERROR_IO: return UsbStatus::Io;
    default: return UsbStatus::Other;
  }
}

std::string port_path_of(libusb_device* device) {
  std::string path = fmt::format("{}", libusb_get_bus_number(device));
  std::uint8_t ports[8];
  const int n = libusb_get_port_numbers(device, ports, 8);
  for (int k = 0; k < n; ++k) path += fmt::format("{}{}", k == 0 ? '-' : '.', ports[k]);
  return path;
}

class Context {
 public:
  Context() : code_(libusb_init(&ctx_)) {}
  ~Context() {
    if (code_ == 0) libusb_exit(ctx_);
  }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  bool ok() const { return code_ == 0; }
  int code() const { return code_; }
  libusb_context* get() const { return ctx_; }

 private:
  libusb_context* ctx_ = nullptr;
  int code_;
};

class LibusbTransport final : public UsbTransport {
 public:
  LibusbTransport(std::unique_ptr<Context> context, libusb_device_handle* handle)
      : context_(std::move(context)), handle_(handle) {}
  ~LibusbTransport() override {
    libusb_release_interface(handle_, 0);
    libusb_close(handle_);
  }
  LibusbTransport(const LibusbTransport&) = delete;
  LibusbTransport& operator=(const LibusbTransport&) = delete;

  UsbStatus control_out(std::uint8_t request, std::uint16_t value, std::uint16_t index, unsigned timeout_ms) override {
    const int r = libusb_control_transfer(handle_, 0x40, request, value, index, nullptr, 0, timeout_ms);
    return r < 0 ? status_of(r) : UsbStatus::Ok;
  }
  UsbStatus bulk_write(const std::uint8_t* data, std::size_t size, std::size_t& written, unsigned timeout_ms) override {
    int done = 0;
    // libusb takes a non-const buffer for both directions; an OUT transfer only reads it.
    const int r = libusb_bulk_transfer(handle_, 0x02, const_cast<std::uint8_t*>(data), static_cast<int>(size), &done,
                                       timeout_ms);
    written = static_cast<std::size_t>(done);
    return status_of(r);
  }
  UsbStatus bulk_read(std::uint8_t* data, std::size_t capacity, std::size_t& got, unsigned timeout_ms) override {
    int done = 0;
    const int r = libusb_bulk_transfer(handle_, 0x81, data, static_cast<int>(capacity), &done, timeout_ms);
    got = static_cast<std::size_t>(done);
    return r == LIBUSB_ERROR_TIMEOUT && done > 0 ? UsbStatus::Ok : status_of(r);
  }

 private:
  std::unique_ptr<Context> context_;
  libusb_device_handle* handle_;
};

std::string no_usb_note() {
  std::error_code ec;
  if (!std::filesystem::exists("/dev/bus/usb", ec)) return "no USB device list: /dev/bus/usb is absent (a container?)";
  return "no USB device list: /dev/bus/usb cannot be read by this user";
}

}  // namespace

UsbEnumeration enumerate_usb(std::uint16_t vendor, std::uint16_t product) {
  UsbEnumeration out;
  Context context;
  if (!context.ok()) {
    out.note = no_usb_note();
    return out;
  }
  libusb_device** list = nullptr;
  const ssize_t n = libusb_get_device_list(context.get(), &list);
  if (n < 0) {
    out.note = no_usb_note();
    return out;
  }
  if (n == 0) {
    std::error_code ec;
    if (!std::filesystem::exists("/dev/bus/usb", ec)) out.note = no_usb_note();
  }
  for (ssize_t k = 0; k < n; ++k) {
    libusb_device_descriptor descriptor{};
    if (libusb_get_device_descriptor(list[k], &descriptor) != 0) continue;
    if (descriptor.idVendor != vendor || descriptor.idProduct != product) continue;
    UsbDeviceInfo info;
    info.bus = libusb_get_bus_number(list[k]);
    info.address = libusb_get_device_address(list[k]);
    info.port_path = port_path_of(list[k]);
    info.vendor = descriptor.idVendor;
    info.product = descriptor.idProduct;
    out.devices.push_back(info);
  }
  libusb_free_device_list(list, 1);
  return out;
}

std::unique_ptr<UsbTransport> open_usb(const std::string& port_path, std::uint16_t vendor, std::uint16_t product,
                                       const std::string& device_id) {
  auto context = std::make_unique<Context>();
  if (!context->ok()) throw DeviceError(device_id, "open", no_usb_note());
  libusb_device** list = nullptr;
  const ssize_t n = libusb_get_device_list(context->get(), &list);
  if (n < 0) throw DeviceError(device_id, "open", no_usb_note());
  libusb_device* found = nullptr;
  for (ssize_t k = 0; k < n && !found; ++k) {
    libusb_device_descriptor descriptor{};
    if (libusb_get_device_descriptor(list[k], &descriptor) != 0) continue;
    if (descriptor.idVendor == vendor && descriptor.idProduct == product && port_path_of(list[k]) == port_path) {
      found = list[k];
    }
  }
  libusb_device_handle* handle = nullptr;
  const int r = found ? libusb_open(found, &handle) : LIBUSB_ERROR_NOT_FOUND;
  libusb_free_device_list(list, 1);
  if (!found) throw DeviceError(device_id, "open", "not attached (run palpa-cli devices)");
  if (r != 0) throw DeviceError(device_id, "open", to_string(status_of(r)));
  libusb_set_auto_detach_kernel_driver(handle, 1);  // the kernel's ftdi_sio may have claimed it
  const int claim = libusb_claim_interface(handle, 0);
  if (claim != 0) {
    libusb_close(handle);
    throw DeviceError(device_id, "claim interface 0", to_string(status_of(claim)));
  }
  return std::make_unique<LibusbTransport>(std::move(context), handle);
}

}  // namespace palpa::device
