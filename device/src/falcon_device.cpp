#include "palpa/device/falcon_device.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include <fmt/format.h>

#include "palpa/device/device_error.hpp"

namespace palpa::device {

using engine::DeviceStatus;

FalconDevice::FalconDevice(std::unique_ptr<UsbTransport> transport, std::string device_id,
                           const FalconOptions& options)
    : transport_(std::move(transport)), serial_(*transport_), id_(std::move(device_id)), options_(options) {
  caps_.name = "Novint Falcon";
  caps_.max_force = options_.max_force;
  caps_.force_output = true;
  caps_.workspace_radius = falcon::Kinematics::kWorkspaceRadius;
}

FalconDevice::~FalconDevice() { stop(); }

int FalconDevice::connect() {
  // The firmware keeps running while the Falcon stays powered: every exercise after the
  // first finds it there, and a needless upload costs seconds and can fail (it is flaky).
  if (falcon::firmware_running(*transport_)) return 0;
  const auto firmware = falcon::read_firmware(options_.firmware, id_);
  return falcon::boot(*transport_, firmware, id_, options_.boot);
}

void FalconDevice::start() {
  if (thread_.joinable()) return;
  stop_.store(false);
  thread_ = std::thread([this] {
    using clock = std::chrono::steady_clock;
    const auto period = std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(1.0 / options_.rate_hz));
    auto next = clock::now();
    while (!stop_.load(std::memory_order_relaxed)) {
      if (!exchange(2)) break;
      next += period;
      const auto now = clock::now();
      if (next < now) next = now;  // late: do not try to catch up with a burst
      std::this_thread::sleep_until(next);
    }
    send_zero_torque();  // every way out: stopped, unplugged, failed (best effort: its error is moot)
  });
}

void FalconDevice::stop() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

void FalconDevice::fail(DeviceStatus status, const std::string& message) {
  {
    std::lock_guard<std::mutex> lock(message_mutex_);
    if (fault_message_.empty()) fault_message_ = message;
  }
  status_.store(status, std::memory_order_release);
}

std::string FalconDevice::fault_message() const {
  {
    std::lock_guard<std::mutex> lock(message_mutex_);
    if (!fault_message_.empty()) return fault_message_;
  }
  std::string message;
  switch (haptic_fault_.load(std::memory_order_acquire)) {
    case HapticFault::None: break;
    case HapticFault::BadReadings:
      message = fmt::format(
          "{} ({}): the encoders read positions no arm can reach, {} times in a row (a loose encoder cable? unplug "
          "and plug in again)",
          caps_.name, id_, options_.bad_readings);
      break;
  }
  return message;
}

void FalconDevice::wait_homed(double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!homed()) {
    if (status() != DeviceStatus::Ok) {
      // fail() and read() set the reason before the status, so it is there; say so if not.
      std::string reason = fault_message();
      if (reason.empty()) reason = "the Falcon stopped answering while homing (no reason given)";
      throw DeviceError(id_, "homing", reason);
    }
    if (std::chrono::steady_clock::now() >= end) {
      throw DeviceError(id_, "homing", "not homed in time: move the grip all the way out and back in, then try again");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

void FalconDevice::send_zero_torque() {
  falcon::Packet packet{};
  falcon::encode(falcon::Words{}, packet);
  serial_.write(packet.data(), packet.size(), 10);
}

bool FalconDevice::zero_and_stop() {
  send_zero_torque();
  return false;
}

bool FalconDevice::exchange(unsigned timeout_ms) {
  // Not Ok (failed here, or the haptic thread gave up on the readings): the motors get a
  // zero, whatever the last command was.
  if (status_.load(std::memory_order_acquire) != DeviceStatus::Ok) return zero_and_stop();
  falcon::Words out;
  if (homed()) {
    commands_.update();
    out.value = commands_.read().torque;
    out.flags = falcon::kLedGreen;
  } else {
    out.flags = falcon::kHomingMode | falcon::kLedRed;  // no torque until the encoders know where they are
  }
  falcon::Packet packet{};
  falcon::encode(out, packet);
  UsbStatus status = serial_.write(packet.data(), packet.size(), timeout_ms);
  std::size_t got = 0;
  std::array<std::uint8_t, falcon::ftdi::kUsbPacket> bytes{};
  if (status == UsbStatus::Ok) status = serial_.read(bytes.data(), bytes.size(), got, timeout_ms);
  if (status == UsbStatus::NoDevice) {
    fail(DeviceStatus::Disconnected, caps_.name + " (" + id_ + "): unplugged");
    return zero_and_stop();  // in case it is only the link that is gone
  }
  if (status != UsbStatus::Ok && status != UsbStatus::Timeout) {
    // A transfer can fail once on a busy bus; three in a row is a broken link.
    if (++failures_ >= 3) {
      std::string message = caps_.name;
      message += " (";
      message += id_;
      message += "): USB transfer failed: ";
      message += to_string(status);
      fail(DeviceStatus::Error, message);
      return zero_and_stop();
    }
    return true;
  }
  failures_ = 0;
  reader_.feed(bytes.data(), got);
  falcon::Words in;
  bool fresh = false;
  while (reader_.next(in)) {
    fresh = true;
    io_reading_.encoder = in.value;
    io_reading_.flags = in.flags;
    ++io_reading_.count;
  }
  reader_bad_.store(reader_.bad_packets(), std::memory_order_relaxed);
  if (!fresh) {
    if (++silent_ >= options_.silent_exchanges) {
      std::string message = caps_.name;
      message += " (";
      message += id_;
      message += "): the firmware stopped answering (power lost? unplug and plug in again)";
      fail(DeviceStatus::Error, message);
      return zero_and_stop();  // a firmware that does not answer may still listen
    }
    return true;
  }
  silent_ = 0;
  packets_.fetch_add(1, std::memory_order_relaxed);
  if ((io_reading_.flags & falcon::kHomedMask) == falcon::kHomedMask) homed_.store(true, std::memory_order_release);
  readings_.write_slot() = io_reading_;
  readings_.publish();
  return true;
}

void FalconDevice::place_workspace(const palpa::Vec3& scene_center, double scale) {
  caps_.workspace_center = scene_center;
  scale_ = scale > 0.0 ? scale : 1.0;
  caps_.workspace_radius = scale_ * falcon::Kinematics::kWorkspaceRadius;
}

// Device frame: x right, y up, z toward the user. Scene: x right, y away from the user, z up.
palpa::Vec3 FalconDevice::to_scene(const palpa::Vec3& p) const {
  const palpa::Vec3 d = p - falcon::Kinematics::workspace_center();
  return caps_.workspace_center + scale_ * palpa::Vec3(d.x(), -d.z(), d.y());
}

palpa::Vec3 FalconDevice::force_to_device(const palpa::Vec3& f) const { return {f.x(), f.z(), -f.y()}; }

engine::DeviceStatus FalconDevice::read(double /*t*/, engine::DevicePose& pose) noexcept {
  const auto status = status_.load(std::memory_order_acquire);
  if (status != DeviceStatus::Ok) return status;
  readings_.update();
  const Reading& reading = readings_.read();
  // Before the axes are homed the counts are relative to wherever the grip was at power-up:
  // no kinematics, the position stays put (the workspace centre).
  const bool homed_reading = (reading.flags & falcon::kHomedMask) == falcon::kHomedMask;
  if (reading.count > 0 && homed_reading) {
    if (reading.count != solved_count_) {
      solved_count_ = reading.count;
      const falcon::Angles angles(falcon::encoder_to_angle(reading.encoder[0]),
                                  falcon::encoder_to_angle(reading.encoder[1]),
                                  falcon::encoder_to_angle(reading.encoder[2]));
      auto p = kinematics_.forward(angles, device_position_);
      if (!p) p = kinematics_.forward(angles, falcon::Kinematics::workspace_center());
      solved_ = p.has_value();
      if (p) device_position_ = *p;
    }
    // Encoders no arm can produce: one garbled reading keeps the last good position; a run
    // of them (reads, so a stalled reading counts too) is a broken encoder or cable.
    if (solved_) {
      bad_readings_ = 0;
    } else if (++bad_readings_ >= options_.bad_readings) {
      haptic_fault_.store(HapticFault::BadReadings, std::memory_order_release);
      auto expected = DeviceStatus::Ok;
      status_.compare_exchange_strong(expected, DeviceStatus::Error, std::memory_order_acq_rel);
      publish_torque({0, 0, 0});
      return status_.load(std::memory_order_acquire);
    }
  }
  pose.position = to_scene(device_position_);
  pose.buttons = reading.flags & falcon::kButtonMask;
  return DeviceStatus::Ok;
}

void FalconDevice::publish_torque(const std::array<std::int16_t, 3>& torque) {
  commands_.write_slot().torque = torque;
  t0_.store(torque[0], std::memory_order_relaxed);
  t1_.store(torque[1], std::memory_order_relaxed);
  t2_.store(torque[2], std::memory_order_relaxed);
  commands_.publish();
}

engine::DeviceStatus FalconDevice::write_force(const palpa::Vec3& force) noexcept {
  const auto status = status_.load(std::memory_order_acquire);
  if (status != DeviceStatus::Ok) {
    publish_torque({0, 0, 0});  // whatever was asked: a failed device gets no force
    return status;
  }
  palpa::Vec3 f = force_to_device(force);
  if (!f.allFinite()) f.setZero();
  const double norm = f.norm();
  if (norm > options_.max_force) f *= options_.max_force / norm;
  const auto torques = kinematics_.torques(device_position_, f);
  std::array<std::int16_t, 3> torque{0, 0, 0};
  if (torques) {
    palpa::Vec3 units((*torques).unaryExpr([](double t) { return falcon::torque_to_units(t); }));
    // One motor at its limit scales all three, so the force keeps its direction.
    const double biggest = units.cwiseAbs().maxCoeff();
    if (biggest > falcon::kMaxTorqueUnits) units *= falcon::kMaxTorqueUnits / biggest;
    for (int k = 0; k < 3; ++k) torque[static_cast<std::size_t>(k)] = static_cast<std::int16_t>(std::lround(units[k]));
  }
  publish_torque(torque);
  return DeviceStatus::Ok;
}

std::array<std::int16_t, 3> FalconDevice::commanded_torque() const {
  return {t0_.load(std::memory_order_relaxed), t1_.load(std::memory_order_relaxed), t2_.load(std::memory_order_relaxed)};
}

}  // namespace palpa::device
