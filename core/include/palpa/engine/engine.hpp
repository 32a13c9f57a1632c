#pragma once
// The haptic engine's tick (paper section 4: a separate high-priority thread at ~1 kHz):
// read the device, find the contact, deform, integrate the awake bodies, govern and write
// the force. The tick is allocation-free, lock-free and does no I/O; the real-time thread
// that paces it lives in realtime_loop.hpp.
#include <array>
#include <cstdint>
#include <vector>

#include "palpa/deform/deformed_body.hpp"
#include "palpa/engine/device.hpp"
#include "palpa/engine/force_governor.hpp"
#include "palpa/scene/scene.hpp"

namespace palpa::engine {

/// m: the drawn contours' knot spans in the engine (DeformOptions::display_span).
inline constexpr double kDisplaySpan = 0.004;

struct EngineOptions {
  double rate_hz = 1000.0;
  bool dynamics = true;  ///< the paper's Table 1 has columns with and without dynamics
  bool shear = true;
  scene::ProbeOptions probe{};  ///< foot-point method and force options (the entry side is always remembered)
  /// The drawn bodies: refined for display so that a dent is fingertip-sized (display_span).
  deform::DeformOptions deform{.display_span = kDisplaySpan};
  SafetyOptions safety{};
};

/// One haptic tick, as the session log keeps it. Plain data (std::array, not Eigen) so it is
/// trivially copyable and can cross threads through a lock-free ring.
struct Sample {
  double t = 0.0;                        ///< s since the engine started
  std::array<double, 3> position{};      ///< m, the probe
  std::array<double, 3> force{};         ///< N, as sent to the device (after the governor)
  std::int32_t body = -1;      ///< index of the contacted body, -1 when none
  double u = 0.0;
  double v = 0.0;
  double depth = 0.0;          ///< m, penetration (0 when not in contact)
  std::uint32_t buttons = 0;
  bool overrun = false;        ///< the tick started after its deadline
  bool fault = false;          ///< device error, stall, pause: the force is ramping to zero
};

class RealtimeLoop;

class Engine {
 public:
  /// The scene must outlive the engine. Sizes everything; ticks allocate nothing.
  Engine(const scene::Scene& scene, Device& device, const EngineOptions& options = {});

  /// One tick at time t (s). `overrun` is recorded in the sample; `hold_fault` (pause,
  /// shutdown, watchdog) ramps the force to zero like a device error.
  Sample tick(double t, bool overrun = false, bool hold_fault = false) noexcept;

  std::size_t body_count() const { return drawn_.size(); }
  const deform::DeformedBody& drawn(std::size_t body) const { return drawn_[body]; }
  const EngineOptions& options() const { return options_; }
  const ForceGovernor& governor() const { return governor_; }
  Device& device() { return *device_; }

 private:
  // Switches, applied between ticks only: while a RealtimeLoop runs the engine they reach
  // it through the loop's command queue, so nothing else may call them.
  friend class RealtimeLoop;
  void set_shear(bool on) { options_.shear = on; options_.probe.force.shear = on; }
  void set_dynamics(bool on) {
    options_.dynamics = on;
    for (auto& body : drawn_) body.set_dynamics(on);
  }

  const scene::Scene* scene_;
  Device* device_;
  EngineOptions options_;
  scene::ProbeState state_;
  std::vector<deform::DeformedBody> drawn_;
  ForceGovernor governor_;
  double last_t_ = 0.0;
  bool started_ = false;
  int pressed_ = -1;  // body pressed at the last tick
  std::array<double, 3> last_position_{};  // the probe at the last tick the device read Ok
};

/// Runs ticks at t = k / rate for k = 0 .. duration * rate as fast as the machine allows
/// (no sleeping): deterministic, the same inputs give the same samples.
template <typename Sink>
void run_fast(Engine& engine, double duration, Sink&& sink) {
  const double rate = engine.options().rate_hz;
  const auto ticks = static_cast<std::uint64_t>(duration * rate + 0.5);
  for (std::uint64_t k = 0; k <= ticks; ++k) sink(engine.tick(static_cast<double>(k) / rate));
}

}  // namespace palpa::engine
