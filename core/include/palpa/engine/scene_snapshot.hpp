#pragma once
// What the GUI draws, copied out of the display thread (RealtimeLoop): the drawn contours'
// control points of every body, the probe and the force. Sized once; capturing into one of
// the same scene allocates nothing.
#include <array>
#include <cstdint>
#include <vector>

#include "palpa/engine/drawn_scene.hpp"
#include "palpa/engine/engine.hpp"

namespace palpa::engine {

struct BodySnapshot {
  std::uint64_t version = 0;   ///< DeformedBody::version(): unchanged means nothing to redraw
  std::vector<double> top;     ///< control points, rows*cols*3, as in BSplineSurface::control()
  std::vector<double> bottom;
  double sum = 0.0;  ///< of top and bottom, computed when they were copied
};

/// When the loop last stalled and the device last faulted, in haptic time (s; -1: never),
/// kept by the display thread from every touch, so a GUI that reads one snapshot in eight
/// still sees a one-tick event.
struct LoopEvents {
  double last_stall = -1.0;
  double last_device_fault = -1.0;
  void note(const Touch& touch) noexcept {
    if (touch.stall) last_stall = touch.sample.t;
    if (touch.device_fault) last_device_fault = touch.sample.t;
  }
};

struct SceneSnapshot {
  std::uint64_t tick = 0;
  double t = 0.0;
  std::array<double, 3> probe{};
  std::array<double, 3> force{};
  std::int32_t body = -1;
  double u = 0.0;      ///< the contact's skeleton parameters (meaningful when body >= 0)
  double v = 0.0;
  double depth = 0.0;  ///< m, penetration of the contacted body (0 when none)
  bool fault = false;  ///< Sample::fault of the last tick (device error, pause, stop)
  LoopEvents events;   ///< the last stall and device fault up to this tick
  std::vector<BodySnapshot> bodies;
  double checksum = 0.0;  ///< sum of all control-point values, so a torn copy would show

  /// A snapshot sized for the drawn bodies.
  static SceneSnapshot sized_for(const DrawnScene& drawn);
  /// Fills this snapshot from the drawn bodies and the tick they last followed (same
  /// sizes: no allocation).
  void capture(const DrawnScene& drawn, const Sample& last, std::uint64_t tick_number,
               const LoopEvents& loop_events = {});
  /// Recomputes the checksum of the contents (tests and the GUI's debug checks).
  double contents_sum() const;
};

}  // namespace palpa::engine
