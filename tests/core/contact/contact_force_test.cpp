// The contact force (paper section 3.4): the normal spring and the four shear springs of
// the membrane, and the cap at max_force. Truths: k depth along z in closed form on a flat
// body, section 3.4's springs written out here on a curved body, symmetry at the flat
// body's centre, and physical properties: zero outside, strictly growing with the press,
// Lipschitz along a constant-depth path and without jumps at the knots.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "contact_test_support.hpp"

namespace palpa::contact {
namespace {

using namespace contact_test;

Vec3 contour_point(const BSplineSurface& contour, double u, double v) {
  std::array<double, 3> out{};
  contour.evaluate(u, v, out);
  return {out[0], out[1], out[2]};
}

// Section 3.4's four shear springs as the specification states them.
Vec3 expected_shear(const MatBody& body, double u, double v, const Vec3& q, const Expected& e, double delta) {
  const BSplineSurface& contour = e.side > 0 ? body.top() : body.bottom();
  const Vec3 m0 = e.p + e.radius * e.outward;
  const double du[4] = {-delta, delta, 0.0, 0.0};
  const double dv[4] = {0.0, 0.0, -delta, delta};
  Vec3 sum = Vec3::Zero();
  for (int i = 0; i < 4; ++i) {
    const double un = clamp01(u + du[i]);
    const double vn = clamp01(v + dv[i]);
    const Vec3 ni = contour_point(contour, un, vn);
    const double kn = std::max(0.0, sk_at(body.skeleton(), un, vn)[mat::kStiffness]);
    const double keq = 0.5 * (kn + e.stiffness);
    const double x = std::max(0.0, (q - ni).norm() - (m0 - ni).norm());
    const double len = (ni - q).norm();
    if (len > 0.0) sum += keq * x * (ni - q) / len;
  }
  return sum;
}

// ======================================================================================
// Force.

TEST(Force, FlatNormalForceIsStiffnessTimesDepthAlongZ) {
  const MatBody& body = flat();
  const FootPointSearch search(body.skeleton());
  ForceOptions options;
  options.shear = false;
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> xy(-0.049, 0.049);
  std::uniform_real_distribution<double> zz(-0.03, 0.03);
  int inside = 0;
  for (int n = 0; n < 300; ++n) {
    const Vec3 q(xy(rng), xy(rng), zz(rng));
    const Probe p = probe(body, search, q, {}, options);
    const double depth = flat_radius(q.x(), q.y()) - std::abs(q.z());
    if (depth < 1e-9) {
      if (depth < -1e-9) {
        EXPECT_EQ(p.force.total, Vec3::Zero()) << q.transpose();
      }
      continue;
    }
    ++inside;
    const Vec3 want = kFlatK * depth * Vec3(0, 0, q.z() > 0 ? 1.0 : -1.0);
    expect_vec_near(p.force.total, want, 1e-9 * want.norm() + 1e-12, "k depth z");
    expect_vec_near(p.force.normal, want, 1e-9 * want.norm() + 1e-12, "normal");
    EXPECT_EQ(p.force.shear, Vec3::Zero());
    EXPECT_EQ(p.force.tumour, Vec3::Zero());
  }
  EXPECT_GT(inside, 50);
}

TEST(Force, NormalAndShearMatchSection34OnACurvedBody) {
  const MatBody& body = saddle();
  const FootPointSearch search(body.skeleton());
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int shear_nonzero = 0;
  for (double delta : {0.05, 0.12}) {
    ForceOptions options;
    options.shear_delta = delta;
    options.max_force = 1e9;  // the uncapped springs
    for (int n = 0; n < 300; ++n) {
      // A point inside: over a random (u, v), between bottom and top.
      const double u = unit(rng);
      const double v = unit(rng);
      const Vec3 p = sk_point(body.skeleton(), u, v);
      const Vec3 nn = sk_normal(body.skeleton(), u, v);
      const double r = sk_at(body.skeleton(), u, v)[mat::kRadius];
      const Vec3 q = p + (2.0 * unit(rng) - 1.0) * r * nn;
      const Probe pr = probe(body, search, q, {}, options);
      if (!pr.contact.inside) continue;
      const Expected e = expected_contact(body, pr.foot.u, pr.foot.v, q);
      const Vec3 normal = e.stiffness * e.depth * e.outward;
      const Vec3 shear = expected_shear(body, pr.foot.u, pr.foot.v, q, e, delta);
      if (shear.norm() > 1e-6) ++shear_nonzero;
      const std::string where = "q (" + std::to_string(q.x()) + ", " + std::to_string(q.y()) + ", " +
                                std::to_string(q.z()) + ") delta " + std::to_string(delta);
      expect_vec_near(pr.force.normal, normal, 1e-9 * normal.norm() + 1e-12, where + " normal");
      expect_vec_near(pr.force.shear, shear, 1e-9 * shear.norm() + 1e-12, where + " shear");
      EXPECT_EQ(pr.force.tumour, Vec3::Zero());
      expect_vec_near(pr.force.total, normal + shear, 1e-9 * (normal + shear).norm() + 1e-12, where + " total");
    }
  }
  EXPECT_GT(shear_nonzero, 200);
}

TEST(Force, ShearVanishesAtTheSurfaceAndIsSymmetricAtTheCentreOfTheFlatBody) {
  const MatBody& body = flat();
  const FootPointSearch search(body.skeleton());
  // At depth 0 (the undeformed surface) no membrane spring is stretched.
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, {0.01, -0.02}, {-0.03, 0.025}}) {
    for (double sign : {1.0, -1.0}) {
      const Vec3 q(x, y, sign * flat_radius(x, y));
      const Probe p = probe(body, search, q);
      EXPECT_LE(p.force.shear.norm(), 1e-9) << x << "," << y;
      EXPECT_LE(p.force.total.norm(), 1e-9) << x << "," << y;
    }
  }
  // Over the centre the four springs balance sideways and pull outwards.
  const Vec3 q(0.0, 0.0, 0.01);
  const Probe p = probe(body, search, q);
  EXPECT_NEAR(p.force.shear.x(), 0.0, 1e-12);
  EXPECT_NEAR(p.force.shear.y(), 0.0, 1e-12);
  EXPECT_GT(p.force.shear.z(), 0.0);
}

// Pressing straight in along the outward direction from the surface (shear on): the
// depth is the indentation, the outward force grows strictly with it and is > 0; just
// outside it is exactly 0.
TEST(Force, PressingStraightInGrowsStrictlyAndPushesOut) {
  const MatBody& body = saddle();
  const FootPointSearch search(body.skeleton());
  ForceOptions options;
  options.max_force = 1e9;  // the springs themselves, not the cap
  for (const auto& [u, v] : {std::pair{0.5, 0.5}, {0.3, 0.6}, {0.7, 0.35}, {0.2, 0.2}, {0.8, 0.75}, {0.45, 0.9}}) {
    const Vec3 p = sk_point(body.skeleton(), u, v);
    const Vec3 n = sk_normal(body.skeleton(), u, v);
    const double r = sk_at(body.skeleton(), u, v)[mat::kRadius];
    for (double sign : {1.0, -1.0}) {
      const Vec3 out = sign * n;
      const std::string where = "(" + std::to_string(u) + ", " + std::to_string(v) + ") side " + std::to_string(sign);
      // Just outside: exactly zero.
      const Vec3 q_out = p + (r + 1e-7) * out;
      const Probe po = probe(body, search, q_out, {}, options);
      EXPECT_FALSE(po.contact.inside) << where;
      EXPECT_EQ(po.force.total, Vec3::Zero()) << where;
      EXPECT_EQ(po.force.normal, Vec3::Zero()) << where;
      EXPECT_EQ(po.force.shear, Vec3::Zero()) << where;
      double previous = 0.0;
      for (int i = 1; i <= 38; ++i) {
        const double t = r * i / 40.0;
        const Vec3 q = p + (r - t) * out;
        const Probe pr = probe(body, search, q, {}, options);
        EXPECT_NEAR(pr.foot.u, u, 1e-8) << where << " t " << t;
        EXPECT_NEAR(pr.foot.v, v, 1e-8) << where << " t " << t;
        EXPECT_NEAR(pr.contact.depth, t, 1e-9) << where;
        expect_vec_near(pr.contact.outward, out, 1e-7, where + " outward");  // zero-cosine test
        const double along = pr.force.total.dot(out);
        EXPECT_GT(along, 0.0) << where << " t " << t;
        EXPECT_GT(along, previous) << where << " t " << t;
        previous = along;
      }
    }
  }
}

// Along a smooth path at constant depth that crosses several knot spans, the force is
// Lipschitz with L = 20 x (k_max + 4 k_max) (normal spring plus the four shear springs)
// and does not jump at the knots.
TEST(Force, IsLipschitzAlongAConstantDepthPathAndDoesNotJumpAtKnots) {
  const MatBody& body = saddle();
  const FootPointSearch search(body.skeleton());
  const double lipschitz = 20.0 * (kSaddleKMax + 4.0 * kSaddleKMax);
  const double depth = 0.004;
  // u from 0.2 to 0.8 and v from 0.3 to 0.7 along a straight line in parameter space.
  const auto at = [&](double s) {
    const double u = 0.2 + 0.6 * s;
    const double v = 0.3 + 0.4 * s;
    const Vec3 p = sk_point(body.skeleton(), u, v);
    const Vec3 n = sk_normal(body.skeleton(), u, v);
    const double r = sk_at(body.skeleton(), u, v)[mat::kRadius];
    return Vec3(p + (r - depth) * n);
  };
  Vec3 q_prev = at(0.0);
  Vec3 f_prev = probe(body, search, q_prev).force.total;
  ASSERT_GT(f_prev.norm(), 0.0);
  double worst_ratio = 0.0;
  const int steps = 2000 * kLoopScale;
  for (int i = 1; i <= steps; ++i) {
    const Vec3 q = at(i / double(steps));
    const Probe p = probe(body, search, q);
    ASSERT_TRUE(p.contact.inside);
    EXPECT_NEAR(p.contact.depth, depth, 1e-8);
    const double ratio = (p.force.total - f_prev).norm() / (q - q_prev).norm();
    worst_ratio = std::max(worst_ratio, ratio);
    q_prev = q;
    f_prev = p.force.total;
  }
  EXPECT_LE(worst_ratio, lipschitz);
  RecordProperty("worst_force_ratio_N_per_m", std::to_string(worst_ratio));
  // At each interior knot crossed (in u or v), the force on either side within 1e-10 in
  // parameter space.
  std::vector<double> crossings;
  for (double k : body.skeleton().knots_u())
    if (k > 0.2 && k < 0.8) crossings.push_back((k - 0.2) / 0.6);
  for (double k : body.skeleton().knots_v())
    if (k > 0.3 && k < 0.7) crossings.push_back((k - 0.3) / 0.4);
  ASSERT_GE(crossings.size(), 4u);
  for (double s : crossings) {
    const Vec3 qa = at(s - 1e-10);
    const Vec3 qb = at(s + 1e-10);
    const Vec3 fa = probe(body, search, qa).force.total;
    const Vec3 fb = probe(body, search, qb).force.total;
    EXPECT_LE((fb - fa).norm(), lipschitz * (qb - qa).norm() + 1e-9) << "knot crossing at s = " << s;
  }
}

TEST(Force, TotalIsTheSumScaledDownToMaxForce) {
  // Stiff tissue (k ~ 3e4 N/m next to positions ~1e-2 m) so that the cap is reached.
  const MatBody body = MatBody::fit(saddle_grid(11, 100.0));
  const FootPointSearch search(body.skeleton());
  const mat::Tumour tumour{"saddle", {0.0, 0.0, 0.005}, 0.004, 2e5};
  const std::vector<mat::Tumour> tumours{tumour};
  std::mt19937_64 rng(14);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int capped = 0;
  int uncapped = 0;
  for (double cap : {30.0, 3.3}) {
    ForceOptions options;
    options.max_force = cap;
    for (int n = 0; n < 300; ++n) {
      const double u = 0.1 + 0.8 * unit(rng);
      const double v = 0.1 + 0.8 * unit(rng);
      const Vec3 p = sk_point(body.skeleton(), u, v);
      const Vec3 nn = sk_normal(body.skeleton(), u, v);
      const double r = sk_at(body.skeleton(), u, v)[mat::kRadius];
      const Vec3 q = p + (1.0 - 0.01 * std::pow(100.0, unit(rng))) * r * nn;  // depths from 1% of r to r
      const Probe pr = probe(body, search, q, tumours, options);
      if (!pr.contact.inside) continue;
      const Vec3 sum = pr.force.normal + pr.force.shear + pr.force.tumour;
      const Vec3 want = sum.norm() > cap ? Vec3(sum * (cap / sum.norm())) : sum;
      (sum.norm() > cap ? capped : uncapped)++;
      expect_vec_near(pr.force.total, want, 1e-12 * cap, "capped sum");
      EXPECT_LE(pr.force.total.norm(), cap * (1.0 + 1e-12));
    }
  }
  EXPECT_GT(capped, 50);
  EXPECT_GT(uncapped, 10);
}

}  // namespace
}  // namespace palpa::contact
