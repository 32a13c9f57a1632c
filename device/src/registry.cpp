#include "palpa/device/registry.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "palpa/device/device_error.hpp"
#include "palpa/device/device_ids.hpp"
#include "palpa/device/replay_device.hpp"
#include "palpa/engine/virtual_device.hpp"

namespace palpa::device {

namespace {

std::string hex4(std::uint16_t value) { return fmt::format("{:04x}", value); }

// A SpaceMouse shows several HID interfaces on some receivers; the probe wants the
// multi-axis controller (usage page 0x01, usage 0x08). Backends that cannot tell (0) pass.
bool is_axis_interface(const HidDeviceInfo& d) {
  return d.usage_page == 0 || (d.usage_page == 0x01 && d.usage == 0x08);
}

struct Found {
  DeviceEntry entry;
  HidDeviceInfo hid;
  UsbDeviceInfo usb;
};

std::vector<Found> find_all(const Enumerators& enumerators, std::vector<std::string>& notes) {
  std::vector<Found> found;
  Found virtual_device;
  virtual_device.entry = {"virtual", "virtual", "virtual (mouse)", false, ""};
  found.push_back(virtual_device);

  HidEnumeration hid = enumerators.hid ? enumerators.hid() : HidEnumeration{};
  if (!hid.note.empty()) notes.push_back("SpaceMouse: " + hid.note);
  std::vector<Found> mice;
  for (const auto& d : hid.devices) {
    const UsbId* model = find_spacemouse(d.vendor, d.product);
    if (!model || !is_axis_interface(d)) continue;
    // One device seen twice (another of its interfaces, where the backend cannot tell
    // usages): the same serial, or no serial and another interface number. Two identical
    // devices without serials have the same interface number: both are listed.
    bool same_device = false;
    for (const auto& m : mice) {
      same_device = same_device || (m.hid.vendor == d.vendor && m.hid.product == d.product && m.hid.serial == d.serial &&
                                    (!d.serial.empty() || m.hid.interface_number != d.interface_number));
    }
    if (same_device) continue;
    Found f;
    f.entry.id = "spacemouse:" + hex4(d.vendor) + ":" + hex4(d.product);
    if (!d.serial.empty()) f.entry.id += ":" + d.serial;
    f.entry.kind = "spacemouse";
    f.entry.name = model->model;
    f.entry.force_output = false;
    f.entry.detail = d.path;
    f.hid = d;
    mice.push_back(std::move(f));
  }
  // Identical models without serial numbers would share an id: tell them apart by their
  // hidraw node (in the serial's place), which can change when they are plugged again.
  bool told_apart = false;
  for (auto& f : mice) {
    if (!f.hid.serial.empty()) continue;
    bool twin = false;
    for (const auto& m : mice) {
      twin = twin || (&m != &f && m.hid.serial.empty() && m.hid.vendor == f.hid.vendor && m.hid.product == f.hid.product);
    }
    if (!twin) continue;
    f.entry.id += ":";
    f.entry.id += std::filesystem::path(f.hid.path).filename().string();
    told_apart = true;
  }
  if (told_apart) {
    notes.push_back("SpaceMouse: identical models without serial numbers are told apart by their /dev/hidraw node "
                    "(the id may change when they are plugged in again)");
  }
  for (auto& f : mice) found.push_back(std::move(f));

  UsbEnumeration usb = enumerators.usb ? enumerators.usb(kFalconId.vendor, kFalconId.product) : UsbEnumeration{};
  if (!usb.note.empty()) notes.push_back("Falcon: " + usb.note);
  for (const auto& d : usb.devices) {
    Found f;
    f.entry.id = "falcon:" + d.port_path;
    f.entry.kind = "falcon";
    f.entry.name = kFalconId.model;
    f.entry.force_output = true;
    f.entry.detail = "USB " + d.port_path;
    f.usb = d;
    found.push_back(std::move(f));
  }
  return found;
}

// "spacemouse:046d:c626" matches "spacemouse:046d:c626:SERIAL"; "spacemouse" the first.
const Found* match(const std::vector<Found>& found, const std::string& id, const std::string& kind) {
  for (const auto& f : found) {
    if (f.entry.kind != kind) continue;
    if (id == kind || f.entry.id == id) return &f;
    if (f.entry.id.compare(0, id.size(), id) == 0 && f.entry.id.size() > id.size() && f.entry.id[id.size()] == ':') {
      return &f;
    }
  }
  return nullptr;
}

std::unique_ptr<engine::Device> open_falcon(const Found& f, const std::string& id, const OpenOptions& options) {
  const auto say = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };
  auto falcon = std::make_unique<FalconDevice>(open_usb(f.usb.port_path, f.usb.vendor, f.usb.product, id), id,
                                               options.falcon);
  say(options.falcon.firmware.empty() ? "Falcon: looking for running firmware"
                                      : "Falcon: uploading firmware " + options.falcon.firmware.string());
  falcon->connect();
  falcon->start();
  if (options.homing_timeout > 0.0 && !falcon->homed()) {
    say("Falcon: homing: move the grip all the way out and back in");
    falcon->wait_homed(options.homing_timeout);  // throws with the device's reason
  }
  return falcon;
}

}  // namespace

DeviceListing list_devices(const Enumerators& enumerators) {
  DeviceListing listing;
  for (auto& f : find_all(enumerators, listing.notes)) listing.devices.push_back(std::move(f.entry));
  return listing;
}

std::unique_ptr<engine::Device> open_device(const std::string& id, const OpenOptions& options,
                                            const Enumerators& enumerators) {
  if (id == "virtual") return std::make_unique<engine::VirtualDevice>(options.virtual_settling);
  if (id.rfind("replay:", 0) == 0) {
    const std::string path = id.substr(7);
    if (path.empty()) throw DeviceError(id, "id", "replay needs a session file: replay:SESSION");
    return ReplayDevice::from_file(path);
  }
  const bool spacemouse = id == "spacemouse" || id.rfind("spacemouse:", 0) == 0;
  const bool falcon = id == "falcon" || id.rfind("falcon:", 0) == 0;
  if (!spacemouse && !falcon) {
    throw DeviceError(id, "id", "unknown device (virtual, spacemouse[:VID:PID[:SERIAL]], falcon[:PORT] or "
                                "replay:SESSION; palpa-cli devices lists what is attached)");
  }
  std::vector<std::string> notes;
  const auto found = find_all(enumerators, notes);
  const Found* f = match(found, id, spacemouse ? "spacemouse" : "falcon");
  if (!f) {
    std::string reason = "not attached";
    for (const auto& note : notes) {
      reason += "; ";
      reason += note;
    }
    throw DeviceError(id, "open", reason + " (palpa-cli devices lists what is attached)");
  }
  if (falcon) return open_falcon(*f, f->entry.id, options);
  auto device = std::make_unique<SpaceMouseDevice>(open_hid(f->hid.path, f->entry.id),
                                                   report_layout(f->hid.vendor, f->hid.product), f->entry.name,
                                                   options.spacemouse);
  device->start();
  return device;
}

}  // namespace palpa::device
