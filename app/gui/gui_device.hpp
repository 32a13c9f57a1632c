#pragma once
// The device a trainee window palpates with, chosen by id (palpa --device, the Device menu):
// "virtual" is the mouse; anything else is opened through device/'s registry.
#include <memory>
#include <string>

#include "palpa/engine/device.hpp"

namespace palpa::gui {

struct DeviceChoice {
  std::string id = "virtual";   ///< an id from palpa-cli devices (device/registry.hpp)
  std::string falcon_firmware;  ///< the firmware file a Novint Falcon needs (the user supplies it)
};

/// The opened device, or null for the virtual one (LiveExercise then uses its own). Progress
/// lines (a Falcon's firmware upload and homing) go to stderr. Throws device::DeviceError or
/// session::SessionError (a replay of a bad session) with one line naming the device.
std::shared_ptr<engine::Device> open_chosen_device(const DeviceChoice& choice);

}  // namespace palpa::gui
