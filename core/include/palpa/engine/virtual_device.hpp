#pragma once
// Devices without hardware: the virtual device follows a target set from another thread
// (the GUI's mouse) through a small mass-damper, so the probe moves smoothly; the
// scripted device plays a trajectory.
#include <atomic>
#include <vector>

#include "palpa/engine/device.hpp"
#include "palpa/engine/triple_buffer.hpp"

namespace palpa::engine {

class VirtualDevice final : public Device {
 public:
  /// The probe follows the target like a mass on a critically damped spring with the
  /// given settling time (s); 0 makes it jump to the target.
  explicit VirtualDevice(double settling_time = 0.03, double max_force = 30.0);

  const DeviceCapabilities& capabilities() const override { return caps_; }
  DeviceStatus read(double t, DevicePose& pose) noexcept override;
  DeviceStatus write_force(const Vec3& force) noexcept override;

  /// From one other thread (the GUI): where the probe should go (m) and the buttons. The
  /// haptic thread always sees a whole target, never x from one call and y from another.
  void set_target(const Vec3& target, std::uint32_t buttons = 0) noexcept;
  /// The last force the engine wrote (for display).
  Vec3 last_force() const noexcept;

 private:
  DeviceCapabilities caps_;
  double omega_;  // natural frequency of the critically damped follower
  struct Target {
    double x = 0.0, y = 0.0, z = 0.0;
    std::uint32_t buttons = 0;
  };
  TripleBuffer<Target> target_{Target{}};
  std::atomic<double> fx_{0.0}, fy_{0.0}, fz_{0.0};
  Vec3 position_ = Vec3::Zero();
  Vec3 velocity_ = Vec3::Zero();
  double last_t_ = -1.0;
};

/// A probe trajectory: times (s, increasing) and positions (m), linear in between, held
/// at the ends.
struct Trajectory {
  std::vector<double> t;
  std::vector<Vec3> position;
  double duration() const { return t.empty() ? 0.0 : t.back(); }
  Vec3 at(double time) const;
};

class ScriptedDevice final : public Device {
 public:
  explicit ScriptedDevice(Trajectory trajectory, double max_force = 30.0);
  const DeviceCapabilities& capabilities() const override { return caps_; }
  DeviceStatus read(double t, DevicePose& pose) noexcept override;
  DeviceStatus write_force(const Vec3& force) noexcept override;
  const Trajectory& trajectory() const { return trajectory_; }
  Vec3 last_force() const { return force_; }

 private:
  DeviceCapabilities caps_;
  Trajectory trajectory_;
  mutable std::size_t cursor_ = 0;  // segment of the last lookup: playback is monotone
  Vec3 force_ = Vec3::Zero();
};

}  // namespace palpa::engine
