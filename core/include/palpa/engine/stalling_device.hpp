#pragma once
// A fault-injection device for tests and acceptance runs, never for training: it wraps
// another device and, on a fixed pseudo-random schedule, blocks inside read() for 20-50 ms
// in bursts (the haptic loop stalls, as on a loaded machine or with a blocked driver) and
// now and then reports a device error for a few ticks (a real fault: the force ramps to
// zero). Between the events every read and write goes to the wrapped device unchanged, so
// the pointer still steers a wrapped virtual device. Blocking in read() breaks the
// real-time rule on purpose: that is the fault it injects.
#include <cstdint>

#include "palpa/engine/device.hpp"

namespace palpa::engine {

struct StallOptions {
  std::uint64_t seed = 1;
  double quiet_until = 1.0;      ///< s of haptic time before the first event
  double burst_every = 0.4;      ///< s between bursts of stalls, on average
  int burst_stalls = 3;          ///< stalls per burst, at most
  double stall_min = 0.020;      ///< s, the shortest stall
  double stall_max = 0.050;      ///< s, the longest stall
  double fault_every = 1.5;      ///< s between device faults, on average (0: no faults)
  double fault_length = 0.030;   ///< s a fault lasts
};

class StallingDevice final : public Device {
 public:
  /// `inner` must outlive this object.
  StallingDevice(Device& inner, const StallOptions& options = {});

  const DeviceCapabilities& capabilities() const override { return inner_->capabilities(); }
  DeviceStatus read(double t, DevicePose& pose) noexcept override;
  DeviceStatus write_force(const Vec3& force) noexcept override;
  void place_workspace(const Vec3& scene_center, double scale) override { inner_->place_workspace(scene_center, scale); }
  std::string fault_message() const override { return "injected fault (StallingDevice)"; }

  /// Events injected so far (haptic thread; read after the loop stopped).
  int stalls() const { return stalls_; }
  int faults() const { return faults_; }

 private:
  double uniform() noexcept;  // [0, 1), xorshift: no allocation
  void schedule_burst(double t) noexcept;
  void schedule_fault(double t) noexcept;

  Device* inner_;
  StallOptions options_;
  std::uint64_t state_;
  double next_stall_ = 0.0;
  int left_in_burst_ = 0;
  double next_fault_ = 0.0;
  double fault_until_ = -1.0;
  int stalls_ = 0;
  int faults_ = 0;
};

}  // namespace palpa::engine
