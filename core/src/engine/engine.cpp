#include "palpa/engine/engine.hpp"
#include "palpa/vec3.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace palpa::engine {

Engine::Engine(const scene::Scene& scene, Device& device, const EngineOptions& options)
    : scene_(&scene),
      device_(&device),
      options_(options),
      state_(scene.make_state()),
      governor_(options.safety, device.capabilities().max_force) {
  if (!(options.rate_hz > 0.0) || !std::isfinite(options.rate_hz)) {
    throw std::invalid_argument("Engine: the haptic rate must be a positive number of Hz");
  }
  options_.probe.remember_side = true;  // successive ticks are one probe path
  options_.probe.force.shear = options.shear;
  options_.deform.dynamics = options.dynamics;
}

Sample Engine::tick(double t, bool overrun, bool hold_fault) noexcept {
  Sample s;
  s.t = t;
  s.overrun = overrun;
  // The governor sees at most one nominal period, so a late tick cannot let the force jump
  // by more than one tick's worth of its rate limit.
  const double period = 1.0 / options_.rate_hz;
  const double dt = started_ ? std::clamp(t - last_t_, 0.0, period) : period;
  last_t_ = t;
  started_ = true;

  DevicePose pose;
  DeviceStatus status = device_->read(t, pose);
  if (status == DeviceStatus::Ok && !pose.position.allFinite()) status = DeviceStatus::Error;  // garbage is a fault
  // On a fault the probe stays where it was last seen (not at the origin): review and the
  // GUI draw it there while the force ramps down.
  if (status == DeviceStatus::Ok) last_position_ = to_array(pose.position);
  s.position = last_position_;
  s.buttons = pose.buttons;
  s.fault = hold_fault || status != DeviceStatus::Ok;

  Vec3 requested = Vec3::Zero();
  touch_.inside = false;
  if (status == DeviceStatus::Ok) {
    // Foot point and force on the rest bodies (boxes cull the rest). The touch tells the
    // drawn bodies where to follow the probe, so that what is seen is what is felt.
    const auto r = scene_->probe(pose.position, state_, options_.probe);
    if (r.body >= 0) {
      s.body = r.body;
      s.u = r.contact.foot.u;
      s.v = r.contact.foot.v;
      s.depth = r.contact.depth;
      requested = r.force.total;
      touch_.inside = r.contact.inside;
      touch_.side = static_cast<std::int8_t>(r.contact.side);
      touch_.outward = to_array(r.contact.outward);
    }
  }
  const Vec3 force = governor_.govern(requested, dt, s.fault);
  s.force = to_array(force);
  const bool write_failed = device_->write_force(force) != DeviceStatus::Ok;
  if (write_failed) s.fault = true;
  touch_.device_fault = status != DeviceStatus::Ok || write_failed;
  touch_.stall = false;  // the loop says so
  touch_.sample = s;
  touch_.dynamics = options_.dynamics;
  return s;
}

}  // namespace palpa::engine
