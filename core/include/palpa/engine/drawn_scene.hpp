#pragma once
// The bodies as the trainee sees them, following the finger tick by tick: each tick's Touch
// presses the body the finger is in and lets go of the one it left, and the awake bodies
// spring back (paper sections 3.2 and 3.3; docs/model.md). The force is computed on the rest
// bodies and never reads these, so this half of the paper's haptic loop runs beside the
// 1 kHz tick instead of inside it: RealtimeLoop's display thread follows the touches in
// order, and fast runs call follow() after each tick. Nothing allocates after construction.
#include <cstddef>
#include <vector>

#include "palpa/deform/deformed_body.hpp"
#include "palpa/engine/engine.hpp"
#include "palpa/scene/scene.hpp"

namespace palpa::engine {

class DrawnScene {
 public:
  /// One drawn body per scene body, refined as `options` says; the scene must outlive this.
  DrawnScene(const scene::Scene& scene, const deform::DeformOptions& options, double rate_hz);
  /// The bodies an engine's options ask for (EngineOptions::deform, rate_hz).
  explicit DrawnScene(const Engine& engine);

  /// One tick: let go of the body the finger left, press the one it is in, then advance the
  /// awake bodies by `periods` haptic periods (more than one after lost touches).
  void follow(const Touch& touch, int periods = 1);

  std::size_t body_count() const { return drawn_.size(); }
  const deform::DeformedBody& drawn(std::size_t body) const { return drawn_[body]; }

 private:
  void set_dynamics(bool on);

  std::vector<deform::DeformedBody> drawn_;
  double period_;
  int pressed_ = -1;  // body pressed at the last touch
  bool dynamics_;
};

}  // namespace palpa::engine
