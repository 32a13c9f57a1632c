#pragma once
// A device that palpates where it is told and is "unplugged" at a given haptic time: the
// stand-in for a SpaceMouse or Falcon whose cable is pulled mid-exercise.
#include <atomic>
#include <string>

#include "palpa/engine/device.hpp"

namespace palpa::device::test {

class UnpluggedAt final : public engine::Device {
 public:
  UnpluggedAt(palpa::Vec3 position, double unplug_at) : position_(position), unplug_at_(unplug_at) {
    caps_.name = "test SpaceMouse";
    caps_.max_force = 30.0;
  }
  const engine::DeviceCapabilities& capabilities() const override { return caps_; }
  engine::DeviceStatus read(double t, engine::DevicePose& pose) noexcept override {
    if (t >= unplug_at_) {
      gone_.store(true);
      return engine::DeviceStatus::Disconnected;
    }
    pose.position = position_ + placed_;
    pose.buttons = 0;
    return engine::DeviceStatus::Ok;
  }
  engine::DeviceStatus write_force(const palpa::Vec3& force) noexcept override {
    last_force_ = force;
    return gone_.load() ? engine::DeviceStatus::Disconnected : engine::DeviceStatus::Ok;
  }
  void place_workspace(const palpa::Vec3& center, double /*scale*/) override { placed_ = center; }
  std::string fault_message() const override { return gone_.load() ? "test SpaceMouse: cable pulled" : ""; }
  palpa::Vec3 last_force_ = palpa::Vec3::Zero();
  palpa::Vec3 placed_ = palpa::Vec3::Zero();

 private:
  engine::DeviceCapabilities caps_;
  palpa::Vec3 position_;
  double unplug_at_;
  std::atomic<bool> gone_{false};
};

}  // namespace palpa::device::test
