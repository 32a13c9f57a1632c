#include "palpa/engine/stalling_device.hpp"

#include <algorithm>
#include <chrono>
#include <thread>

namespace palpa::engine {

StallingDevice::StallingDevice(Device& inner, const StallOptions& options)
    : inner_(&inner), options_(options), state_(options.seed * 0x9E3779B97F4A7C15ULL + 1) {
  schedule_burst(options_.quiet_until);
  schedule_fault(options_.quiet_until);
}

double StallingDevice::uniform() noexcept {
  state_ ^= state_ << 13;
  state_ ^= state_ >> 7;
  state_ ^= state_ << 17;
  return static_cast<double>(state_ >> 11) * 0x1.0p-53;
}

void StallingDevice::schedule_burst(double t) noexcept {
  next_stall_ = t + (0.5 + uniform()) * options_.burst_every;
  left_in_burst_ = 1 + static_cast<int>(uniform() * std::max(1, options_.burst_stalls));
}

void StallingDevice::schedule_fault(double t) noexcept {
  next_fault_ = options_.fault_every > 0.0 ? t + (0.5 + uniform()) * options_.fault_every : 1e300;
}

DeviceStatus StallingDevice::read(double t, DevicePose& pose) noexcept {
  if (t >= next_stall_) {
    const double length = options_.stall_min + uniform() * (options_.stall_max - options_.stall_min);
    std::this_thread::sleep_for(std::chrono::duration<double>(length));  // the injected stall
    ++stalls_;
    // The next stall of the burst a few ticks later, or the next burst.
    if (--left_in_burst_ > 0) {
      next_stall_ = t + length + 0.005 + 0.02 * uniform();
    } else {
      schedule_burst(t);
    }
  }
  if (t >= next_fault_) {
    fault_until_ = t + options_.fault_length;
    ++faults_;
    schedule_fault(t);
  }
  const DeviceStatus status = inner_->read(t, pose);  // the wrapped device keeps its own time
  return t < fault_until_ ? DeviceStatus::Error : status;
}

DeviceStatus StallingDevice::write_force(const Vec3& force) noexcept { return inner_->write_force(force); }

}  // namespace palpa::engine
