#include "palpa/device/replay_device.hpp"

#include "palpa/device/device_error.hpp"
#include "palpa/session/session_reader.hpp"

namespace palpa::device {

ReplayDevice::ReplayDevice(const session::Session& session, const std::string& source) : source_(source) {
  caps_.name = "replay of ";
  caps_.name += session.info.device.empty() ? std::string("a session") : session.info.device;
  caps_.max_force = 30.0;
  caps_.force_output = false;
  caps_.workspace_radius = 1.0;
  t_.reserve(session.samples.size());
  position_.reserve(session.samples.size());
  buttons_.reserve(session.samples.size());
  palpa::Vec3 last = palpa::Vec3::Zero();
  bool seen = false;
  for (const auto& s : session.samples) {
    const palpa::Vec3 p(s.position[0], s.position[1], s.position[2]);
    // Sessions recorded before the engine kept the last position on a fault have the
    // origin there: hold the last good position instead.
    if (!s.fault || !seen) {
      last = p;
      seen = seen || !s.fault;
    }
    t_.push_back(s.t);
    position_.push_back(last);
    buttons_.push_back(s.buttons);
  }
  if (t_.empty()) throw DeviceError("replay:" + source, "samples", "the session has no samples to play");
  const double tick = t_.size() > 1 ? (t_.back() - t_.front()) / static_cast<double>(t_.size() - 1) : 0.0;
  end_ = t_.back() + 0.5 * tick;
}

std::unique_ptr<ReplayDevice> ReplayDevice::from_file(const std::filesystem::path& path) {
  return std::make_unique<ReplayDevice>(session::read_session(path), path.string());
}

engine::DeviceStatus ReplayDevice::read(double t, engine::DevicePose& pose) noexcept {
  const double time = t_.front() + t;
  if (time > end_) {
    ended_.store(true, std::memory_order_relaxed);
    pose.position = position_.back();
    pose.buttons = 0;
    return engine::DeviceStatus::Disconnected;
  }
  if (cursor_ >= t_.size() || t_[cursor_] > time) cursor_ = 0;
  while (cursor_ + 1 < t_.size() && t_[cursor_ + 1] <= time) ++cursor_;
  pose.position = position_[cursor_];
  pose.buttons = buttons_[cursor_];
  return engine::DeviceStatus::Ok;
}

engine::DeviceStatus ReplayDevice::write_force(const palpa::Vec3& /*force*/) noexcept {
  return engine::DeviceStatus::Ok;
}

std::string ReplayDevice::fault_message() const {
  if (!ended_.load(std::memory_order_relaxed)) return {};
  std::string message = "replay:";
  message += source_;
  message += ": the replay ended";
  return message;
}

}  // namespace palpa::device
