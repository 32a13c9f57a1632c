#pragma once
// A recorded session played back as a device: the probe goes where the session's probe
// went, at the recorded times (the sample standing at t, as review mode shows it), with
// the recorded buttons; more than half a tick (half the mean sample interval) after the
// last sample it reports Disconnected ("the replay ended"): the engine's k/rate and the
// recorded times differ by rounding, and the last tick must still play. Ticks recorded during a device fault keep the last good position. For review
// and re-scoring: `palpa-cli exercise --device replay:SESSION` runs the recorded hand
// through the current engine and scores the new session.
#include <atomic>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "palpa/engine/device.hpp"
#include "palpa/session/session.hpp"

namespace palpa::device {

class ReplayDevice final : public engine::Device {
 public:
  /// Throws DeviceError when the session has no samples.
  ReplayDevice(const session::Session& session, const std::string& source);
  /// Reads the session file; throws session::SessionError or DeviceError.
  static std::unique_ptr<ReplayDevice> from_file(const std::filesystem::path& path);

  const engine::DeviceCapabilities& capabilities() const override { return caps_; }
  /// t = 0 is the session's first sample.
  engine::DeviceStatus read(double t, engine::DevicePose& pose) noexcept override;
  engine::DeviceStatus write_force(const palpa::Vec3& force) noexcept override;
  std::string fault_message() const override;

  double duration() const { return t_.back() - t_.front(); }
  std::size_t size() const { return t_.size(); }

 private:
  engine::DeviceCapabilities caps_;
  std::string source_;
  std::vector<double> t_;
  double end_ = 0.0;  // s: the last sample plus half a tick
  std::vector<palpa::Vec3> position_;
  std::vector<std::uint32_t> buttons_;
  std::size_t cursor_ = 0;  // the sample of the last read: playback moves forward
  std::atomic<bool> ended_{false};  // read by fault_message() from another thread
};

}  // namespace palpa::device
