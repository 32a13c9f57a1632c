#include "palpa/engine/force_governor.hpp"

#include <algorithm>
#include <cmath>

namespace palpa::engine {

ForceGovernor::ForceGovernor(const SafetyOptions& options, double device_max_force)
    : cap_(std::max(0.0, std::min(options.max_force, device_max_force > 0.0 ? device_max_force : options.max_force))),
      rate_(std::max(0.0, options.max_force_rate)),
      ramp_rate_(options.ramp_time > 0.0 ? cap_ / options.ramp_time : 1e300) {}

Vec3 ForceGovernor::govern(const Vec3& requested, double dt, bool fault) noexcept {
  Vec3 target = fault ? Vec3::Zero() : requested;
  if (!target.allFinite()) target.setZero();
  const double norm = target.norm();
  if (norm > cap_) target *= cap_ / norm;
  // On a fault the ramp may be faster than the normal rate limit, never slower; back from
  // a fault a rising force is never faster than the ramp.
  if (fault) recovering_ = true;
  const bool rising = target.squaredNorm() > last_.squaredNorm();
  const double rate = fault                    ? std::max(rate_, ramp_rate_)
                      : recovering_ && rising  ? std::min(rate_, ramp_rate_)
                                               : rate_;
  const double max_step = rate * std::max(0.0, dt);
  const Vec3 step = target - last_;
  const double len = step.norm();
  last_ = len > max_step ? Vec3(last_ + step * (max_step / len)) : target;
  if (!fault && len <= max_step) recovering_ = false;  // caught up with the request
  return last_;
}

}  // namespace palpa::engine
