#include "palpa/engine/fallback_device.hpp"

namespace palpa::engine {

FallbackDevice::FallbackDevice(Device* primary, VirtualDevice& fallback, double hold_time)
    : primary_(primary),
      fallback_(&fallback),
      hold_time_(hold_time > 0.0 ? hold_time : 0.0),
      state_(primary ? State::Primary : State::Fallback) {
  if (!primary_) on_fallback_.store(true, std::memory_order_relaxed);
}

const DeviceCapabilities& FallbackDevice::capabilities() const {
  return primary_ ? primary_->capabilities() : fallback_->capabilities();
}

const std::string& FallbackDevice::active_name() const {
  return on_fallback() ? fallback_->capabilities().name : primary_->capabilities().name;
}

void FallbackDevice::place_workspace(const Vec3& scene_center, double scale) {
  if (primary_) primary_->place_workspace(scene_center, scale);
}

std::string FallbackDevice::fault_message() const {
  return primary_ && switched() ? primary_->fault_message() : std::string();
}

DeviceStatus FallbackDevice::read(double t, DevicePose& pose) noexcept {
  if (state_ == State::Primary) {
    const DeviceStatus status = primary_->read(t, pose);
    if (status == DeviceStatus::Ok && pose.position.allFinite()) {
      last_ = pose;
      return DeviceStatus::Ok;
    }
    // Let the primary go: no more force to it (it may still hear us, e.g. a driver error
    // with the cable in), hold the last pose while the force ramps down.
    primary_->write_force(Vec3::Zero());
    state_ = State::Holding;
    switch_status_ = status == DeviceStatus::Ok ? DeviceStatus::Error : status;  // non-finite pose: an error
    switched_at_ = t;
    last_published_ = last_.position;
    switched_.store(true, std::memory_order_release);
  }
  if (state_ == State::Holding) {
    if (!resume_.load(std::memory_order_acquire) || t - switched_at_ < hold_time_) {
      pose.position = last_.position;
      pose.buttons = 0;
      return DeviceStatus::Disconnected;
    }
    state_ = State::Fallback;
    on_fallback_.store(true, std::memory_order_release);
  }
  return fallback_->read(t, pose);
}

DeviceStatus FallbackDevice::write_force(const Vec3& force) noexcept {
  switch (state_) {
    case State::Primary: return primary_->write_force(force);
    case State::Holding: return DeviceStatus::Ok;  // the primary is gone; the force ramps down meanwhile
    case State::Fallback: break;
  }
  return fallback_->write_force(force);
}

}  // namespace palpa::engine
