#pragma once
// The damped linear oscillator m x'' + b x' + k x = 0 of each control point (paper section
// 3.2), advanced by its exact solution: stable for every k, b >= 0, m > 0 and time step.

namespace palpa::deform {

/// The exact one-step map of (x, v) over a step dt: [x; v] <- [xx xv; vx vv] [x; v].
struct OscillatorStep {
  double xx = 1.0, xv = 0.0, vx = 0.0, vv = 1.0;

  /// For stiffness k (N/m, >= 0), damping b (N s/m, >= 0), mass m (kg, > 0) and dt (s,
  /// >= 0). Valid in every regime (under-, critically and over-damped, k = 0, b = 0) and
  /// for any magnitudes: no overflow, and the energy E = (m v^2 + k x^2) / 2 of the result
  /// never exceeds that of the input beyond round-off.
  static OscillatorStep exact(double k, double b, double m, double dt);

  void apply(double& x, double& v) const {
    const double x1 = xx * x + xv * v;
    v = vx * x + vv * v;
    x = x1;
  }
};

/// Damping for a target damping ratio zeta: b = 2 zeta sqrt(k m).
double damping_for_ratio(double k, double m, double zeta);

/// Damping such that an under- or critically damped point's amplitude envelope
/// exp(-b t / 2m) falls to `fraction` (e.g. 0.02) after `settling_time` seconds:
/// b = -2 m ln(fraction) / settling_time.
double damping_for_settling(double m, double settling_time, double fraction = 0.02);

}  // namespace palpa::deform
