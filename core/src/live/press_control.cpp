#include "palpa/live/press_control.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

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

double force_bound(const io::Thresholds& thresholds) { return kForceBoundShare * thresholds.max_force; }

PressureDial::PressureDial(const io::Thresholds& thresholds, int index, double top)
    : thresholds_(thresholds), top_(std::clamp(std::isfinite(top) ? top : kMaxShare, 0.0, kMaxShare)) {
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
  const double top = std::max(top_, deep);
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

namespace {

// The (body, u, v) spots of the exam region on a regular grid of each of its parts (the
// whole top contour of every body when the case sets none).
std::vector<std::array<double, 3>> exam_spots(const scene::Scene& scene, const io::Thresholds& thresholds) {
  constexpr int kGrid = 13;
  std::vector<std::array<double, 3>> spots;
  const auto add = [&](std::size_t b, double u0, double u1, double v0, double v1) {
    for (int i = 0; i < kGrid; ++i)
      for (int j = 0; j < kGrid; ++j)
        spots.push_back({static_cast<double>(b), u0 + (u1 - u0) * i / (kGrid - 1), v0 + (v1 - v0) * j / (kGrid - 1)});
  };
  if (thresholds.exam_region.empty()) {
    for (std::size_t b = 0; b < scene.size(); ++b) add(b, 0.0, 1.0, 0.0, 1.0);
  }
  for (const auto& part : thresholds.exam_region) {
    for (std::size_t b = 0; b < scene.size(); ++b)
      if (scene.body(b).body.id() == part.body) add(b, part.u0, part.u1, part.v0, part.v1);
  }
  return spots;
}

}  // namespace

double deepest_plain_share(const scene::Scene& scene, const io::Thresholds& thresholds,
                           const scene::ProbeOptions& options, double bound, double room) {
  const double deep = std::max(thresholds.deep_min, thresholds.light_max);
  const double floor = std::min(PressureDial::kMaxShare, deep + (PressureDial::kMaxShare - deep) / 6.0);
  if (!(bound > 0.0)) return PressureDial::kMaxShare;
  auto state = scene.make_state();
  scene::ProbeOptions fresh = options;
  fresh.remember_side = false;
  const double allowed = bound / (1.0 + std::max(0.0, room));
  // The plain tissue's push-back at a spot and share: the force without the tumours' part.
  const auto plain = [&](const std::array<double, 3>& spot, double share) {
    const auto frame = surface_frame(scene.body(static_cast<std::size_t>(spot[0])).body, spot[1], spot[2]);
    if (!(frame.thickness > 0.0)) return 0.0;
    std::fill(state.warm.begin(), state.warm.end(), 0);
    state.held = -1;
    const auto r = scene.probe(frame.top - share * frame.thickness * frame.normal, state, fresh);
    return (r.force.total - r.force.tumour).norm();
  };
  // The answer is the least over the spots of the share where each reaches `allowed`. The
  // force grows with the share at every spot, so a spot within `allowed` at the best share
  // so far cannot lower it: only the others are bisected, the hardest-pressing first.
  std::vector<std::pair<double, std::array<double, 3>>> spots;
  for (const auto& spot : exam_spots(scene, thresholds)) spots.emplace_back(plain(spot, PressureDial::kMaxShare), spot);
  std::sort(spots.begin(), spots.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  double best = PressureDial::kMaxShare;
  for (const auto& [at_max, spot] : spots) {
    if (at_max <= allowed) break;  // this and every later spot stays within at the deepest share
    if (plain(spot, best) <= allowed) continue;
    if (plain(spot, floor) > allowed) return floor;
    double lo = floor, hi = best;  // within at lo, above at hi
    while (hi - lo > 2e-3) {
      const double mid = 0.5 * (lo + hi);
      (plain(spot, mid) > allowed ? hi : lo) = mid;
    }
    best = lo;
  }
  return best;
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

double apparent_firmness(const scene::Scene& scene, scene::ProbeState& state, const scene::ProbeOptions& options,
                         std::size_t body, double u, double v, double depth) {
  const auto& sb = scene.body(body);
  if (!sb.layer || !(depth > 0.0)) return 0.0;
  const auto frame = surface_frame(sb.body, u, v);
  std::fill(state.warm.begin(), state.warm.end(), 0);
  state.held = -1;
  scene::ProbeOptions fresh = options;
  fresh.remember_side = false;
  fresh.force.shear = false;  // the tissue's answer to pressing, not to sliding
  const auto r = scene.probe(frame.top - depth * frame.normal, state, fresh);
  if (r.body != static_cast<int>(body) || !(r.contact.radius > 0.0)) return 0.0;
  const double per_pascal = (*sb.layer)(1.0, 2.0 * r.contact.radius);  // N/m per Pa of this layer
  if (!(per_pascal > 0.0)) return 0.0;
  const double tissue = r.contact.stiffness / per_pascal;  // Pa: the modulus under the pad
  const double plain = r.force.normal.norm();
  const double with_tumours = (r.force.normal + r.force.tumour).norm();
  return plain > 0.0 ? tissue * with_tumours / plain : tissue;
}

SurfaceFollower::SurfaceFollower(const scene::Scene& scene, const FollowerOptions& options)
    : scene_(&scene), options_(options), probe_state_(scene.make_state()) {
  options_.probe.remember_side = false;  // every bound probe is a fresh press
}

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

double SurfaceFollower::force_at_share(double u, double v, double share) const {
  const auto frame = surface_frame(scene_->body(body_).body, u, v);
  const Vec3 q = frame.top - share * frame.thickness * frame.normal;
  std::fill(probe_state_.warm.begin(), probe_state_.warm.end(), 0);
  probe_state_.held = -1;
  return scene_->probe(q, probe_state_, options_.probe).force.total.norm();
}

double SurfaceFollower::bounded_share(double u, double v, double want) const {
  const double bound = options_.force_bound;
  if (!(bound > 0.0) || want <= 0.0 || force_at_share(u, v, want) <= bound) return want;
  double lo = 0.0, hi = want;  // f(lo) <= bound < f(hi)
  while (hi - lo > 1e-4) {
    const double mid = 0.5 * (lo + hi);
    (force_at_share(u, v, mid) <= bound ? lo : hi) = mid;
  }
  return lo;
}

// The share to press to, at most where the model's force reaches the bound: at the finger's
// new spot and halfway from where it was (a slide onto a lump must not overshoot between
// frames). The follower sees the engine's force only at the GUI's rate, so the bound is
// predicted from the model, and a force felt above it backs the finger off.
double SurfaceFollower::bound_press(double want, double felt, double from_u, double from_v) {
  bounded_ = false;
  if (!(options_.force_bound > 0.0) || want <= 0.0) return want;
  double cap = bounded_share(u_, v_, want);
  cap = std::min(cap, bounded_share(0.5 * (u_ + from_u), 0.5 * (v_ + from_v), want));
  if (felt > options_.force_bound && press_ > 0.0) cap = std::min(cap, press_ * options_.force_bound / felt);
  bounded_ = cap < want - 1e-3;
  return std::min(want, cap);
}

double SurfaceFollower::share_for_force(double u, double v, double newtons) const {
  const double top = PressureDial::kMaxShare;
  if (force_at_share(u, v, top) <= newtons) return top;
  double lo = 0.0, hi = top;  // f(lo) <= newtons < f(hi)
  while (hi - lo > 1e-4) {
    const double mid = 0.5 * (lo + hi);
    (force_at_share(u, v, mid) <= newtons ? lo : hi) = mid;
  }
  return lo;
}

// Force mode presses to the share where the model's fresh press reaches the target, found
// anew at every frame at the finger's spot: no loop closes through the engine's force, which
// the GUI sees late and at a rate that falls under load (an integral controller on it swung
// 0.65-18 N with two busy cores). The engine's force is that model's at the same point.
double SurfaceFollower::desired_press(bool hold) {
  if (!aimed_on_body_ || aim_body_ != body_) return -1.0;
  if (force_target_ > 0.0 && !hold) share_ = share_for_force(u_, v_, force_target_);
  return share_;
}

std::optional<Vec3> SurfaceFollower::advance(double dt, double felt, bool hold) {
  if (!started_) return std::nullopt;
  dt = std::clamp(std::isfinite(dt) ? dt : 0.0, 0.0, 0.1);
  const double from_u = u_, from_v = v_;
  const std::size_t from_body = body_;
  walk(dt);
  double want = desired_press(hold);
  if (want >= 0.0) {
    want = bound_press(want, felt, body_ == from_body ? from_u : u_, body_ == from_body ? from_v : v_);
  } else {
    bounded_ = false;
  }
  if (force_target_ > 0.0 && bounded_) share_ = std::min(share_, want);  // no wind-up at the bound
  if (hold) want = std::min(want, std::max(press_, 0.0));  // stalled or faulted: never deeper
  // In the air (press < 0) the finger moves at the lift rate, in the tissue at the press rate.
  const double rate = (press_ < 0.0 || want < 0.0) && !(press_ > 0.0) ? options_.lift_rate
                      : want < press_                                  ? options_.release_rate
                                                                       : options_.press_rate;
  const double step = rate * dt;
  press_ += std::clamp(want - press_, -step, step);
  at_bound_ = bounded_ && press_ >= want - 1e-3;  // arrived at the bound, not on the way to it
  const auto frame = surface_frame(scene_->body(body_).body, u_, v_);
  // A share of the thickness under the skin, or a lift above it: never past the support.
  const double offset = press_ >= 0.0 ? -press_ * frame.thickness : -press_ * options_.lift;
  return frame.top + offset * frame.normal;
}

}  // namespace palpa::live
