#include "palpa/engine/virtual_device.hpp"

#include <algorithm>
#include <cmath>

namespace palpa::engine {

VirtualDevice::VirtualDevice(double settling_time, double max_force)
    // A critically damped follower settles to 2 % in about 5.8 / omega.
    : omega_(settling_time > 0.0 ? 5.8 / settling_time : 0.0) {
  caps_.name = "virtual (mouse)";
  caps_.max_force = max_force;
  caps_.workspace_radius = 1.0;
  caps_.force_output = false;
}

void VirtualDevice::set_target(const Vec3& target, std::uint32_t buttons) noexcept {
  target_.write_slot() = Target{target.x(), target.y(), target.z(), buttons};
  target_.publish();
}

DeviceStatus VirtualDevice::read(double t, DevicePose& pose) noexcept {
  target_.update();
  const Target& latest = target_.read();
  const std::uint32_t buttons = latest.buttons;
  const Vec3 target(latest.x, latest.y, latest.z);
  if (last_t_ < 0.0 || omega_ == 0.0) {
    position_ = target;
    velocity_.setZero();
  } else {
    // Exact step of the critically damped follower x'' = -w^2 (x - target) - 2 w x' over dt.
    const double dt = std::max(0.0, t - last_t_);
    const double e = std::exp(-omega_ * dt);
    const Vec3 offset = position_ - target;
    const Vec3 c = velocity_ + omega_ * offset;
    position_ = target + (offset + c * dt) * e;
    velocity_ = (c - omega_ * (offset + c * dt)) * e;
  }
  const double dt = last_t_ < 0.0 ? 0.0 : std::max(0.0, t - last_t_);
  last_t_ = t;
  pose.position = position_ + give_way(dt);
  pose.buttons = buttons;
  return DeviceStatus::Ok;
}

Vec3 VirtualDevice::give_way(double dt) noexcept {
  if (limit_ <= 0.0) return Vec3::Zero();
  // m per N of excess per second: the tissue under a fingertip is 0.2-5 N/mm, so one tick
  // (1 ms, the force written last tick) corrects 3-75 % of the excess: fast, and stable.
  constexpr double kGain = 0.15;
  const Vec3 force = last_force();
  const double magnitude = force.norm();
  if (magnitude > 1e-9) yield_direction_ = force / magnitude;
  yield_ = std::max(0.0, yield_ + kGain * (magnitude - limit_) * std::min(dt, 0.002));
  yielded_.store(yield_, std::memory_order_relaxed);
  return yield_ * yield_direction_;
}

DeviceStatus VirtualDevice::write_force(const Vec3& force) noexcept {
  fx_.store(force.x(), std::memory_order_relaxed);
  fy_.store(force.y(), std::memory_order_relaxed);
  fz_.store(force.z(), std::memory_order_relaxed);
  return DeviceStatus::Ok;
}

Vec3 VirtualDevice::last_force() const noexcept {
  return {fx_.load(std::memory_order_relaxed), fy_.load(std::memory_order_relaxed),
          fz_.load(std::memory_order_relaxed)};
}

Vec3 Trajectory::at(double time) const {
  if (t.empty()) return Vec3::Zero();
  if (time <= t.front()) return position.front();
  if (time >= t.back()) return position.back();
  const auto it = std::upper_bound(t.begin(), t.end(), time);
  const auto k = static_cast<std::size_t>(it - t.begin());
  const double a = (time - t[k - 1]) / (t[k] - t[k - 1]);
  return position[k - 1] + a * (position[k] - position[k - 1]);
}

ScriptedDevice::ScriptedDevice(Trajectory trajectory, double max_force) : trajectory_(std::move(trajectory)) {
  caps_.name = "scripted";
  caps_.max_force = max_force;
  caps_.workspace_radius = 1.0;
  caps_.force_output = true;
}

DeviceStatus ScriptedDevice::read(double time, DevicePose& pose) noexcept {
  const auto& tt = trajectory_.t;
  if (tt.empty()) {
    pose.position.setZero();
    return DeviceStatus::Ok;
  }
  // Playback moves forward: continue the search from the last segment (no log n per tick).
  if (cursor_ >= tt.size() || tt[cursor_] > time) cursor_ = 0;
  while (cursor_ + 1 < tt.size() && tt[cursor_ + 1] <= time) ++cursor_;
  if (time <= tt.front()) {
    pose.position = trajectory_.position.front();
  } else if (cursor_ + 1 >= tt.size()) {
    pose.position = trajectory_.position.back();
  } else {
    const double a = (time - tt[cursor_]) / (tt[cursor_ + 1] - tt[cursor_]);
    pose.position = trajectory_.position[cursor_] + a * (trajectory_.position[cursor_ + 1] - trajectory_.position[cursor_]);
  }
  pose.buttons = 0;
  return DeviceStatus::Ok;
}

DeviceStatus ScriptedDevice::write_force(const Vec3& force) noexcept {
  force_ = force;
  return DeviceStatus::Ok;
}

}  // namespace palpa::engine
