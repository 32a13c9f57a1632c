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
  /// A finger that gives way: while the force the engine wrote exceeds `newtons` the probe
  /// yields along it, at the haptic rate, until it no longer does, and comes back as the
  /// force falls (integral control on the excess). The mouse's finger so never presses
  /// past the bound between two GUI frames, however fast it slides onto a stiff lump. 0 (the
  /// default): no yield. Set before the haptic loop starts.
  void set_force_limit(double newtons) noexcept { limit_ = newtons > 0.0 ? newtons : 0.0; }
  /// m: how far the probe has given way (0 when the force is under the limit); any thread.
  double yielded() const noexcept { return yielded_.load(std::memory_order_relaxed); }

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
  double limit_ = 0.0;        // N, set_force_limit
  double yield_ = 0.0;        // m along yield_direction_
  Vec3 yield_direction_ = Vec3::UnitZ();
  std::atomic<double> yielded_{0.0};
  Vec3 give_way(double dt) noexcept;
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
