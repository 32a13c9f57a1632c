#include "palpa/live/press_control.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace palpa::live {

const char* to_string(PressureLevel level) {
  switch (level) {
    case PressureLevel::Light: return "light";
    case PressureLevel::Medium: return "medium";
    case PressureLevel::Deep: return "deep";
    case PressureLevel::None: break;
  }
  return "none";
}

PressureLevel level_of(double fraction, const io::Thresholds& thresholds) {
  if (fraction < thresholds.light_max) return PressureLevel::Light;
  return fraction >= thresholds.deep_min ? PressureLevel::Deep : PressureLevel::Medium;
}

PressureDial::PressureDial(const io::Thresholds& thresholds, int index) : thresholds_(thresholds) {
  set_index(index);
}

void PressureDial::set_index(int index) { index_ = std::clamp(index, 0, kSettings - 1); }

PressureLevel PressureDial::level() const {
  return index_ < kStepsPerLevel ? PressureLevel::Light
         : index_ < 2 * kStepsPerLevel ? PressureLevel::Medium
                                       : PressureLevel::Deep;
}

double PressureDial::share() const {
  const double light = thresholds_.light_max, deep = std::max(thresholds_.deep_min, light);
  const double top = std::max(kMaxShare, deep);
  const std::array<double, 4> edges{0.0, light, deep, top};
  const int band = index_ / kStepsPerLevel;
  // An eighth into the band, its middle, an eighth before its end: the first and last steps
  // sit near the band's edges, so "just deep" is there for tissue that is stiff when deep.
  constexpr std::array<double, kStepsPerLevel> kAt{0.125, 0.5, 0.875};
  const double at = kAt[static_cast<std::size_t>(index_ % kStepsPerLevel)];
  const auto b = static_cast<std::size_t>(band);
  return edges[b] + at * (edges[b + 1] - edges[b]);
}

int PressureDial::middle_of(PressureLevel level) {
  switch (level) {
    case PressureLevel::Light: return 1;
    case PressureLevel::Deep: return 2 * kStepsPerLevel + 1;
    default: return kStepsPerLevel + 1;
  }
}

SurfaceFrame surface_frame(const mat::MatBody& body, double u, double v) {
  std::array<double, mat::kSkeletonChannels> sk{};
  body.skeleton().evaluate(u, v, sk);
  double n[3] = {0.0, 0.0, 1.0};
  mat::skeleton_normal(body.skeleton(), u, v, n);
  SurfaceFrame f;
  f.normal = Vec3(n[0], n[1], n[2]);
  const double r = std::max(0.0, sk[mat::kRadius]);
  f.top = Vec3(sk[mat::kX], sk[mat::kY], sk[mat::kZ]) + r * f.normal;
  f.thickness = 2.0 * r;
  f.stiffness = std::max(0.0, sk[mat::kStiffness]);
  return f;
}

SurfaceFollower::SurfaceFollower(const scene::Scene& scene, const FollowerOptions& options)
    : scene_(&scene), options_(options) {}

void SurfaceFollower::aim(const std::optional<render::SurfacePick>& pick) {
  if (!pick || pick->body >= scene_->size()) {
    aimed_on_body_ = false;
    return;
  }
  const auto& sb = scene_->body(pick->body);
  // The skeleton point whose normal passes through the picked top-contour point.
  const auto foot = sb.search.closest(sb.body.skeleton(), pick->point);
  aim_body_ = pick->body;
  aim_u_ = foot.u;
  aim_v_ = foot.v;
  aimed_on_body_ = true;
  if (!started_) {  // the first pick: start lifted over it
    started_ = true;
    body_ = aim_body_;
    u_ = aim_u_;
    v_ = aim_v_;
    press_ = -1.0;
  }
}

void SurfaceFollower::set_share(double share) {
  share_ = std::clamp(share, 0.0, PressureDial::kMaxShare);
  force_target_ = 0.0;
}

void SurfaceFollower::set_force_target(double newtons) {
  force_target_ = std::isfinite(newtons) ? std::max(0.0, newtons) : 0.0;
  if (force_target_ > 0.0) share_ = std::max(0.0, press_);
}

void SurfaceFollower::walk(double dt) {
  // Across to another body only through the air: lift first, then move over.
  if (aim_body_ != body_) {
    if (press_ > -1.0) return;
    body_ = aim_body_;
    u_ = aim_u_;
    v_ = aim_v_;
    return;
  }
  // Along the surface: a straight line in (u, v), at most max_speed * dt on the skin.
  const auto& body = scene_->body(body_).body;
  const Vec3 here = surface_frame(body, u_, v_).top;
  const Vec3 there = surface_frame(body, aim_u_, aim_v_).top;
  const double distance = (there - here).norm();
  const double reach = (press_ < 0.0 ? options_.lifted_speed : options_.max_speed) * dt;
  const double f = distance <= reach ? 1.0 : reach / distance;
  u_ += f * (aim_u_ - u_);
  v_ += f * (aim_v_ - v_);
}

double SurfaceFollower::desired_press(double dt, double felt) {
  if (!aimed_on_body_ || aim_body_ != body_) return -1.0;
  if (force_target_ > 0.0 && press_ >= 0.0) {
    // Integral control of the share on the force error, scaled by the local tissue's own
    // stiffness (a stiffer spot answers the same share with more force: it sinks less).
    const auto frame = surface_frame(scene_->body(body_).body, u_, v_);
    const double per_share = std::max(1e-6, frame.stiffness * frame.thickness);  // N per share
    share_ += options_.force_gain * dt * (force_target_ - felt) / per_share;
    share_ = std::clamp(share_, 0.0, PressureDial::kMaxShare);
  }
  return share_;
}

std::optional<Vec3> SurfaceFollower::advance(double dt, double felt) {
  if (!started_) return std::nullopt;
  dt = std::clamp(std::isfinite(dt) ? dt : 0.0, 0.0, 0.1);
  walk(dt);
  const double want = desired_press(dt, felt);
  // In the air (press < 0) the finger moves at the lift rate, in the tissue at the press rate.
  const double rate = (press_ < 0.0 || want < 0.0) && !(press_ > 0.0) ? options_.lift_rate
                      : want < press_                                  ? options_.release_rate
                                                                       : options_.press_rate;
  const double step = rate * dt;
  press_ += std::clamp(want - press_, -step, step);
  const auto frame = surface_frame(scene_->body(body_).body, u_, v_);
  // A share of the thickness under the skin, or a lift above it: never past the support.
  const double offset = press_ >= 0.0 ? -press_ * frame.thickness : -press_ * options_.lift;
  return frame.top + offset * frame.normal;
}

}  // namespace palpa::live
