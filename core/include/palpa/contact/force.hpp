#pragma once
// Contact force (paper section 3.4, docs/model.md): the normal spring k(u,v) * depth,
// four shear springs to the contour at (u +- delta, v) and (u, v +- delta), and the
// tumours a press reaches.
#include <span>

#include "palpa/contact/contact.hpp"
#include "palpa/contact/finger.hpp"
#include "palpa/mat/tumour.hpp"

namespace palpa::contact {

/// How a tumour is felt (docs/model.md, "Tumours"). A tumour whose top lies s below the
/// surface is met once the indentation passes reach * s; its spring then adds smoothly
/// (a C1 ramp of width `ramp`), weighted by how far the tumour is beside the finger pad.
struct TumourFeel {
  double reach = 0.7;          ///< share of the overlying tissue a press must push through
  double ramp = 1e-3;          ///< m, width of the smooth onset (no step a device would buzz on)
  double pad_radius = 7.5e-3;  ///< m, fingertip pad radius: lateral reach beyond the tumour
};

/// How a tumour given in Pa is felt (docs/model.md, "Tumours in Pa"): it adds C - 1 times
/// the normal force, C the contrast a finite-element model gives for a stiff sphere of
/// radius r, centre s below the skin and modulus q times the tissue's, under a flat pad of
/// radius a on a layer of thickness h over a rigid base:
///
///     C - 1 = A (q - 1) / (q + g) (r / a)^m (1 + (s / (k a))^2)^(-p) ((h - s) / h)^d
///             (h / a)^e (max(s - r, h / 20) / a)^(-c)
///
/// (the clamps of s to 0.95 h and of s - r to h / 20 rounded C1 over 0.5 % of h)
///
/// fitted to the on-axis FEM sweeps of data/reference, layers of 20, 30 and 40 mm
/// (tools/fem/fit_contrast.py: within 14.2 % of C - 1 on 72 inclusions, 19.8 % on a layer
/// left out of the fit). Beside the pad's axis the extra force fades C1 with the finger's
/// offset rho from the tumour's centre: w = 1 - 3x^2 + 2x^3, x = rho / (2 l) clamped to
/// [0, 1], with l = a + spread s the half-width (C - 1 halves at rho = l), fitted to the 3-D
/// sweep of data/reference (tools/fem/lateral.py); a tumour wider than l keeps its full
/// contrast over its inside (x = (rho - (r - l)) / (2 l) there).
struct TumourContrast {
  double a_scale = 5.373;      ///< A
  double ratio_knee = 1.691;   ///< g: (q - 1) / (q + g) saturates for a rigid sphere
  double size_power = 3.326;   ///< m: about the inclusion's volume
  double depth_power = 2.977;  ///< p: the pad's strain field decaying along its axis
  double depth_knee = 2.336;   ///< k, in pad radii: where that decay sets in
  double base_power = 0.3258;  ///< d: the rigid base shields an inclusion near it
  double layer_power = -0.7517;  ///< e: a thinner layer makes an inclusion a larger part of it
  double gap_power = -0.4377;  ///< c: an inclusion nearly reaching the skin saturates its size effect
  double lateral_spread = 0.24;  ///< the half-width grows by this per metre of depth: the pad's field spreads
  double pad_radius = 7.5e-3;  ///< m, a
  /// Evaluate C - 1 on the layer as the press compresses it: s and h shrink by 1 - eps at
  /// the nominal strain eps = depth / h (saturating smoothly at half the layer), which gives
  /// the neo-Hookean FEM twins' growth with the press within 2 %; false: the small-strain
  /// limit, the linear sweeps' contrast at every press.
  bool compressed = true;
  /// Under the rounded finger (ForceOptions::finger) the model is read with the pad radius
  /// the finger's contact acts like, a_f = alpha a (c / a)^n for Sneddon's contact radius c
  /// at the press d, the layer power e_f for e, the tissue over and under the tumour
  /// shortened by kappa d, and C - 1 scaled by beta; fitted to the three neo-Hookean finger
  /// twins of data/reference (tools/fem/fit_finger_contrast.py: every press within 0.87 of
  /// the bench's mark, max(0.2 (C - 1), 0.02)).
  struct Finger {
    double radius_scale = 0.8791;   ///< alpha
    double radius_power = 0.7054;   ///< n: a small contact acts wider than it is
    double scale = 0.5496;          ///< beta
    double shift = 0.3214;          ///< kappa: the share of the press that thins the tissue over the tumour
    double layer_power = -0.4256;   ///< e_f: a small contact feels the layer's thickness less than the pad
  } finger{};
};

/// w: the share of a tumour's on-axis contrast felt with the finger `lateral` (m) beside
/// its centre, for a tumour of radius r whose centre lies s below the skin (1 on the axis,
/// 0 from 2 l on; C1).
double contrast_lateral_weight(double lateral, double r, double s, const TumourContrast& model = {});

/// The calibrated normal force's factor for strain stiffening (docs/model.md, "Strain
/// stiffening"): a layer whose tangent modulus is E exp(b eps) at the nominal strain
/// eps = depth / thickness pushes back with (exp(b eps) - 1) / (b eps) times its small-strain
/// force (1 for b = 0 or eps <= 0).
double stiffening_factor(double strain, double b);

/// C - 1 for a tumour of radius r, centre s below the skin, modulus ratio q, in tissue of
/// local thickness h, on the pad's axis (q <= 1 or a degenerate layer: 0), in the small-strain
/// limit: the linear FEM's contrast.
double tumour_contrast(double r, double s, double q, double h, const TumourContrast& model = {});

/// C - 1 for the same tumour under the rounded finger of radius R pressed d deep (its
/// contact radius from sphere_contact_radius; 0 before contact): TumourContrast::Finger.
double finger_tumour_contrast(double r, double s, double q, double h, double d, double R,
                              const TumourContrast& model = {});
/// The same with the contact radius c (sphere_contact_radius(d, R)) already known.
double finger_tumour_contrast_at_contact(double r, double s, double q, double h, double d, double c,
                                         const TumourContrast& model);

/// The share 1 - eps' of the layer left under a press at nominal strain eps, as the contrast
/// model sees it: eps' = tanh(2 eps) / 2, about eps up to a fifth of the layer and never more
/// than a half (C-infinity in the press, so the force stays smooth however deep it goes).
double compressed_share(double strain);

struct ForceOptions {
  bool shear = true;          ///< the four shear springs of section 3.4
  double shear_delta = 0.1;   ///< their offset in parameter space (docs/model.md: why 0.1)
  double max_force = 30.0;    ///< N: |F| is capped here (devices cap lower, per device)
  /// N/m: the rigid support under a body with "support": "bottom" (chest wall, pelvis,
  /// table), met once a press reaches the bottom contour. Stiff against tissue (100-300
  /// N/m in the bundled cases) yet below what desktop devices render stably (1-3 N/mm):
  /// docs/model.md, "Bodies on a support".
  double support_stiffness = 2000.0;
  /// b of the body's strain stiffening (calibrated law only; the scene sets it per body).
  double stiffening = 0.0;
  TumourFeel tumour{};
  TumourContrast contrast{};
  /// A rounded finger instead of the pad (case "indenter": "finger", calibrated law only):
  /// the scene sets it per probe with the tissue's modulus at the contact; the normal force
  /// is then finger_force, and a tumour in Pa adds its contrast to that.
  struct Finger {
    bool on = false;
    double modulus = 0.0;   ///< Pa
    double poisson = 0.49;
    FingerLaw law{};
  } finger{};
};

struct Force {
  Vec3 total = Vec3::Zero();   ///< N, acting on the probe; capped at max_force
  Vec3 normal = Vec3::Zero();  ///< the normal spring
  Vec3 shear = Vec3::Zero();   ///< the four shear springs
  Vec3 tumour = Vec3::Zero();  ///< the tumours' springs
  Vec3 support = Vec3::Zero(); ///< the rigid support's wall (bodies on a support only)
};

/// The force on a probe at q in contact (zero when !contact.inside). `tumours` are the
/// body's own. For a body on a support pass the contact through top_side_contact first:
/// the tissue is then compressed at most to its thickness 2R, any deeper press meets the
/// support's wall spring, and no component of the force points into the support (along
/// -N). Allocation-free.
Force contact_force(const mat::MatBody& body, const Contact& contact, const Vec3& q,
                    std::span<const mat::Tumour> tumours, const ForceOptions& options = {});

/// The magnitude (N) a tumour adds along `outward` when the probe indents the column
/// through foot point `foot` (surface at `radius` along `outward`) by `depth` (docs/model.md).
double tumour_spring(const mat::Tumour& tumour, const Vec3& foot, const Vec3& outward, double radius, double depth,
                     const TumourFeel& feel);

}  // namespace palpa::contact
