#pragma once
// A 3Dconnexion SpaceMouse as the probe: input only (the force is shown, not felt). Its I/O
// thread reads HID reports and publishes the axes through a triple buffer; the haptic
// thread turns the newest axes into a probe position:
//  - position control: the cap's deflection is an offset from the workspace centre (full
//    deflection = workspace_radius); let go and the probe springs back;
//  - rate control: the deflection is a velocity (full deflection = max_speed) that the
//    haptic thread integrates, kept inside the workspace sphere.
// Translation only: the probe is a point, the rotations are read and not used.
#include <array>
#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "palpa/device/hid_transport.hpp"
#include "palpa/device/spacemouse_report.hpp"
#include "palpa/engine/device.hpp"
#include "palpa/engine/triple_buffer.hpp"

namespace palpa::device {


enum class SpaceMouseMode : std::uint8_t { Position, Rate };

struct SpaceMouseOptions {
  SpaceMouseMode mode = SpaceMouseMode::Rate;
  double full_scale = 350.0;       ///< counts at full deflection (about +-350: docs/devices.md)
  int dead_zone = 20;              ///< counts: smaller deflections are none (the cap never rests at 0)
  double workspace_radius = 0.06;  ///< m: full deflection (position), the probe's reach (rate)
  double max_speed = 0.05;         ///< m/s at full deflection (rate)
  /// Scene axis k = axis_sign[k] * device axis k. The HID frame has X right, Y toward the
  /// user and Z down (pushing the cap); the scene has x right, y away from the user, z up.
  std::array<double, 3> axis_sign{1.0, -1.0, -1.0};
};

class SpaceMouseDevice final : public engine::Device {
 public:
  /// `name` is the model ("SpaceMouse Pro"). Nothing is read until start() (or poll()).
  SpaceMouseDevice(std::unique_ptr<HidTransport> transport, ReportLayout layout, std::string name,
                   const SpaceMouseOptions& options = {});
  ~SpaceMouseDevice() override;  ///< stops the I/O thread
  SpaceMouseDevice(const SpaceMouseDevice&) = delete;
  SpaceMouseDevice& operator=(const SpaceMouseDevice&) = delete;

  /// Starts the I/O thread (poll() in a loop until stopped or the device is gone).
  void start();
  void stop();
  /// One step of the I/O thread: waits at most timeout_ms for a report and folds it in.
  /// False once the device is gone. Tests call it directly instead of start().
  bool poll(int timeout_ms);

  const engine::DeviceCapabilities& capabilities() const override { return caps_; }
  engine::DeviceStatus read(double t, engine::DevicePose& pose) noexcept override;
  engine::DeviceStatus write_force(const Vec3& force) noexcept override;
  void place_workspace(const Vec3& scene_center, double scale) override;
  std::string fault_message() const override;

  /// The deflection as the probe sees it: each axis in [-1, 1] after the dead zone.
  Vec3 deflection(const SpaceMouseState& state) const noexcept;
  std::uint64_t bad_reports() const { return bad_reports_.load(std::memory_order_relaxed); }
  /// The last odd report's message (empty if none came), for a log line.
  std::string last_bad_report() const;
  Vec3 last_force() const noexcept;

 private:
  void fail(engine::DeviceStatus status, const std::string& message);

  std::unique_ptr<HidTransport> transport_;
  ReportLayout layout_;
  SpaceMouseOptions options_;
  engine::DeviceCapabilities caps_;
  double scale_ = 1.0;
  // I/O thread
  SpaceMouseState io_state_;
  engine::TripleBuffer<SpaceMouseState> published_{SpaceMouseState{}};
  std::atomic<std::uint64_t> bad_reports_{0};
  std::atomic<engine::DeviceStatus> status_{engine::DeviceStatus::Ok};
  mutable std::mutex message_mutex_;  // I/O and GUI threads only, never the haptic thread
  std::string fault_message_;
  std::string last_bad_report_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  // haptic thread
  Vec3 position_ = Vec3::Zero();
  double last_t_ = -1.0;
  std::atomic<double> fx_{0.0}, fy_{0.0}, fz_{0.0};
};

}  // namespace palpa::device
