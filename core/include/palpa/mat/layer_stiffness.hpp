#pragma once
// The stiffness of soft tissue under a fingertip, from its Young's modulus: a rigid flat
// pad of radius a pressed into an elastic layer of thickness h bonded to a rigid base
// (tissue on a chest wall, a pelvis, a table). Sneddon's half-space result times the
// bonded-layer factor of Hayes, Keer, Herrmann and Mockros (J. Biomech. 5 (1972) 541-551):
//
//     k = F / d = 2 a E kappa(a / h, nu) / (1 - nu^2)
//
// kappa >= 1 grows as the layer thins (20 mm of tissue under a 7.5 mm pad is 1.6 times
// stiffer than a half-space). docs/model.md, "Stiffness from the tissue's modulus", gives
// the derivation and the FEM checks (data/reference/).
#include <array>
#include <span>
#include <vector>

namespace palpa::mat {

/// m: the fingertip pad a stiffness is derived for (a pad about 15 mm across; the same
/// radius the tumour model and the coverage grid use).
inline constexpr double kFingertipPadRadius = 7.5e-3;

/// Hayes et al.'s kappa(a/h, nu) for a frictionless flat punch on a layer bonded to a rigid
/// base, solved from their Fredholm integral equation (not read from their table).
/// a_over_h in [0, 10], nu in [0, 0.5); throws std::invalid_argument outside.
double bonded_layer_factor(double a_over_h, double nu);

/// N/m: the small-depth stiffness of a pad of radius `pad_radius` (m) on a layer of
/// `thickness` (m) and Young's modulus `modulus` (Pa), Poisson's ratio `nu`. A layer
/// thinner than the pad radius is taken as that thick (where a body thins to its rim the
/// pad presses on the support beside it, which the support's wall renders).
double layer_stiffness(double modulus, double nu, double pad_radius, double thickness);

/// layer_stiffness for the many points of one material: kappa solved once at 33 values of
/// a/h over [0, 1] (the thickness floor keeps a/h <= 1) and interpolated by cubic Lagrange
/// polynomials through the four nearest, within 1e-6 of solving at each point.
class LayerStiffnessTable {
 public:
  LayerStiffnessTable(double nu, double pad_radius);
  /// N/m for `modulus` (Pa, finite and >= 0) over `thickness` (m).
  double operator()(double modulus, double thickness) const;

 private:
  static constexpr int kIntervals = 32;
  double nu_, pad_radius_;
  std::array<double, kIntervals + 1> kappa_{};
};

/// N/m per skeleton point of a body given by its modulus (Pa per point) over the local
/// thickness 2 radius (m per point), under the fingertip pad (kFingertipPadRadius): what a
/// case file's "modulus" becomes. The vectors have the same length.
std::vector<double> layer_stiffness_field(const std::vector<double>& modulus, const std::vector<double>& radius,
                                          double nu);

/// One tissue layer of a column under the pad: thickness (m) and Young's modulus (Pa).
struct TissueLayer {
  double thickness;
  double modulus;
};

/// Pa: the one modulus of a layered column (layers listed from the skin down, each bonded
/// to the next, the last to a rigid base, one Poisson's ratio `nu`) that gives its
/// small-depth stiffness under a flat pad of `pad_radius` (m) through Hayes' homogeneous
/// formula at the column's total thickness h, unfloored:
///   k = 2 a E_eff kappa(a / h, nu) / (1 - nu^2).
/// Solved exactly (within 1e-4) by extending Hayes et al.'s integral equation to the
/// layered column's surface compliance (docs/model.md, "Layered columns"); the FEM columns of
/// data/reference/twolayer_linear.csv agree within 2.6 %. Zero-thickness layers are skipped,
/// a single layer returns its modulus, a layer of zero modulus makes the column 0, and a
/// column thinner than a tenth of the pad radius (a/h > 10) takes its uniaxial-strain
/// limit, the layers as springs in series. Throws std::invalid_argument on an empty list,
/// a total thickness that is not > 0, a negative or non-finite value, or nu outside [0, 0.5).
double column_modulus(std::span<const TissueLayer> layers_from_skin, double nu,
                      double pad_radius = kFingertipPadRadius);

}  // namespace palpa::mat
