#pragma once
// Pressure for a mouse (docs/user-guide.md, "How pressure works"). A mouse has no force:
// the trainee chooses a pressure and the finger follows the surface under the pointer at
// it. PressureDial is the choice in the trainee's terms (light, medium, deep: the score's
// own bands, a share of the local tissue thickness, with three steps inside each band);
// SurfaceFollower turns the pointer's pick and that share into the probe's target, walking
// along the top contour (never a chord through the body), lifting off the body, and
// never pressing past the support.
#include <cstddef>
#include <optional>

#include "palpa/scene/scene.hpp"
#include "palpa/io/thresholds.hpp"
#include "palpa/render/surface_pick.hpp"
#include "palpa/vec3.hpp"

namespace palpa::live {


enum class PressureLevel : std::uint8_t { None, Light, Medium, Deep };
const char* to_string(PressureLevel level);

/// The level a press of `fraction` of the local thickness counts as (the score's bands).
PressureLevel level_of(double fraction, const io::Thresholds& thresholds);

/// The finger stops at this share of the case's safety gate (Thresholds::max_force) wherever
/// a dial setting or a force target would take it further: the gate and the steps are read
/// from the same thresholds, so they cannot disagree.
inline constexpr double kForceBoundShare = 0.9;
/// N: kForceBoundShare of the case's max_force.
double force_bound(const io::Thresholds& thresholds);

/// Nine settings, three per level, from the lightest light to the deepest deep.
class PressureDial {
 public:
  static constexpr int kStepsPerLevel = 3;
  static constexpr int kSettings = 3 * kStepsPerLevel;
  /// The deepest share it offers: the last quarter of the tissue is left to the support.
  static constexpr double kMaxShare = 0.85;

  /// `top`: the deepest share the case allows (deepest_plain_share; kMaxShare at most).
  explicit PressureDial(const io::Thresholds& thresholds, int index = 4, double top = kMaxShare);
  int index() const { return index_; }
  void set_index(int index);
  void step(int delta) { set_index(index_ + delta); }
  PressureLevel level() const;
  /// 1 .. kStepsPerLevel within the level.
  int step_in_level() const { return index_ % kStepsPerLevel + 1; }
  /// The share of the local thickness this setting presses to: an eighth into the band,
  /// its middle and an eighth before its end (light [0, light_max), medium [light_max,
  /// deep_min), deep [deep_min, top]).
  double share() const;
  /// The first setting of a level (Light, Medium or Deep), its middle step.
  static int middle_of(PressureLevel level);

 private:
  io::Thresholds thresholds_;
  int index_ = 4;
  double top_ = kMaxShare;
};

/// How much firmer than plain tissue a spot may be and still read under the force bound at
/// the deepest step: a tumour of the bundled ladder adds 5-60 % at a deep press.
inline constexpr double kLumpRoom = 0.6;

/// The deepest share the pressure dial offers on a case: where the case's plain tissue
/// (its tumours left out) pushes back with at most bound / (1 + room) over its whole exam
/// region, so no step is held at the bound over plain tissue and a lump up to `room`
/// firmer still reads above its surroundings (docs/user-guide.md, "How pressure works").
/// At most PressureDial::kMaxShare; never below the case's deep_min plus a sixth of the
/// deep band, so deep stays deep where the tissue is too stiff for that (the bound then
/// holds the press). Fresh probes on a 13 x 13 grid of each exam-region part.
double deepest_plain_share(const scene::Scene& scene, const io::Thresholds& thresholds,
                           const scene::ProbeOptions& options, double bound, double room = kLumpRoom);

/// Where the top contour is over a skeleton point, as the contact measures it.
struct SurfaceFrame {
  Vec3 top = Vec3::Zero();       ///< m, SK(u,v) + R N: depth 0 of the contact
  Vec3 normal = Vec3::UnitZ();   ///< unit skeleton normal N (out of the top)
  double thickness = 0.0;        ///< m, 2R
  double stiffness = 0.0;        ///< N/m, k(u,v)
};
SurfaceFrame surface_frame(const mat::MatBody& body, double u, double v);

/// m: tissue thinner than a fingertip pad is wide (2 x 7.5 mm). There a press reads the
/// skin over the support more than the tissue, and a firmness is said to be of thin tissue.
inline constexpr double kThinTissue = 0.015;  // twice mat::kFingertipPadRadius

/// Pa: the firmness force mode shows (docs/user-guide.md, "Force mode"): the modulus of a
/// uniform layer of the local thickness that would push back as this spot does at this
/// depth. The tissue's modulus under the pad times the contrast the tumours add there; so
/// thickness, strain stiffening and the support (which a trainee cannot see) do not enter,
/// and it is never negative. 0 for a body given in N/m (no modulus) or without contact.
double apparent_firmness(const scene::Scene& scene, scene::ProbeState& state, const scene::ProbeOptions& options,
                         std::size_t body, double u, double v, double depth);

struct FollowerOptions {
  double lift = 0.015;       ///< m above the surface when the pointer is off the bodies
  double max_speed = 0.40;   ///< m/s along the surface, pressing (a pointer jump becomes a fast slide)
  double lifted_speed = 0.8; ///< m/s over the surface while lifted (the finger moves through the air)
  double press_rate = 3.0;   ///< shares of the thickness per second, pressing in
  double release_rate = 6.0; ///< shares of the thickness per second, easing off (a finger lets go faster)
  double lift_rate = 8.0;    ///< lifts per second, rising off or coming down to the skin
  /// N: no press goes past the share where the model's force reaches this (force_bound());
  /// 0: no bound.
  double force_bound = 0.0;
  /// How the bound is predicted: a fresh probe of the rest scene, as the engine's tick
  /// queries it (pass the engine's options so shear and the indenter match).
  scene::ProbeOptions probe{};
};

class SurfaceFollower {
 public:
  explicit SurfaceFollower(const scene::Scene& scene, const FollowerOptions& options = {});

  /// The pointer is over a top contour at `pick`, or off every body (nullopt): lift there.
  void aim(const std::optional<render::SurfacePick>& pick);
  /// Level mode: press to this share of the local thickness (clamped to [0, kMaxShare]).
  void set_share(double share);
  /// Force mode: sink to where the model's |F| is `newtons` (over a stiff lump the finger sinks less);
  /// 0 returns to level mode at the current share.
  void set_force_target(double newtons);
  double force_target() const { return force_target_; }

  /// Advances dt seconds; `felt` is |F| now (a force felt past the bound backs the finger
  /// off). `hold`: the haptic loop is stalled or faulted, so `felt` is stale or zero: the
  /// finger does not press deeper and force mode keeps its share. Returns the probe target, or nothing before the first pick.
  std::optional<Vec3> advance(double dt, double felt, bool hold = false);

  /// The press is held at the force bound (the chosen share or force would go further).
  bool at_force_bound() const { return at_bound_; }
  double force_bound() const { return options_.force_bound; }
  /// The deepest share at (u, v) whose fresh probe force stays within the force bound
  /// (the whole `want` when it does; no bound: `want`). Bisection to a 1e-4 share.
  double bounded_share(double u, double v, double want) const;

  bool started() const { return started_; }
  std::size_t body() const { return body_; }
  double u() const { return u_; }
  double v() const { return v_; }
  /// The commanded press: a share of the thickness (>= 0), or a lift (-1 .. 0: -1 is the full lift).
  double press() const { return press_; }
  /// Whether the finger means to press (the pointer is on a body).
  bool on_body() const { return aimed_on_body_; }

 private:
  void walk(double dt);
  double desired_press(bool hold);
  double force_at_share(double u, double v, double share) const;
  /// Force mode: the shallowest share at (u, v) whose fresh press reaches `newtons`
  /// (kMaxShare if none does). Bisection to a 1e-4 share.
  double share_for_force(double u, double v, double newtons) const;
  double bound_press(double want, double felt, double from_u, double from_v);

  const scene::Scene* scene_;
  FollowerOptions options_;
  bool started_ = false;
  bool aimed_on_body_ = false;
  std::size_t body_ = 0, aim_body_ = 0;
  double u_ = 0.5, v_ = 0.5, aim_u_ = 0.5, aim_v_ = 0.5;
  double press_ = -1.0;
  double share_ = 0.35;
  double force_target_ = 0.0;
  bool bounded_ = false;   // the bound cuts the wanted press short
  bool at_bound_ = false;  // ... and the finger has got there
  mutable scene::ProbeState probe_state_;  // the bound's fresh probes (sized once)
};

}  // namespace palpa::live
