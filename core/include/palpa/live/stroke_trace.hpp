#pragma once
// What a mouse user sees instead of feeling (docs/perception.md): the push-back trace of
// the current stroke and the finger that sticks on a firm spot.
//
// StrokeTrace keeps the tissue's apparent firmness (apparent_firmness(), kPa in the GUI)
// along the stroke the finger is sliding, for the last few seconds, with a baseline: the
// median firmness over the stroke's trailing few centimetres. A lump passing under the
// finger is a bump above the baseline, the way a hand feels a firm spot while sliding
// (the cue is change under a moving finger, not an absolute number).
//
// ControlDisplay is the pseudo-haptic finger (Lecuyer et al. 2000: stiffness shown by the
// ratio of the input's motion to the displayed motion): where the tissue is firmer than the
// stroke's baseline the on-screen finger follows the pointer more slowly, and it catches up
// once the tissue is plain again or the pointer rests.
#include <Eigen/Core>
#include <cstddef>
#include <deque>
#include <vector>

#include "palpa/vec3.hpp"

namespace palpa::live {

struct TracePoint {
  double t = 0.0;         ///< s on the haptic clock
  double along = 0.0;     ///< m the finger travelled on the skin since the stroke began
  double firmness = 0.0;  ///< Pa
  double baseline = 0.0;  ///< Pa: the stroke's baseline when this point was taken
  Vec3 at = Vec3::Zero(); ///< the finger (m)
  /// m: where the finger went into the skin (the rest top of its column, what the window's
  /// contact ring shows); the finger itself when not given.
  Vec3 skin = Vec3::Zero();
};

class StrokeTrace {
 public:
  /// s of stroke the trace shows (and a person remembers of it).
  static constexpr double kMemory = 3.0;
  /// m: the baseline is the median firmness over this much of the stroke behind the finger,
  /// sampled evenly along the skin (a resting finger does not outweigh a sliding one).
  static constexpr double kBaselineSpan = 0.04;
  /// m: a bump is judged only once the stroke has this much behind it.
  static constexpr double kSettledAlong = 0.015;
  /// m: a larger move of the finger between two frames is a jump (a new stroke), not a
  /// slide. The finger pressed deep in a curved body can move several millimetres in a frame
  /// while the pointer slides (its column turns under it): a slide at 10 cm/s moves 2 mm.
  static constexpr double kJump = 0.025;

  /// One frame's reading: the finger at `finger` reads `firmness` (Pa; 0 or less: off the
  /// body, or a body without a modulus) at pressure setting `setting` (any number naming
  /// the dial's step or the force target: a change starts a new stroke, since readings at
  /// two pressures are not comparable).
  void feed(double t, const Vec3& finger, double firmness, double setting) { feed(t, finger, firmness, setting, finger); }
  /// The same, with where the finger went into the skin (TracePoint::skin).
  void feed(double t, const Vec3& finger, double firmness, double setting, const Vec3& skin);
  /// The stroke's points of the last kMemory seconds, oldest first.
  const std::deque<TracePoint>& points() const { return points_; }
  /// The newest point's firmness over its baseline; 1 when there is no stroke or it has not
  /// settled yet (kSettledAlong).
  double contrast() const;
  /// m travelled on the skin since the stroke began.
  double along() const { return along_; }
  /// Bumped each time a stroke begins.
  std::size_t stroke() const { return stroke_; }

 private:
  void restart();
  double baseline() const;

  std::deque<TracePoint> points_;
  struct Spot {
    double along, firmness;
  };
  std::deque<Spot> spots_;  // even along the skin, for the baseline
  mutable std::vector<double> scratch_;  // the baseline's median, without a new buffer a frame
  double along_ = 0.0;
  double setting_ = 0.0;
  std::size_t stroke_ = 0;
  bool on_ = false;
};

/// The control/display gain of the pseudo-haptic finger for a contrast (firmness over the
/// stroke's baseline): (1 / contrast)^kGainPower, between kMinGain and 1.
inline constexpr double kGainPower = 2.0;
inline constexpr double kMinGain = 0.35;
double control_display_gain(double contrast);

class ControlDisplay {
 public:
  /// s: the finger catches up with the pointer with this time constant.
  static constexpr double kCatchUp = 0.2;
  /// The finger never lags the pointer by more than this (px).
  static constexpr double kMaxLag = 30.0;

  /// The pointer is at `pointer` (px) now, `dt` s after the last call, over tissue that
  /// gives `gain` (control_display_gain). Returns where the finger is shown (px): moved by
  /// gain times the pointer's move, catching up when the gain is 1 or the pointer rests.
  Eigen::Vector2d follow(const Eigen::Vector2d& pointer, double gain, double dt);
  /// The finger jumps to the pointer (it left the bodies, the view turned).
  void reset(const Eigen::Vector2d& at);
  const Eigen::Vector2d& finger() const { return finger_; }
  /// px between the pointer and the finger.
  double lag() const { return (pointer_ - finger_).norm(); }

 private:
  Eigen::Vector2d pointer_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d finger_ = Eigen::Vector2d::Zero();
  double rest_ = 0.0;  // s the pointer has not moved
  bool started_ = false;
};

}  // namespace palpa::live
