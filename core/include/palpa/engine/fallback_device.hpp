#pragma once
// A chosen device with the virtual device behind it. While the chosen (primary) device
// reads Ok it is the device. The first time it reads Error or Disconnected (a cable
// pulled, a driver fault) the fallback switches over for good:
//  1. it holds the probe at the primary's last pose and reports Disconnected, so the
//     engine's ForceGovernor ramps the force to zero (at least `hold_time`, s);
//  2. another thread (the GUI) sees switched(), points the virtual device at
//     last_position() and calls resume();
//  3. from then on (and not before hold_time has passed) the virtual device is the device,
//     starting at that pose: the session goes on without a jump.
// read() and write_force() belong to the haptic thread and stay allocation-, lock- and
// wait-free; the accessors may be called from any thread.
#include <atomic>

#include "palpa/engine/device.hpp"
#include "palpa/engine/virtual_device.hpp"

namespace palpa::engine {

class FallbackDevice final : public Device {
 public:
  /// `primary` may be null: then the virtual device is the device from the start. Both
  /// must outlive this object.
  FallbackDevice(Device* primary, VirtualDevice& fallback, double hold_time = 0.1);

  /// The primary's capabilities (the engine sizes its force cap from them), or the
  /// virtual device's when there is no primary.
  const DeviceCapabilities& capabilities() const override;
  DeviceStatus read(double t, DevicePose& pose) noexcept override;
  DeviceStatus write_force(const Vec3& force) noexcept override;
  void place_workspace(const Vec3& scene_center, double scale) override;
  std::string fault_message() const override;

  Device* primary() const { return primary_; }
  /// The primary faulted and was let go (any thread).
  bool switched() const noexcept { return switched_.load(std::memory_order_acquire); }
  /// Why: Error or Disconnected (meaningful once switched()).
  DeviceStatus switch_status() const noexcept { return switch_status_; }
  /// Haptic time of the switch, s, and the primary's last good position, m (both
  /// meaningful once switched()).
  double switched_at() const noexcept { return switched_at_; }
  Vec3 last_position() const noexcept { return last_published_; }
  /// Lets the virtual device take over (after hold_time). Call after pointing it at
  /// last_position().
  void resume() noexcept { resume_.store(true, std::memory_order_release); }
  /// The virtual device is the device now.
  bool on_fallback() const noexcept { return on_fallback_.load(std::memory_order_acquire); }
  /// The name of the device in use: the primary's until the switch, then the virtual one's.
  const std::string& active_name() const;

 private:
  enum class State : std::uint8_t { Primary, Holding, Fallback };
  Device* primary_;
  VirtualDevice* fallback_;
  double hold_time_;
  State state_;                 // haptic thread only
  DevicePose last_{};           // haptic thread only
  // Written by the haptic thread before the release store of switched_, read after an
  // acquire load of it: no race.
  DeviceStatus switch_status_ = DeviceStatus::Ok;
  double switched_at_ = 0.0;
  Vec3 last_published_ = Vec3::Zero();
  std::atomic<bool> switched_{false};
  std::atomic<bool> resume_{false};
  std::atomic<bool> on_fallback_{false};
};

}  // namespace palpa::engine
