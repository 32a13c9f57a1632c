#pragma once
// The rounded finger (docs/model.md, "A rounded finger"): the force of a rigid sphere of
// radius R pressed into an elastic layer of thickness h bonded to a rigid base, for cases
// whose "indenter" is "finger" (the flat pad of layer_stiffness.hpp is the default).
//
//   Sneddon (1965), rigid sphere on a half-space, contact radius c:
//       d = (c / 2) ln((R + c) / (R - c)),
//       F = E* / 2 [(c^2 + R^2) ln((R + c) / (R - c)) - 2 c R],   E* = E / (1 - nu^2);
//   Dimitriadis et al. (Biophys. J. 82, 2002), bonded layer, chi = c / h:
//       D(chi) = 1 - 2 a0 chi / pi + 4 a0^2 chi^2 / pi^2
//                - 8 (a0^3 + 4 pi^2 b0 / 15) chi^3 / pi^3 + 16 a0 (a0^3 + 3 pi^2 b0 / 5) chi^4 / pi^4,
//       a0 = -(1.2876 - 1.4678 nu + 1.3442 nu^2) / (1 - nu),  b0 = (0.6387 - 1.0277 nu + 1.5164 nu^2) / (1 - nu);
//   a finite-strain softening fitted to the neo-Hookean FEM reference (data/reference):
//       S = 1 / (1 + s (d / R)^2 (h / R)^t).
// Allocation-free; for the haptic tick.

namespace palpa::contact {

/// m: a fingertip's radius of curvature (the FEM reference's sphere).
inline constexpr double kFingertipRadius = 8e-3;

/// s and t fitted (least squares on log F) to the two neo-Hookean finger curves of
/// data/reference, 40 mm to 9.5 mm deep and 20 mm to 8 mm: within 4.2 % of both.
struct FingerLaw {
  double radius = kFingertipRadius;      ///< m, R
  double softening = 0.0879;             ///< s
  double softening_layer_power = 0.2581; ///< t
};

/// c (m): Sneddon's contact radius of a rigid sphere of radius R pressed `depth` (m) deep;
/// 0 for depth <= 0, below R for any depth.
double sphere_contact_radius(double depth, double R);

/// Dimitriadis et al.'s bonded-layer factor D(chi) for Poisson's ratio nu, chi = c / h
/// (clamped to [0, 1], where the series still grows monotonically).
double bonded_sphere_factor(double chi, double nu);

/// N: the force of the finger pressed `depth` (m) into a layer of `thickness` (m), Young's
/// modulus `modulus` (Pa) and Poisson's ratio `nu` over a rigid base. A layer thinner than R
/// is taken as that thick (as the pad's stiffness takes a layer thinner than the pad).
double finger_force(double modulus, double nu, double depth, double thickness, const FingerLaw& law = {});
/// The same with Sneddon's contact radius `c` = sphere_contact_radius(depth, law.radius)
/// already known: the haptic tick finds it once for the tissue and every tumour.
double finger_force_at_contact(double modulus, double nu, double depth, double thickness, double c,
                               const FingerLaw& law);

}  // namespace palpa::contact
