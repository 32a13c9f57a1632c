// The tumour spring (paper section 3.4, docs/model.md): what a press feels of a tumour
// under the surface. Truths: values computed by hand, the formula written out here (and its
// invariance under rigid motions), the stiffness a light and a deep press feel on a flat
// body in closed form, a C1 onset, and the sum over a body's tumours along outward.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <span>
#include <vector>

#include "contact_test_support.hpp"

namespace palpa::contact {
namespace {

using namespace contact_test;

double smoothstep_down(double x) { return 1.0 - 3.0 * x * x + 2.0 * x * x * x; }

double expected_tumour(const mat::Tumour& t, const Vec3& p, const Vec3& n, double radius, double depth,
                       const TumourFeel& feel) {
  const Vec3 c(t.center[0], t.center[1], t.center[2]);
  const double tc = (c - p).dot(n);
  const double rho = ((c - p) - tc * n).norm();
  const double s = radius - tc - t.radius;
  double w = 0.0;
  if (rho <= t.radius)
    w = 1.0;
  else if (rho < t.radius + feel.pad_radius)
    w = smoothstep_down((rho - t.radius) / feel.pad_radius);
  const double e = depth - feel.reach * s;
  double h = 0.0;
  if (e >= feel.ramp)
    h = e - 0.5 * feel.ramp;
  else if (e > 0.0)
    h = e * e / (2.0 * feel.ramp);
  return w * t.stiffness * h;
}

// ======================================================================================
// Tumours.

TEST(Tumour, SpringMatchesHandComputedValues) {
  // Foot at the origin, outward +z, surface 20 mm above the foot point, tumour of radius
  // 3 mm centred 3 mm above the foot point and 6 mm to the side, k_t = 1000 N/m, default
  // feel (reach 0.7, ramp 1 mm, pad 7.5 mm):
  //   t_c = 0.003, rho = 0.006, s = 0.020 - 0.003 - 0.003 = 0.014, reach * s = 0.0098
  //   x = (0.006 - 0.003) / 0.0075 = 0.4, w = 1 - 3 (0.16) + 2 (0.064) = 0.648
  const mat::Tumour t{"b", {0.006, 0.0, 0.003}, 0.003, 1000.0};
  const TumourFeel feel;
  const Vec3 foot = Vec3::Zero();
  const Vec3 z = Vec3::UnitZ();
  // depth 12 mm: e = 0.0022 >= ramp, h = 0.0022 - 0.0005 = 0.0017, F = 0.648 * 1000 * 0.0017
  EXPECT_NEAR(tumour_spring(t, foot, z, 0.02, 0.012, feel), 1.1016, 1e-12);
  // depth 10.3 mm: e = 0.0005 in the ramp, h = 0.0005^2 / 0.002 = 1.25e-4, F = 0.081
  EXPECT_NEAR(tumour_spring(t, foot, z, 0.02, 0.0103, feel), 0.081, 1e-12);
  // depth 9.8 mm: e = 0 (onset): nothing yet; 5 mm: nothing.
  EXPECT_NEAR(tumour_spring(t, foot, z, 0.02, 0.0098, feel), 0.0, 1e-15);
  EXPECT_EQ(tumour_spring(t, foot, z, 0.02, 0.005, feel), 0.0);
  // Directly over the tumour (rho = 2 mm <= a): w = 1, F = 1000 * 0.0017 = 1.7.
  const mat::Tumour over{"b", {0.002, 0.0, 0.003}, 0.003, 1000.0};
  EXPECT_NEAR(tumour_spring(over, foot, z, 0.02, 0.012, feel), 1.7, 1e-12);
  // Beside it beyond a + pad (rho = 11 mm > 10.5 mm): nothing.
  const mat::Tumour beside{"b", {0.011, 0.0, 0.003}, 0.003, 1000.0};
  EXPECT_EQ(tumour_spring(beside, foot, z, 0.02, 0.015, feel), 0.0);
  // Below the foot point along outward (t_c = -0.004): s = 0.02 + 0.004 - 0.003 = 0.021,
  // reach s = 0.0147, depth 0.018: e = 0.0033, h = 0.0028, w = 1: F = 2.8.
  const mat::Tumour under{"b", {0.0, 0.001, -0.004}, 0.003, 1000.0};
  EXPECT_NEAR(tumour_spring(under, foot, z, 0.02, 0.018, feel), 2.8, 1e-12);
  // Another feel: reach 0.5, ramp 2 mm, pad 5 mm, the first tumour: x = 0.6,
  // w = 1 - 1.08 + 0.432 = 0.352; reach s = 0.007, depth 0.008: e = 0.001 in the ramp,
  // h = 1e-6 / 0.004 = 2.5e-4, F = 0.352 * 1000 * 2.5e-4 = 0.088.
  const TumourFeel other{0.5, 2e-3, 5e-3};
  EXPECT_NEAR(tumour_spring(t, foot, z, 0.02, 0.008, other), 0.088, 1e-12);
}

TEST(Tumour, SpringIsInvariantUnderRigidMotionsAndMatchesTheFormula) {
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const TumourFeel feel;
  for (int n = 0; n < 500; ++n) {
    // In the frame of the foot point (outward +z): a tumour somewhere under the surface.
    const double radius = 0.005 + 0.02 * unit(rng);
    const double a = 0.001 + 0.006 * unit(rng);
    const Vec3 c_local(0.015 * (2 * unit(rng) - 1), 0.015 * (2 * unit(rng) - 1), radius * (2 * unit(rng) - 1));
    const double depth = radius * unit(rng);
    const mat::Tumour local{"b", {c_local.x(), c_local.y(), c_local.z()}, a, 500.0 + 3000.0 * unit(rng)};
    const double want = expected_tumour(local, Vec3::Zero(), Vec3::UnitZ(), radius, depth, feel);
    EXPECT_NEAR(tumour_spring(local, Vec3::Zero(), Vec3::UnitZ(), radius, depth, feel), want, 1e-12);
    // The same configuration rotated and moved.
    const Eigen::Quaterniond rot = Eigen::Quaterniond(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized();
    const Vec3 shift(0.1 * gauss(rng), 0.1 * gauss(rng), 0.1 * gauss(rng));
    const Vec3 c = rot * c_local + shift;
    const mat::Tumour moved{"b", {c.x(), c.y(), c.z()}, a, local.stiffness};
    EXPECT_NEAR(tumour_spring(moved, shift, rot * Vec3::UnitZ(), radius, depth, feel), want, 1e-9 * (1 + want));
  }
}

// Flat body, press at (x, y) = (2, -1) mm over a tumour of radius 4 mm centred 2 mm above
// the skeleton (its top 14 mm under a 20 mm surface): reach * s = 9.8 mm.
struct PressSetup {
  double x = 0.002;
  double y = -0.001;
  mat::Tumour tumour{"flat", {0.0, 0.0, 0.002}, 0.004, 1500.0};
  double radius() const { return flat_radius(x, y); }
  double onset(const TumourFeel& feel = {}) const {
    const double s = radius() - tumour.center[2] - tumour.radius;
    return feel.reach * s;
  }
};

// The outward force (+z) at indentation t, with and without the tumour.
double press_force(const PressSetup& s, double t, bool with_tumour) {
  static const FootPointSearch search(flat().skeleton());
  const Vec3 q(s.x, s.y, s.radius() - t);
  const std::vector<mat::Tumour> tumours{s.tumour};
  const Probe p = probe(flat(), search, q, with_tumour ? std::span<const mat::Tumour>(tumours)
                                                       : std::span<const mat::Tumour>());
  EXPECT_NEAR(p.contact.depth, t, 1e-12);
  return p.force.total.z();
}

double press_stiffness(const PressSetup& s, double t, bool with_tumour, double h = 1e-6) {
  return (press_force(s, t + h, with_tumour) - press_force(s, t - h, with_tumour)) / (2 * h);
}

TEST(Tumour, LightPressFeelsOnlyTissueDeepPressFeelsTheTumour) {
  const PressSetup s;
  const double k_t = s.tumour.stiffness;
  // Light: 20 % of the local thickness, far above the onset.
  const double light = 0.2 * s.radius();
  ASSERT_LT(light, s.onset());
  const double f_light = press_force(s, light, false);
  EXPECT_NEAR(press_force(s, light, true), f_light, 1e-12 * f_light);
  const double k_light = press_stiffness(s, light, false);
  EXPECT_GT(k_light, kFlatK);  // the normal spring plus the shear springs
  EXPECT_NEAR(press_stiffness(s, light, true), k_light, 1e-9 * k_light);
  // Deep: 60 %, past the onset and its ramp: the tumour's spring adds its full k_t (w = 1
  // directly over it, and h' = 1 past the ramp).
  const double deep = 0.6 * s.radius();
  ASSERT_GT(deep, s.onset() + TumourFeel{}.ramp);
  const double k_tissue = press_stiffness(s, deep, false);
  const double k_deep = press_stiffness(s, deep, true);
  EXPECT_GE(k_deep, k_tissue + 0.5 * k_t);
  EXPECT_NEAR(k_deep - k_tissue, k_t, 1e-5 * k_t);
}

TEST(Tumour, OnsetIsC1) {
  const PressSetup s;
  const double k_t = s.tumour.stiffness;
  const double ramp = TumourFeel{}.ramp;
  const double d0 = s.onset();
  // Continuous: across the onset the force changes by no more than the tissue's slope.
  for (double eta : {1e-6, 1e-8}) {
    const double jump = press_force(s, d0 + eta, true) - press_force(s, d0 - eta, true);
    const double tissue = press_force(s, d0 + eta, false) - press_force(s, d0 - eta, false);
    EXPECT_NEAR(jump, tissue, k_t * eta * eta / ramp + 1e-12) << "eta " << eta;
  }
  // The tumour's own stiffness rises from 0 as k_t e / ramp: no step in dF/d(depth).
  const double delta = 1e-6;
  const double below = press_stiffness(s, d0 - delta, true, delta / 4) - press_stiffness(s, d0 - delta, false, delta / 4);
  const double above = press_stiffness(s, d0 + delta, true, delta / 4) - press_stiffness(s, d0 + delta, false, delta / 4);
  EXPECT_NEAR(below, 0.0, 1e-6 * k_t);
  EXPECT_NEAR(above, k_t * delta / ramp, 1e-3 * k_t * delta / ramp + 1e-6 * k_t);
  EXPECT_LE(std::abs(above - below), 2.0 * k_t * delta / ramp);
  // Mid-ramp and the end of the ramp in closed form (w = 1): h = e^2 / (2 ramp).
  for (double e : {0.25 * ramp, 0.5 * ramp, ramp, 2.0 * ramp}) {
    const double h = e < ramp ? e * e / (2 * ramp) : e - 0.5 * ramp;
    const double t = d0 + e;
    EXPECT_NEAR(press_force(s, t, true) - press_force(s, t, false), k_t * h, 1e-9) << "e " << e;
  }
}

TEST(Tumour, ForceIsAlongOutwardAndSumsOverTheBodysTumours) {
  const MatBody& body = saddle();
  const FootPointSearch search(body.skeleton());
  const TumourFeel feel;
  // Two tumours under the middle of the saddle, one beside the other.
  const Vec3 p_mid = sk_point(body.skeleton(), 0.5, 0.5);
  const std::vector<mat::Tumour> tumours{
      {"saddle", {p_mid.x(), p_mid.y(), p_mid.z() + 0.002}, 0.004, 1500.0},
      {"saddle", {p_mid.x() + 0.008, p_mid.y() - 0.003, p_mid.z()}, 0.003, 2500.0},
  };
  std::mt19937_64 rng(16);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int felt = 0;
  for (int n = 0; n < 300; ++n) {
    const double u = 0.35 + 0.3 * unit(rng);
    const double v = 0.35 + 0.3 * unit(rng);
    const Vec3 p = sk_point(body.skeleton(), u, v);
    const Vec3 nn = sk_normal(body.skeleton(), u, v);
    const double r = sk_at(body.skeleton(), u, v)[mat::kRadius];
    const Vec3 q = p + (2.0 * unit(rng) - 1.0) * r * nn;
    ForceOptions options;
    options.max_force = 1e9;
    const Probe pr = probe(body, search, q, tumours, options);
    if (!pr.contact.inside) continue;
    const Expected e = expected_contact(body, pr.foot.u, pr.foot.v, q);
    double magnitude = 0.0;
    for (const auto& t : tumours) {
      const double m = expected_tumour(t, e.p, e.outward, e.radius, e.depth, feel);
      EXPECT_NEAR(tumour_spring(t, e.p, e.outward, e.radius, e.depth, feel), m, 1e-9);
      magnitude += m;
    }
    if (magnitude > 0.0) ++felt;
    expect_vec_near(pr.force.tumour, magnitude * e.outward, 1e-9 * (1.0 + magnitude), "tumour force");
    // And the rest is unchanged by the tumours.
    const Probe plain = probe(body, search, q, {}, options);
    expect_vec_near(pr.force.normal, plain.force.normal, 1e-12, "normal");
    expect_vec_near(pr.force.shear, plain.force.shear, 1e-12, "shear");
  }
  EXPECT_GT(felt, 20);
}

}  // namespace
}  // namespace palpa::contact
