#pragma once
// What the finger felt between two frames of the window. The window learns where the finger
// is once a frame, but the finger slid over everything in between: on a busy computer
// (10 frames a second) a stroke at 10 cm/s would be sampled only every 10 mm and a lump's
// top, 12 mm across, fall between two samples. The push-back trace is fed the path between
// the last two snapshots felt every kFeltStep of it instead, so what it draws does not
// depend on the frame rate (docs/perception.md, "The push-back trace").
#include <vector>

#include "palpa/scene/scene.hpp"

namespace palpa::live {

/// One end of a stretch of the finger's path: the snapshot's time, finger and contact.
struct ContactEnd {
  double t = 0.0;               ///< s on the haptic clock
  Vec3 finger = Vec3::Zero();   ///< m
  int body = -1;                ///< contacted body, -1 when none
  double u = 0.0, v = 0.0;      ///< the contact's skeleton parameters
  double depth = 0.0;           ///< m of indentation
};

/// The finger somewhere along that path, and the tissue it felt there.
struct FeltPoint {
  double t = 0.0;
  Vec3 finger = Vec3::Zero();
  double firmness = 0.0;   ///< Pa (apparent_firmness); 0 off the bodies
  double thickness = 0.0;  ///< m: the tissue's local thickness 2R there; 0 off the bodies
  /// m: where the finger went into the skin, the rest top of its column (the finger itself
  /// off the bodies), and the skin's outward normal there.
  Vec3 skin = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
};

/// m of path between two felt points, at most.
inline constexpr double kFeltStep = 0.001;
/// Felt points per stretch, at most (a 64 mm jump between two frames is a jump, not a
/// stroke; the trace restarts at one of 25 mm anyway).
inline constexpr int kFeltMost = 64;

/// The path from `from` (excluded) to `to` (included), straight in the skeleton's (u, v),
/// the depth, the finger and the time, felt every kFeltStep of the finger's travel. Only
/// `to` when the two are not on one body in contact, the parameters wrap round (a jump of
/// more than half their range) or the time does not advance. Clears `out` first.
void felt_between(const scene::Scene& scene, scene::ProbeState& state, const scene::ProbeOptions& options,
                  const ContactEnd& from, const ContactEnd& to, std::vector<FeltPoint>& out);

}  // namespace palpa::live
