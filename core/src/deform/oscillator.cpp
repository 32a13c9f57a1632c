#include "palpa/deform/oscillator.hpp"

#include <cmath>

namespace palpa::deform {

OscillatorStep OscillatorStep::exact(double k, double b, double m, double dt) {
  OscillatorStep s;
  if (!(dt > 0.0) || !(m > 0.0)) return s;
  k = k > 0.0 ? k : 0.0;
  b = b > 0.0 ? b : 0.0;
  // x = exp(-alpha t) y with y'' = beta^2 y, beta^2 = alpha^2 - w2 (see docs/model.md).
  const double alpha = b / (2.0 * m);
  const double w2 = k / m;
  const double beta2 = alpha * alpha - w2;
  double ec = 0.0;  // exp(-alpha t) C(t), C'' = beta^2 C, C(0) = 1, C'(0) = 0
  double es = 0.0;  // exp(-alpha t) S(t), S'' = beta^2 S, S(0) = 0, S'(0) = 1
  double xx = 0.0;
  double vv = 0.0;
  const double z = beta2 * dt * dt;
  if (std::abs(z) < 1e-4) {
    // Near critical damping the closed forms cancel: use the series of C and S.
    const double decay = std::exp(-alpha * dt);
    ec = decay * (1.0 + z / 2.0 + z * z / 24.0);
    es = decay * dt * (1.0 + z / 6.0 + z * z / 120.0);
    xx = ec + alpha * es;
    vv = ec - alpha * es;
  } else if (beta2 < 0.0) {  // under-damped
    const double wd = std::sqrt(-beta2);
    const double decay = std::exp(-alpha * dt);
    ec = decay * std::cos(wd * dt);
    es = decay * std::sin(wd * dt) / wd;
    xx = ec + alpha * es;
    vv = ec - alpha * es;
  } else {  // over-damped: combine the exponentials so nothing overflows
    const double beta = std::sqrt(beta2);
    const double slow = w2 / (alpha + beta);  // alpha - beta without cancellation
    const double fast = alpha + beta;
    const double e1 = std::exp(-slow * dt);
    const double e2 = std::exp(-fast * dt);
    es = (e1 - e2) / (2.0 * beta);
    xx = (e1 * fast - e2 * slow) / (2.0 * beta);
    vv = (e2 * fast - e1 * slow) / (2.0 * beta);
  }
  s.xx = xx;
  s.xv = es;
  s.vx = -w2 * es;
  s.vv = vv;

  // Guard: in the energy norm (sqrt(k) x, sqrt(m) v) the exact map is a contraction; make
  // sure round-off cannot lift its norm above 1.
  if (k > 0.0) {
    const double rk = std::sqrt(k);
    const double rm = std::sqrt(m);
    const double a = s.xx;
    const double bb = s.xv * rk / rm;
    const double c = s.vx * rm / rk;
    const double d = s.vv;
    // Largest squared singular value of [[a, bb], [c, d]]; the discriminant frob^2 - 4 det^2
    // is written as a product of sums of squares, which does not cancel for the rotations
    // of an undamped oscillator (where it is exactly 0).
    const double frob = a * a + bb * bb + c * c + d * d;
    const double disc = std::sqrt(((a - d) * (a - d) + (bb + c) * (bb + c)) * ((a + d) * (a + d) + (bb - c) * (bb - c)));
    const double sigma2 = 0.5 * (frob + disc);
    if (sigma2 > 1.0) {
      const double scale = 1.0 / std::sqrt(sigma2);
      s.xx *= scale;
      s.xv *= scale;
      s.vx *= scale;
      s.vv *= scale;
    }
  } else if (std::abs(s.vv) > 1.0) {
    s.vv = s.vv > 0.0 ? 1.0 : -1.0;
  }
  return s;
}

double damping_for_ratio(double k, double m, double zeta) { return 2.0 * zeta * std::sqrt(k * m); }

double damping_for_settling(double m, double settling_time, double fraction) {
  return -2.0 * m * std::log(fraction) / settling_time;
}

}  // namespace palpa::deform
