#include "gui_device.hpp"

#include <cstdio>

#include "palpa/device/registry.hpp"

namespace palpa::gui {

std::shared_ptr<engine::Device> open_chosen_device(const DeviceChoice& choice) {
  if (choice.id.empty() || choice.id == "virtual") return nullptr;
  device::OpenOptions options;
  if (!choice.falcon_firmware.empty()) options.falcon.firmware = choice.falcon_firmware;
  options.progress = [](const std::string& line) { std::fprintf(stderr, "palpa: %s\n", line.c_str()); };
  return device::open_device(choice.id, options);
}

}  // namespace palpa::gui
