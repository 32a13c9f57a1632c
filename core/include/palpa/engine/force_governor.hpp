#pragma once
// The last stage before a force reaches a device: a per-device cap, a limit on how fast
// the force may change, and a ramp to zero on any fault (device error, pause, shutdown),
// so the hand never gets a jolt. After a fault the force comes back no faster than the
// ramp (cap / ramp_time), never at the full rate limit: the hand gets the force back as
// gently as it lost it. A stalled loop is not a fault (realtime_loop.hpp): the force is
// computed afresh and only rate-limited.
#include "palpa/engine/device.hpp"

namespace palpa::engine {

struct SafetyOptions {
  double max_force = 30.0;         ///< N; the device's own maximum caps this further
  double max_force_rate = 5000.0;  ///< N/s: |dF/dt| limit (a 1500 N/m tumour pressed at 0.5 m/s needs 750)
  double ramp_time = 0.05;         ///< s: a fault takes the force from the cap to 0 in this time
  /// s between tick starts beyond which the loop counts a tick as a stall (Sample::overrun,
  /// SceneSnapshot::last_stall). A stall is not a fault: the force is not ramped down.
  double watchdog_timeout = 0.02;
};

class ForceGovernor {
 public:
  ForceGovernor(const SafetyOptions& options, double device_max_force);

  /// The force to send after a tick of length dt: `requested` capped and rate-limited, or
  /// ramping to zero while `fault` holds. Allocation-free.
  Vec3 govern(const Vec3& requested, double dt, bool fault) noexcept;

  double cap() const { return cap_; }
  const Vec3& last() const { return last_; }

 private:
  double cap_;
  double rate_;
  double ramp_rate_;
  Vec3 last_ = Vec3::Zero();
  bool recovering_ = false;  // since a fault: rising forces come back at the ramp rate
};

}  // namespace palpa::engine
