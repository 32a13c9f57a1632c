// Stability of DeformedBody: energy never grows after release across extreme stiffness,
// mass, damping and time steps; degenerate presses (on the skeleton, at the rim, at zero
// depth) stay finite; and review findings kept as regression tests (a soft site among stiff
// ones, a reduced window while sliding, an outside contact, jittery time steps). Truths are
// physical properties: energy, finiteness, rest and sleep.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "deform_test_support.hpp"

namespace palpa::deform {
namespace {

using namespace deform_test;

// Stress case 10 on whole bodies: extreme stiffness, mass and damping channels and any
// time step; energy never grows after release, nothing becomes NaN, a sleeping body is at
// rest.
TEST(DeformedBody, EnergyNeverGrowsAfterReleaseAcrossExtremeMaterials) {
  const int steps = long_tests() ? 400 : 30;
  for (double k : kGridK)
    for (double m : kGridM)
      for (double b : kGridB) {
        mat::BodyGrid g = test::flat_body(7, 7, kHalf, kR0, k);
        g.damping.assign(g.medial.size(), b);
        g.mass.assign(g.medial.size(), m);
        const MatBody rest = MatBody::fit(g);
        for (double dt : kGridDt) {
          for (const Scheme scheme : {Scheme::SkeletonMoves, Scheme::Compression}) {
            DeformOptions options;
            options.scheme = scheme;
            DeformedBody body(rest, options);
            const Vec3 q = probe_over(rest, 0.45, 0.53, 0.3 * eval_radius(rest.skeleton(), 0.45, 0.53), 1);
            const contact::Contact c = contact_on_rest(rest, q);
            body.press(c, q);
            ASSERT_LT((eval3(body.top(), c.foot.u, c.foot.v) - q).norm(), 1e-9) << params(k, b, m, dt);
            body.release();
            double e_prev = body.energy();
            const double e0 = e_prev;
            ASSERT_TRUE(std::isfinite(e0)) << params(k, b, m, dt);
            ASSERT_GT(e0, 0.0) << params(k, b, m, dt);
            for (int n = 1; n <= steps; ++n) {
              body.step(dt);
              const double e = body.energy();
              ASSERT_TRUE(std::isfinite(e) && all_finite(body)) << params(k, b, m, dt) << " step " << n;
              ASSERT_GE(e, 0.0);
              ASSERT_LE(e, e_prev * (1 + 1e-12) + e0 * 1e-200)
                  << params(k, b, m, dt) << " scheme " << static_cast<int>(scheme) << " step " << n;
              if (!body.awake()) {
                ASSERT_TRUE(at_rest(body)) << params(k, b, m, dt);
                ASSERT_EQ(e, 0.0);
              }
              e_prev = e;
            }
          }
        }
      }
}

// Degenerate presses stay finite: the probe exactly on the skeleton (outward = N, depth =
// R), near the rim where R -> 0, and at zero depth (nothing to move).
TEST(DeformedBody, DegeneratePressesStayFinite) {
  for (const Scheme scheme : {Scheme::SkeletonMoves, Scheme::Compression}) {
    DeformOptions options;
    options.scheme = scheme;
    {
      DeformedBody body(flat(), options);
      const Vec3 q = eval3(flat().skeleton(), 0.5, 0.5);
      const contact::Contact c = contact_on_rest(flat(), q);
      body.press(c, q);
      EXPECT_TRUE(all_finite(body));
      EXPECT_LT((eval3(near_surface(body, c.side), c.foot.u, c.foot.v) - q).norm(), 1e-9);
    }
    {
      DeformedBody body(flat(), options);
      const Vec3 q(0.049, 0.0, 0.5 * flat_radius(0.049, 0.0));
      const contact::Contact c = contact_on_rest(flat(), q);
      ASSERT_TRUE(c.inside);
      body.press(c, q);
      EXPECT_TRUE(all_finite(body));
      EXPECT_LT((eval3(near_surface(body, c.side), c.foot.u, c.foot.v) - q).norm(), 1e-9);
      body.release();
      for (int n = 0; n < 100; ++n) body.step(1e-2);
      EXPECT_TRUE(all_finite(body));
    }
    {
      DeformedBody body(flat(), options);
      const Vec3 q = probe_over(flat(), 0.5, 0.5, 0.0, 1);
      const contact::Contact c = contact_on_rest(flat(), q);
      body.press(c, q);
      EXPECT_TRUE(all_finite(body));
      EXPECT_LT(body.max_displacement(), 1e-12);
    }
  }
}

// Review findings, kept as regression tests.

TEST(DeformedBodyReview, ASoftSiteAmongStiffOnesStillSpringsBackAndSleeps) {
  // One 150 N/m site in a 300 N/m field: the control points' own stiffness coefficients
  // overshoot to about -149 N/m; the springs must not take them (a dent that never heals).
  auto g = test::flat_body(7, 7, 0.05, 0.02, 300.0);
  g.stiffness[3 * 7 + 3] = 150.0;
  const auto rest = mat::MatBody::fit(g);
  DeformedBody body(rest);
  const contact::FootPointSearch search(rest.skeleton());
  const palpa::Vec3 q(0.0, 0.0, 0.006);
  body.press(contact::make_contact(rest, search.closest(rest.skeleton(), q), q), q);
  EXPECT_GT(body.max_displacement(), 0.005);
  body.release();
  int steps = 0;
  while (body.awake() && steps < 20000) {
    body.step(1e-3);
    ++steps;
  }
  EXPECT_FALSE(body.awake()) << "still displaced by " << body.max_displacement() << " m after 20 s";
  EXPECT_EQ(body.max_displacement(), 0.0);
}

TEST(DeformedBodyReview, AReducedWindowStaysOnTheProbeWhileSteppingAndSliding) {
  const auto rest = mat::MatBody::fit(test::flat_body(9, 9));
  const contact::FootPointSearch search(rest.skeleton());
  for (int window : {1, 2, 3, 0}) {
    DeformOptions o;
    o.influence_u = window;
    o.influence_v = window;
    DeformedBody body(rest, o);
    double worst = 0.0;
    for (int k = 0; k < 300; ++k) {
      const double t = 1e-3 * k;
      const palpa::Vec3 q(0.02 * std::sin(5 * t), 0.01 * std::cos(3 * t), 0.012);
      const auto c = contact::make_contact(rest, search.closest(rest.skeleton(), q), q);
      ASSERT_TRUE(c.inside);
      body.press(c, q);
      body.step(1e-3);
      std::array<double, 3> p{};
      body.top().evaluate(c.foot.u, c.foot.v, p);
      worst = std::max(worst, (palpa::Vec3(p[0], p[1], p[2]) - q).norm());
    }
    EXPECT_LT(worst, 1e-9) << "window " << window;
  }
}

TEST(DeformedBodyReview, PressingWithAnOutsideContactReleases) {
  const auto rest = mat::MatBody::fit(test::flat_body(7, 7));
  const contact::FootPointSearch search(rest.skeleton());
  DeformedBody body(rest);
  const palpa::Vec3 far(0.0, 0.0, 0.07);  // 5 cm above the body
  const auto c = contact::make_contact(rest, search.closest(rest.skeleton(), far), far);
  ASSERT_FALSE(c.inside);
  body.press(c, far);
  EXPECT_EQ(body.max_displacement(), 0.0);
}

TEST(DeformedBodyReview, JitteryTimeStepsStayStableAndSettle) {
  const auto rest = mat::MatBody::fit(test::flat_body(7, 7));
  const contact::FootPointSearch search(rest.skeleton());
  DeformedBody body(rest);
  const palpa::Vec3 q(0.0, 0.0, 0.01);
  body.press(contact::make_contact(rest, search.closest(rest.skeleton(), q), q), q);
  body.release();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(0.999e-3, 1.001e-3);
  double energy = body.energy();
  for (int k = 0; k < 5000 && body.awake(); ++k) {
    body.step(jitter(rng));
    EXPECT_LE(body.energy(), energy * (1 + 1e-12) + 1e-300);
    energy = body.energy();
  }
  EXPECT_FALSE(body.awake());
}

}  // namespace
}  // namespace palpa::deform
