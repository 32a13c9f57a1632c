// Penetration (paper section 3.1): a probe's depth, inside/outside, side and outward
// direction from its foot point. Truths: closed forms on a flat skeleton (depth = R - |z|),
// the radius and normal at a probe placed exactly on the skeleton, and the specification's
// formulas evaluated here from the splines on a curved body.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <utility>

#include "contact_test_support.hpp"

namespace palpa::contact {
namespace {

using namespace contact_test;

// ======================================================================================
// Contact on the flat skeleton, in closed form.

TEST(Contact, FlatDepthIsRadiusMinusHeight) {
  const MatBody& body = flat();
  const FootPointSearch search(body.skeleton());
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> xy(-0.049, 0.049);
  std::uniform_real_distribution<double> zz(-0.03, 0.03);
  for (int n = 0; n < 300; ++n) {
    const Vec3 q(xy(rng), xy(rng), zz(rng));
    const Contact c = make_contact(body, search.closest(body.skeleton(), q), q);
    const double r = flat_radius(q.x(), q.y());
    const double sign = q.z() > 0 ? 1.0 : -1.0;
    EXPECT_NEAR(c.depth, r - std::abs(q.z()), 1e-9) << q.transpose();
    EXPECT_EQ(c.inside, c.depth >= 0.0);
    EXPECT_NEAR(c.radius, r, 1e-12);
    EXPECT_NEAR(c.stiffness, kFlatK, 1e-9);
    EXPECT_EQ(c.side, q.z() > 0 ? 1 : -1);
    expect_vec_near(c.outward, Vec3(0, 0, sign), 1e-9, "outward");
  }
}

TEST(Contact, FlatInsideOutsideIsNeverWrongFartherThanOneNanometreFromTheSurface) {
  const MatBody& body = flat();
  const FootPointSearch search(body.skeleton());
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> xy(-0.045, 0.045);
  for (int n = 0; n < 200; ++n) {
    const double x = xy(rng);
    const double y = xy(rng);
    const double r = flat_radius(x, y);
    for (double sign : {1.0, -1.0}) {
      const Vec3 in(x, y, sign * (r - 1e-9));
      const Vec3 out(x, y, sign * (r + 1e-9));
      const Contact ci = make_contact(body, search.closest(body.skeleton(), in), in);
      const Contact co = make_contact(body, search.closest(body.skeleton(), out), out);
      EXPECT_TRUE(ci.inside) << in.transpose() << " depth " << ci.depth;
      EXPECT_FALSE(co.inside) << out.transpose() << " depth " << co.depth;
      EXPECT_GE(ci.depth, 0.0);
      EXPECT_LT(co.depth, 0.0);
      EXPECT_EQ(contact_force(body, co, out, {}).total, Vec3::Zero());
    }
  }
}

TEST(Contact, ProbeExactlyOnTheSkeletonIsInsideByTheRadiusAndPushedAlongPlusN) {
  ForceOptions no_shear;
  no_shear.shear = false;
  for (const MatBody* body : {&flat(), &cylinder(), &saddle()}) {
    const FootPointSearch search(body->skeleton());
    for (const auto& [u0, v0] : {std::pair{0.5, 0.5}, {0.3, 0.7}, {0.61, 0.25}, {0.9, 0.12}}) {
      const Vec3 q = sk_point(body->skeleton(), u0, v0);  // on the skeleton, to round-off
      const Vec3 n = sk_normal(body->skeleton(), u0, v0);
      const double r = sk_at(body->skeleton(), u0, v0)[mat::kRadius];
      const double k = sk_at(body->skeleton(), u0, v0)[mat::kStiffness];
      const std::string where = body->id() + " at " + std::to_string(u0) + "," + std::to_string(v0);
      const FootPoint f = search.closest(body->skeleton(), q);
      EXPECT_LE(f.distance, 1e-15) << where;
      EXPECT_NEAR(f.u, u0, 1e-9) << where;
      EXPECT_NEAR(f.v, v0, 1e-9) << where;
      const Contact c = make_contact(*body, f, q);
      EXPECT_TRUE(c.inside) << where;
      EXPECT_NEAR(c.depth, r, 1e-13) << where;
      EXPECT_EQ(c.side, 1) << where;
      expect_vec_near(c.outward, n, 1e-9, where + ": outward on the skeleton is +N");
      const Force plain = contact_force(*body, c, q, {}, no_shear);
      expect_vec_near(plain.total, k * r * n, 1e-9 * k * r, where + ": k R N");
      const Force full = contact_force(*body, c, q, {});
      EXPECT_TRUE(finite(full.total)) << where;
      EXPECT_GT(full.total.dot(n), 0.0) << where;
    }
    // On the boundary of the skeleton the radius is 0: depth 0, no force.
    const Vec3 edge = sk_point(body->skeleton(), 0.0, 0.4);
    const Contact ce = make_contact(*body, search.closest(body->skeleton(), edge), edge);
    EXPECT_NEAR(ce.depth, 0.0, 1e-12) << body->id();
    const Force fe = contact_force(*body, ce, edge, {});
    EXPECT_TRUE(finite(fe.total)) << body->id();
    EXPECT_LE(fe.total.norm(), 1e-9) << body->id();
  }
}

// make_contact against the specification's formulas at the implementation's foot point
// (whose correctness the FootPoint tests establish), on a curved body.
TEST(Contact, MatchesTheSpecificationOnACurvedBody) {
  const MatBody& body = saddle();
  const FootPointSearch search(body.skeleton());
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> box(-0.06, 0.06);
  for (int n = 0; n < 300; ++n) {
    const Vec3 q(box(rng), box(rng), 0.5 * box(rng));
    const FootPoint f = search.closest(body.skeleton(), q);
    const Contact c = make_contact(body, f, q);
    const Expected e = expected_contact(body, f.u, f.v, q);
    EXPECT_NEAR(c.depth, e.depth, 1e-12);
    EXPECT_EQ(c.inside, e.depth >= 0.0);
    EXPECT_NEAR(c.radius, e.radius, 1e-12);
    EXPECT_NEAR(c.stiffness, e.stiffness, 1e-9);
    EXPECT_EQ(c.side, e.side) << q.transpose();
    expect_vec_near(c.outward, e.outward, 1e-9, "outward");
    EXPECT_EQ(c.foot.u, f.u);
    EXPECT_EQ(c.foot.v, f.v);
  }
}

}  // namespace
}  // namespace palpa::contact
