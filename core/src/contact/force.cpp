#include "palpa/contact/force.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include "../common/numeric.hpp"
#include "palpa/vec3.hpp"

namespace palpa::contact {
namespace {



// Section 3.4's shear springs (docs/model.md): each ties the probe to the contour point
// delta away in parameter space; its rest length is the distance from the undeformed
// surface point over the foot point, so it is slack at depth 0, and it carries tension
// only (a membrane cannot push).
Vec3 shear_force(const mat::MatBody& body, const Contact& c, const Vec3& q, double delta) {
  const Vec3 rest = c.foot.point + c.radius * c.outward;
  const double u = c.foot.u;
  const double v = c.foot.v;
  const std::array<std::array<double, 2>, 4> at{{{clamp01(u - delta), v},
                                                 {clamp01(u + delta), v},
                                                 {u, clamp01(v - delta)},
                                                 {u, clamp01(v + delta)}}};
  const auto& contour = c.side > 0 ? body.top() : body.bottom();
  Vec3 total = Vec3::Zero();
  for (const auto& [un, vn] : at) {
    // One basis serves the contour and the skeleton: they share parameters and knots.
    const auto basis = body.skeleton().basis(un, vn);
    std::array<double, 3> p;
    contour.evaluate(basis, p, 0, 3);
    double k_neighbour = 0.0;
    body.skeleton().evaluate(basis, std::span<double>(&k_neighbour, 1), mat::kStiffness, 1);
    const Vec3 neighbour(p[0], p[1], p[2]);
    const Vec3 to = neighbour - q;
    const double len = to.norm();
    const double stretch = len - (neighbour - rest).norm();
    if (!(stretch > 0.0) || !(len > 0.0)) continue;
    const double k_eq = 0.5 * (std::max(0.0, k_neighbour) + c.stiffness);
    total += (k_eq * stretch / len) * to;
  }
  return total;
}

// Where a tumour is for the pad over a foot point: its centre's height above the foot along
// the way out, and the weight of its force by how far it lies beside the column (1 within
// its radius, falling C1 to 0 one pad radius beyond its rim).
struct TumourPlace {
  double height;
  double weight;
};

TumourPlace place_of(const mat::Tumour& tumour, const Vec3& foot, const Vec3& outward, double pad_radius) {
  const Vec3 to_center = to_vec3(tumour.center) - foot;
  const double height = to_center.dot(outward);
  const double lateral = (to_center - height * outward).norm();
  double weight = 1.0;
  if (lateral > tumour.radius) {
    const double x = (lateral - tumour.radius) / pad_radius;
    weight = x >= 1.0 ? 0.0 : 1.0 - x * x * (3.0 - 2.0 * x);
  }
  return {height, weight};
}

// max(x, floor) rounded over a band of half-width w about the floor: C1, and exact outside
// the band (a kink in the contrast would be a kink in the force a device renders).
double soft_floor(double x, double floor, double w) {
  if (x >= floor + w) return x;
  if (x <= floor - w) return floor;
  const double t = x - floor + w;
  return floor + t * t / (4.0 * w);
}

double soft_ceiling(double x, double ceiling, double w) { return -soft_floor(-x, -ceiling, w); }

// C1 onset: 0 below 0, a parabola across [0, width], then linear with slope 1.
double smooth_ramp(double e, double width) {
  if (e <= 0.0) return 0.0;
  if (e >= width) return e - 0.5 * width;
  return e * e / (2.0 * width);
}

}  // namespace

double tumour_spring(const mat::Tumour& tumour, const Vec3& foot, const Vec3& outward, double radius, double depth,
                     const TumourFeel& feel) {
  const auto [height, weight] = place_of(tumour, foot, outward, feel.pad_radius);
  if (weight <= 0.0) return 0.0;
  const double above = radius - height - tumour.radius;  // tissue between the surface and the tumour
  return weight * tumour.stiffness * smooth_ramp(depth - feel.reach * above, feel.ramp);
}

double stiffening_factor(double strain, double b) {
  const double x = b * strain;
  if (!(x > 1e-12)) return 1.0;
  return std::expm1(x) / x;  // the stress int_0^eps E exp(b e) de over E eps
}

double tumour_contrast(double r, double s, double q, double h, const TumourContrast& model) {
  if (!(q > 1.0) || !(h > 0.0) || !(r > 0.0)) return 0.0;
  const double a = model.pad_radius;
  // The fit's domain: at least 5 % of the layer between the inclusion and the skin or base,
  // reached smoothly (a band of 0.5 % of the layer) so that a deep press meets no kink.
  const double band = 0.005 * h;
  const double depth = soft_ceiling(std::max(s, 0.0), 0.95 * h, band);
  const double gap = soft_floor(s - r, 0.05 * h, band);
  const double along_axis = 1.0 + (depth / (model.depth_knee * a)) * (depth / (model.depth_knee * a));
  return model.a_scale * (q - 1.0) / (q + model.ratio_knee) * std::pow(r / a, model.size_power) *
         std::pow(along_axis, -model.depth_power) * std::pow((h - depth) / h, model.base_power) *
         std::pow(h / a, model.layer_power) * std::pow(gap / a, -model.gap_power);
}

double finger_tumour_contrast(double r, double s, double q, double h, double d, double R,
                              const TumourContrast& model) {
  return finger_tumour_contrast_at_contact(r, s, q, h, d, sphere_contact_radius(d, R), model);
}

double finger_tumour_contrast_at_contact(double r, double s, double q, double h, double d, double c,
                                         const TumourContrast& model) {
  const auto& f = model.finger;
  const double a = model.pad_radius;
  if (!(c > 0.0)) return 0.0;
  TumourContrast as_pad = model;
  as_pad.pad_radius = f.radius_scale * a * std::pow(c / a, f.radius_power);
  as_pad.layer_power = f.layer_power;
  const double thinned = f.shift * d;
  return f.scale * tumour_contrast(r, s - thinned, q, h - thinned, as_pad);
}

double compressed_share(double strain) { return 1.0 - 0.5 * std::tanh(2.0 * std::max(strain, 0.0)); }

double contrast_lateral_weight(double lateral, double r, double s, const TumourContrast& model) {
  const double half_width = model.pad_radius + model.lateral_spread * std::max(s, 0.0);
  const double plateau = std::max(r - half_width, 0.0);  // a tumour wider than the falloff: felt fully inside
  const double x = std::clamp((lateral - plateau) / (2.0 * half_width), 0.0, 1.0);
  return 1.0 - x * x * (3.0 - 2.0 * x);
}

namespace {

// A tumour given in Pa: the extra force along the way out is C - 1 times the normal
// spring's, so it grows with the press from 0 like the tissue's own (no onset to buzz on)
// and fades beside the pad's axis as the 3-D FEM's does.
// Under strain stiffening the ratio of tangent moduli at the press's nominal strain counts:
// q exp((b_t - b) eps). The geometry is the compressed layer's (TumourContrast::compressed).
double tumour_in_pa(const mat::Tumour& tumour, const Contact& contact, double normal, double strain,
                    double finger_contact_radius, const ForceOptions& options) {
  const Vec3 to_center = to_vec3(tumour.center) - contact.foot.point;
  const double height = to_center.dot(contact.outward);
  const double below_skin = contact.radius - height;  // the skin is R above the foot point
  const double lateral = (to_center - height * contact.outward).norm();
  const double weight = contrast_lateral_weight(lateral, tumour.radius, below_skin, options.contrast);
  if (weight <= 0.0) return 0.0;
  const double ratio = tumour.modulus_ratio * std::exp((tumour.stiffening - options.stiffening) * strain);
  const double thickness = 2.0 * contact.radius;
  if (options.finger.on) {
    return weight * normal *
           finger_tumour_contrast_at_contact(tumour.radius, below_skin, ratio, thickness, contact.depth,
                                             finger_contact_radius, options.contrast);
  }
  // The tissue over and under the tumour is thinner by the press: the contrast grows.
  const double left = options.contrast.compressed ? compressed_share(strain) : 1.0;
  return weight * normal *
         tumour_contrast(tumour.radius, left * below_skin, ratio, left * thickness, options.contrast);
}

}  // namespace

Force contact_force(const mat::MatBody& body, const Contact& contact, const Vec3& q,
                    std::span<const mat::Tumour> tumours, const ForceOptions& options) {
  Force f;
  if (!contact.inside) return f;
  // On a support the tissue compresses at most to its thickness; the rest is the wall.
  const bool anchored = body.anchored();
  const double tissue = contact.depth;  // at most 2R on a support (top_side_contact)
  const double thickness = 2.0 * contact.radius;
  const double strain = thickness > 0.0 ? std::clamp(tissue / thickness, 0.0, 1.0) : 0.0;
  // Sneddon's contact radius of the rounded finger: once per tick, for the tissue and every tumour.
  const double c = options.finger.on ? sphere_contact_radius(tissue, options.finger.law.radius) : 0.0;
  const double linear = options.finger.on ? finger_force_at_contact(options.finger.modulus, options.finger.poisson,
                                                                    tissue, thickness, c, options.finger.law)
                                          : contact.stiffness * tissue;
  const double normal = linear * stiffening_factor(strain, options.stiffening);
  f.normal = normal * contact.outward;
  if (options.shear) {
    // The shear springs stretch to the probe, or to the bottom contour under it once the
    // press is in the support (equal to q while the press is in the tissue).
    const Vec3 at = anchored ? Vec3(contact.foot.point + (contact.radius - tissue) * contact.outward) : q;
    f.shear = shear_force(body, contact, at, options.shear_delta);
  }
  double tumour = 0.0;
  for (const auto& t : tumours) {
    tumour += t.modulus_ratio > 0.0 ? tumour_in_pa(t, contact, normal, strain, c, options)
                                    : tumour_spring(t, contact.foot.point, contact.outward, contact.radius, tissue,
                                                    options.tumour);
  }
  f.tumour = tumour * contact.outward;
  if (anchored) f.support = options.support_stiffness * contact.support_depth * contact.outward;
  f.total = f.normal + f.shear + f.tumour + f.support;
  if (anchored) {
    // Nothing may push the finger into the support: drop a component along -N (a shear
    // spring to a lower neighbour on a steep flank can have one).
    const Vec3 n = contact.foot.su.cross(contact.foot.sv);
    const double nn = n.squaredNorm();
    const double into = nn > 0.0 ? f.total.dot(n) : 0.0;
    if (into < 0.0) f.total -= (into / nn) * n;
  }
  const double magnitude = f.total.norm();
  if (!std::isfinite(magnitude)) {
    f = Force{};  // never hand a device a NaN
  } else if (magnitude > options.max_force) {
    f.total *= options.max_force / magnitude;
  }
  return f;
}

}  // namespace palpa::contact
