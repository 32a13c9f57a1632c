#include "palpa/engine/drawn_scene.hpp"
#include "palpa/vec3.hpp"

#include <stdexcept>

namespace palpa::engine {
namespace {

// The contact a touch describes: the fields DeformedBody::press reads (the foot point's
// parameters, the depth, the entered side and the way out).
contact::Contact contact_of(const Touch& touch) {
  contact::Contact c;
  c.foot.u = touch.sample.u;
  c.foot.v = touch.sample.v;
  c.depth = touch.sample.depth;
  c.inside = touch.inside;
  c.side = touch.side;
  c.outward = to_vec3(touch.outward);
  return c;
}

}  // namespace

DrawnScene::DrawnScene(const scene::Scene& scene, const deform::DeformOptions& options, double rate_hz)
    : period_(1.0 / rate_hz), dynamics_(options.dynamics) {
  if (!(rate_hz > 0.0)) throw std::invalid_argument("DrawnScene: the haptic rate must be a positive number of Hz");
  drawn_.reserve(scene.size());
  for (std::size_t b = 0; b < scene.size(); ++b) drawn_.emplace_back(scene.body(b).body, options);
}

DrawnScene::DrawnScene(const Engine& engine)
    : DrawnScene(engine.scene(), engine.options().deform, engine.options().rate_hz) {}

void DrawnScene::set_dynamics(bool on) {
  dynamics_ = on;
  for (auto& body : drawn_) body.set_dynamics(on);
}

void DrawnScene::follow(const Touch& touch, int periods) {
  if (touch.dynamics != dynamics_) set_dynamics(touch.dynamics);
  const int body = touch.sample.body;
  if (pressed_ >= 0 && pressed_ != body) drawn_[static_cast<std::size_t>(pressed_)].release();
  if (body >= 0 && static_cast<std::size_t>(body) < drawn_.size()) {
    const palpa::Vec3 q(touch.sample.position[0], touch.sample.position[1], touch.sample.position[2]);
    drawn_[static_cast<std::size_t>(body)].press(contact_of(touch), q);
  }
  pressed_ = body;
  // Only awake bodies integrate; a body at rest costs one flag test.
  for (int k = 0; k < periods; ++k) {
    for (auto& drawn : drawn_) {
      if (drawn.awake()) drawn.step(period_);
    }
  }
}

}  // namespace palpa::engine
