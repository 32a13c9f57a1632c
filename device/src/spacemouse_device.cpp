#include "palpa/device/spacemouse_device.hpp"

#include <algorithm>
#include <cmath>

namespace palpa::device {

SpaceMouseDevice::SpaceMouseDevice(std::unique_ptr<HidTransport> transport, ReportLayout layout, std::string name,
                                   const SpaceMouseOptions& options)
    : transport_(std::move(transport)), layout_(layout), options_(options) {
  caps_.name = std::move(name);
  caps_.max_force = 30.0;  // nothing is felt: the engine's own cap decides what is shown
  caps_.force_output = false;
  caps_.workspace_radius = options_.workspace_radius;
}

SpaceMouseDevice::~SpaceMouseDevice() { stop(); }

void SpaceMouseDevice::start() {
  if (thread_.joinable()) return;
  stop_.store(false);
  thread_ = std::thread([this] {
    // 50 ms: short enough to notice stop() soon, long enough to cost nothing while idle.
    while (!stop_.load(std::memory_order_relaxed) && poll(50)) {
    }
  });
}

void SpaceMouseDevice::stop() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

void SpaceMouseDevice::fail(engine::DeviceStatus status, const std::string& message) {
  {
    std::lock_guard<std::mutex> lock(message_mutex_);
    if (fault_message_.empty()) fault_message_ = message;
  }
  status_.store(status, std::memory_order_release);
}

bool SpaceMouseDevice::poll(int timeout_ms) {
  if (status_.load(std::memory_order_acquire) != engine::DeviceStatus::Ok) return false;
  std::array<std::uint8_t, 64> report{};
  const int n = transport_->read(report.data(), report.size(), timeout_ms);
  if (n < 0) {
    std::string message = caps_.name;
    message += ": read failed (unplugged?): ";
    message += transport_->error();
    fail(engine::DeviceStatus::Disconnected, message);
    return false;
  }
  if (n == 0) return true;
  const auto outcome = parse_report(layout_, report.data(), static_cast<std::size_t>(n), io_state_);
  if (outcome.kind == ReportKind::Bad) {
    // One odd report does not stop the device: counted, and the last one kept for a log line.
    bad_reports_.fetch_add(1, std::memory_order_relaxed);
    std::lock_guard<std::mutex> lock(message_mutex_);
    last_bad_report_ = caps_.name;
    last_bad_report_ += ": ";
    last_bad_report_ += outcome.message.data();
    return true;
  }
  if (outcome.kind != ReportKind::Other) {
    published_.write_slot() = io_state_;
    published_.publish();
  }
  return true;
}

std::string SpaceMouseDevice::fault_message() const {
  std::lock_guard<std::mutex> lock(message_mutex_);
  return fault_message_;
}

std::string SpaceMouseDevice::last_bad_report() const {
  std::lock_guard<std::mutex> lock(message_mutex_);
  return last_bad_report_;
}

void SpaceMouseDevice::place_workspace(const Vec3& scene_center, double scale) {
  caps_.workspace_center = scene_center;
  scale_ = scale > 0.0 ? scale : 1.0;
  caps_.workspace_radius = scale_ * options_.workspace_radius;
  position_ = scene_center;
  last_t_ = -1.0;
}

Vec3 SpaceMouseDevice::deflection(const SpaceMouseState& state) const noexcept {
  Vec3 d;
  const double dead = std::max(0, options_.dead_zone);
  const double span = std::max(1.0, options_.full_scale - dead);
  for (int k = 0; k < 3; ++k) {
    const double raw = state.axes[static_cast<std::size_t>(k)];
    // Past the dead zone the deflection starts from 0, so leaving it causes no jump.
    const double beyond = std::max(0.0, std::abs(raw) - dead) / span;
    d[k] = options_.axis_sign[static_cast<std::size_t>(k)] * std::copysign(std::min(beyond, 1.0), raw);
  }
  return d;
}

engine::DeviceStatus SpaceMouseDevice::read(double t, engine::DevicePose& pose) noexcept {
  const auto status = status_.load(std::memory_order_acquire);
  if (status != engine::DeviceStatus::Ok) return status;
  published_.update();
  const SpaceMouseState& state = published_.read();
  const Vec3 d = deflection(state);
  const Vec3& center = caps_.workspace_center;
  if (options_.mode == SpaceMouseMode::Position) {
    position_ = center + caps_.workspace_radius * d;
  } else {
    const double dt = last_t_ < 0.0 ? 0.0 : std::clamp(t - last_t_, 0.0, 0.1);  // a stall is not a leap
    position_ += (scale_ * options_.max_speed * dt) * d;
    const Vec3 offset = position_ - center;
    const double reach = offset.norm();
    if (reach > caps_.workspace_radius) position_ = center + offset * (caps_.workspace_radius / reach);
  }
  last_t_ = t;
  pose.position = position_;
  pose.buttons = state.buttons;
  return engine::DeviceStatus::Ok;
}

engine::DeviceStatus SpaceMouseDevice::write_force(const Vec3& force) noexcept {
  fx_.store(force.x(), std::memory_order_relaxed);
  fy_.store(force.y(), std::memory_order_relaxed);
  fz_.store(force.z(), std::memory_order_relaxed);
  return status_.load(std::memory_order_acquire);
}

Vec3 SpaceMouseDevice::last_force() const noexcept {
  return {fx_.load(std::memory_order_relaxed), fy_.load(std::memory_order_relaxed),
          fz_.load(std::memory_order_relaxed)};
}

}  // namespace palpa::device
