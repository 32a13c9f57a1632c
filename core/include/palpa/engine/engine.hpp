#pragma once
// The haptic engine's tick (paper section 4: a separate high-priority thread at ~1 kHz):
// read the device, find the contact and the force on the rest bodies, govern and write the
// force. The tick is allocation-free, lock-free and does no I/O; the real-time thread that
// paces it lives in realtime_loop.hpp. What the trainee sees, the bodies pressed in and
// springing back, is computed from each tick's Touch by a DrawnScene (drawn_scene.hpp),
// beside the tick rather than inside it: the force never depends on the drawn bodies.
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
  bool dynamics = true;  ///< the drawn bodies spring back (Table 1 has columns with and without)
  bool shear = true;
  scene::ProbeOptions probe{};  ///< foot-point method and force options (the entry side is always remembered)
  /// The drawn bodies (DrawnScene): refined for display so that a dent is fingertip-sized.
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
  bool overrun = false;        ///< the tick started after its deadline (also: after a stall of the loop)
  bool fault = false;          ///< device error, pause, stop: the force is ramping to zero
};

/// What the drawn bodies need from one tick to follow the finger (DrawnScene::follow): the
/// tick's sample and the contact's entered side and way out. Plain data, like Sample, so it
/// crosses from the haptic thread to the display thread through a lock-free ring.
struct Touch {
  Sample sample;
  std::uint64_t tick = 0;  ///< counts ticks from 1 (RealtimeLoop); a gap means touches were lost
  std::array<double, 3> outward{0.0, 0.0, 1.0};  ///< contact::Contact::outward
  std::int8_t side = 1;    ///< contact::Contact::side
  bool inside = false;     ///< the probe is in body sample.body (contact::Contact::inside)
  bool device_fault = false;  ///< the device read or write failed (not a pause or a stop)
  bool stall = false;      ///< the tick came after a stall of the loop (RealtimeLoop's watchdog)
  bool dynamics = true;    ///< EngineOptions::dynamics at this tick (it can change between ticks)
};

class RealtimeLoop;

class Engine {
 public:
  /// The scene must outlive the engine. Sizes everything; ticks allocate nothing.
  Engine(const scene::Scene& scene, Device& device, const EngineOptions& options = {});

  /// One tick at time t (s). `overrun` is recorded in the sample; `hold_fault` (pause,
  /// shutdown) ramps the force to zero like a device error.
  Sample tick(double t, bool overrun = false, bool hold_fault = false) noexcept;

  /// The last tick's Touch (tick number 0: the RealtimeLoop numbers them).
  const Touch& last_touch() const { return touch_; }
  const scene::Scene& scene() const { return *scene_; }
  const EngineOptions& options() const { return options_; }
  const ForceGovernor& governor() const { return governor_; }
  Device& device() { return *device_; }

 private:
  // Switches, applied between ticks only: while a RealtimeLoop runs the engine they reach
  // it through the loop's command queue, so nothing else may call them.
  friend class RealtimeLoop;
  void set_shear(bool on) { options_.shear = on; options_.probe.force.shear = on; }
  void set_dynamics(bool on) { options_.dynamics = on; }  // reaches the drawn bodies with the next Touch

  const scene::Scene* scene_;
  Device* device_;
  EngineOptions options_;
  scene::ProbeState state_;
  ForceGovernor governor_;
  Touch touch_;
  double last_t_ = 0.0;
  bool started_ = false;
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
