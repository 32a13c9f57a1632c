#pragma once
// A body as drawn: its rest model plus the displacements of its control points, pressed
// by the probe and springing back (paper sections 3.2 and 3.3; docs/model.md).
#include <array>
#include <cstdint>
#include <vector>

#include "palpa/contact/contact.hpp"
#include "palpa/deform/oscillator.hpp"
#include "palpa/mat/mat_body.hpp"

namespace palpa::deform {

enum class Scheme {
  SkeletonMoves,  ///< (a) the skeleton moves by the press and both contours follow
  Compression,    ///< (b) the skeleton moves by g * depth, the radius shrinks by (1 - g) * depth
};

struct DeformOptions {
  Scheme scheme = Scheme::Compression;
  double g = 0.5;  ///< share of the press taken by the skeleton in scheme (b); 0.5 keeps the far side still
  /// The p' x q' most influential control points a press moves (0: all (p+1) x (q+1)).
  int influence_u = 0;
  int influence_v = 0;
  bool dynamics = true;  ///< false: released points return to rest at once
  /// A body sleeps (no integration) once every displacement is below this (m) and every
  /// velocity below sleep_velocity (m/s); it is then put exactly at rest.
  double sleep_displacement = 1e-7;
  double sleep_velocity = 1e-5;
  /// m: refine the drawn surfaces by knot insertion (The NURBS Book A5.4) until no knot
  /// span is longer than this on the top contour, so that a press moves a patch the size
  /// of a fingertip (a cubic's support is four spans: 4 mm spans give a 16 mm dent, a
  /// fingertip pad is about 15 mm across) rather than a fifth of the body. 0 draws the
  /// fitted control net as the paper does. The contact and force never see the refinement.
  double display_span = 0.0;
  /// At most this many control points per direction after refinement (memory and tick bound).
  int max_display_points = 72;
};

/// The rest body's skeleton and contours as DeformedBody draws them: refined by knot
/// insertion to DeformOptions::display_span (the same knots in all three), or copies of
/// the fitted surfaces when display_span is 0. The same surfaces, evaluated at any (u, v).
struct DisplayNet {
  spline::BSplineSurface skeleton, top, bottom;
};
DisplayNet display_net(const mat::MatBody& rest, const DeformOptions& options);

class DeformedBody {
 public:
  /// Sizes everything once: press() and step() allocate nothing afterwards.
  explicit DeformedBody(const mat::MatBody& rest, const DeformOptions& options = {});

  const mat::MatBody& rest() const { return *rest_; }
  /// The drawn surfaces at rest: the rest body's, refined for display (display_net).
  const spline::BSplineSurface& rest_skeleton() const { return net_.skeleton; }
  const spline::BSplineSurface& rest_top() const { return net_.top; }
  const spline::BSplineSurface& rest_bottom() const { return net_.bottom; }
  const spline::BSplineSurface& skeleton() const { return skeleton_; }
  const spline::BSplineSurface& top() const { return top_; }
  const spline::BSplineSurface& bottom() const { return bottom_; }
  const DeformOptions& options() const { return options_; }
  /// Switches the springs on or off (off: a release puts the body at rest at once).
  /// Turning dynamics off puts a body the finger has left at rest at once (a dent still
  /// springing back stops there); a held dent goes back when the finger leaves.
  void set_dynamics(bool on);

  /// Moves the surface under the probe onto the probe (the contact is computed on the rest
  /// model, so the force it gives is the force for what is drawn). The pressed control
  /// points are held there until the next press or release.
  void press(const contact::Contact& contact, const palpa::Vec3& q);
  /// The probe left: every control point springs back.
  void release();
  /// Advances the free control points by dt seconds; a body at rest does nothing.
  void step(double dt);

  bool awake() const { return awake_; }
  /// Increments whenever the drawn surfaces change (tessellation redoes only changed bodies).
  std::uint64_t version() const { return version_; }
  /// Largest control-point displacement from rest (m), over skeleton and contours.
  double max_displacement() const;
  /// Kinetic + spring energy of the control points (J), for tests and benchmarks.
  double energy() const;

 private:
  static constexpr int kComponents = 10;  // SK x y z r, top x y z, bottom x y z
  void write_back(std::size_t point);
  void rebuild_steps(double dt);
  void activate(std::size_t point);
  /// Un-holds the points the last press held; with `snap`, those left with a displacement
  /// below an invisible 10 um are put at rest at once (a slide, not a release).
  void clear_hold(bool snap);
  void put_at_rest();  ///< every displaced point exactly at rest; the body sleeps

  const mat::MatBody* rest_;
  DeformOptions options_;
  DisplayNet net_;                     // the drawn surfaces at rest
  spline::BSplineSurface skeleton_, top_, bottom_;
  int rows_, cols_;
  std::vector<double> x_, v_;          // per control point, kComponents each: displacement, velocity
  std::vector<double> k_, b_, m_;      // per control point
  std::vector<OscillatorStep> steps_;  // per control point, for step_dt_
  std::vector<char> held_;             // pressed this tick: positioned, not integrated
  std::vector<std::uint32_t> active_;  // points displaced or moving (capacity: all, never reallocates)
  std::vector<char> is_active_;
  std::array<std::uint32_t, 64> held_list_{};  // the last press's support: at most (p+1)(q+1), p, q <= 7
  std::size_t held_count_ = 0;
  double step_dt_ = -1.0;
  bool awake_ = false;
  std::uint64_t version_ = 0;
};

}  // namespace palpa::deform
