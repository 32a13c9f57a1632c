#include "palpa/engine/engine.hpp"

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
  drawn_.reserve(scene.size());
  for (std::size_t b = 0; b < scene.size(); ++b) drawn_.emplace_back(scene.body(b).body, options_.deform);
}

Sample Engine::tick(double t, bool overrun, bool hold_fault) noexcept {
  Sample s;
  s.t = t;
  s.overrun = overrun;
  // The governor sees at most one nominal period, so a late tick cannot let the force jump
  // by more than one tick's worth of its rate limit; the springs always advance by the
  // nominal period (a measured, jittery dt would rebuild their step maps inside the tick).
  const double period = 1.0 / options_.rate_hz;
  const double dt = started_ ? std::clamp(t - last_t_, 0.0, period) : period;
  last_t_ = t;
  started_ = true;

  DevicePose pose;
  DeviceStatus status = device_->read(t, pose);
  if (status == DeviceStatus::Ok && !pose.position.allFinite()) status = DeviceStatus::Error;  // garbage is a fault
  // On a fault the probe stays where it was last seen (not at the origin): review and the
  // GUI draw it there while the force ramps down.
  if (status == DeviceStatus::Ok) last_position_ = {pose.position.x(), pose.position.y(), pose.position.z()};
  s.position = last_position_;
  s.buttons = pose.buttons;
  s.fault = hold_fault || status != DeviceStatus::Ok;

  Vec3 requested = Vec3::Zero();
  if (status == DeviceStatus::Ok) {
    // Foot point and force on the rest bodies (boxes cull the rest), then the drawn body
    // follows the probe so that what is seen is what is felt.
    const auto r = scene_->probe(pose.position, state_, options_.probe);
    if (pressed_ >= 0 && pressed_ != r.body) drawn_[static_cast<std::size_t>(pressed_)].release();
    if (r.body >= 0) {
      drawn_[static_cast<std::size_t>(r.body)].press(r.contact, pose.position);
      s.body = r.body;
      s.u = r.contact.foot.u;
      s.v = r.contact.foot.v;
      s.depth = r.contact.depth;
      requested = r.force.total;
    }
    pressed_ = r.body;
  }
  // Only awake bodies integrate; a body at rest costs one flag test.
  for (auto& body : drawn_) {
    if (body.awake()) body.step(period);
  }
  const Vec3 force = governor_.govern(requested, dt, s.fault);
  s.force = {force.x(), force.y(), force.z()};
  if (device_->write_force(force) != DeviceStatus::Ok) s.fault = true;
  return s;
}

}  // namespace palpa::engine
