#pragma once
// The device a trainee window palpates with, chosen by id (palpa --device, the Device menu):
// "virtual" is the mouse; anything else is opened through device/'s registry.
#include <functional>
#include <memory>
#include <string>

#include "palpa/engine/device.hpp"

class QWidget;

namespace palpa::gui {

struct DeviceChoice {
  std::string id = "virtual";   ///< an id from palpa-cli devices (device/registry.hpp)
  std::string falcon_firmware;  ///< the firmware file a Novint Falcon needs (the user supplies it)
};

/// The opened device, or null for the virtual one (LiveExercise then uses its own). Progress
/// lines (a Falcon's firmware upload and homing) go to `progress`, or to stderr without one;
/// it is called on the opening thread. Throws device::DeviceError or session::SessionError
/// (a replay of a bad session) with one line naming the device.
std::shared_ptr<engine::Device> open_chosen_device(const DeviceChoice& choice,
                                                   std::function<void(const std::string&)> progress = {});

/// open_chosen_device on a worker thread while the GUI stays responsive, with the progress
/// lines in a dialog over `parent` (opening a Falcon can take a minute: firmware upload and
/// homing). Throws what open_chosen_device throws.
std::shared_ptr<engine::Device> open_chosen_device_with_progress(const DeviceChoice& choice, QWidget* parent);

}  // namespace palpa::gui
