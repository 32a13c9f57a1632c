#include "palpa/contact/finger.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace palpa::contact {
namespace {

// Sneddon's depth of a sphere with contact radius c: d(c) = (c / 2) ln((R + c) / (R - c)).
double sphere_depth(double c, double R) { return 0.5 * c * std::log((R + c) / (R - c)); }

}  // namespace

double sphere_contact_radius(double depth, double R) {
  if (!(depth > 0.0) || !(R > 0.0)) return 0.0;
  // d(c) rises monotonically from 0 to infinity over (0, R): bisect on c / R, then polish
  // with Newton's method (d'(c) = d / c + c R / (R^2 - c^2)). 60 halvings reach 1e-18 R.
  double lo = 0.0, hi = R;
  double c = std::min(std::sqrt(R * depth), 0.5 * R);  // Hertz's c = sqrt(R d) as the first guess
  for (int k = 0; k < 60; ++k) {
    if (sphere_depth(c, R) > depth) hi = c; else lo = c;
    if (hi - lo <= 1e-15 * R) break;
    const double slope = sphere_depth(c, R) / c + c * R / (R * R - c * c);
    const double next = c - (sphere_depth(c, R) - depth) / slope;
    c = (next > lo && next < hi) ? next : 0.5 * (lo + hi);
  }
  return c;
}

double bonded_sphere_factor(double chi, double nu) {
  constexpr double pi = std::numbers::pi;
  const double x = std::clamp(chi, 0.0, 1.0);
  const double a0 = -(1.2876 - 1.4678 * nu + 1.3442 * nu * nu) / (1.0 - nu);
  const double b0 = (0.6387 - 1.0277 * nu + 1.5164 * nu * nu) / (1.0 - nu);
  return 1.0 - 2.0 * a0 * x / pi + 4.0 * a0 * a0 * x * x / (pi * pi) -
         8.0 * (a0 * a0 * a0 + 4.0 * pi * pi * b0 / 15.0) * x * x * x / (pi * pi * pi) +
         16.0 * a0 * (a0 * a0 * a0 + 3.0 * pi * pi * b0 / 5.0) * x * x * x * x / (pi * pi * pi * pi);
}

double finger_force(double modulus, double nu, double depth, double thickness, const FingerLaw& law) {
  return finger_force_at_contact(modulus, nu, depth, thickness, sphere_contact_radius(depth, law.radius), law);
}

double finger_force_at_contact(double modulus, double nu, double depth, double thickness, double c,
                               const FingerLaw& law) {
  const double R = law.radius;
  if (!(depth > 0.0) || !(modulus > 0.0) || !(R > 0.0)) return 0.0;
  const double h = std::isfinite(thickness) ? std::max(thickness, R) : R;
  const double e_star = modulus / (1.0 - nu * nu);
  const double half_space = 0.5 * e_star * ((c * c + R * R) * std::log((R + c) / (R - c)) - 2.0 * c * R);
  const double strain = depth / R;
  const double softening = 1.0 / (1.0 + law.softening * strain * strain * std::pow(h / R, law.softening_layer_power));
  return half_space * bonded_sphere_factor(c / h, nu) * softening;
}

}  // namespace palpa::contact
