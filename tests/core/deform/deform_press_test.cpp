// Pressing a DeformedBody (paper section 3.2) in each deformation scheme: (a) the skeleton
// moves, (b) compression with share g. Truths: the specification's moves of skeleton,
// radius and contours written out (the surface under the probe lands on it; g = 0.5 keeps
// the far contour still), the least-norm control-point changes from Cox-de Boor basis
// functions, partition-of-unity bounds and local support, and a probe pressing along a path.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

#include "deform_test_support.hpp"

namespace palpa::deform {
namespace {

using namespace deform_test;

TEST(DeformedBody, StartsAtRest) {
  const DeformedBody body(flat());
  EXPECT_TRUE(at_rest(body));
  EXPECT_EQ(body.max_displacement(), 0.0);
  EXPECT_EQ(body.energy(), 0.0);
  EXPECT_EQ(&body.rest(), &flat());
}

// Scheme (a): skeleton xyz and both contours move by D = -depth * outward at (u, v); the
// radius does not change; the surface under the probe lands on it.
TEST(DeformedBody, SkeletonMovesLandsOnTheProbe) {
  DeformOptions options;
  options.scheme = Scheme::SkeletonMoves;
  for (const Press& pr : presses()) {
    DeformedBody body(flat(), options);
    const Vec3 q = probe_over(flat(), pr.u, pr.v, pr.depth, pr.side);
    const contact::Contact c = contact_on_rest(flat(), q);
    ASSERT_TRUE(c.inside);
    ASSERT_EQ(c.side, pr.side);
    const std::uint64_t version = body.version();
    body.press(c, q);
    const double u = c.foot.u, v = c.foot.v;
    const Vec3 d = -c.depth * c.outward;
    EXPECT_LT((eval3(near_surface(body, c.side), u, v) - q).norm(), 1e-9) << "u=" << u << " v=" << v;
    EXPECT_LT((eval3(body.skeleton(), u, v) - eval3(flat().skeleton(), u, v) - d).norm(), 1e-9);
    EXPECT_LT((eval3(far_surface(body, c.side), u, v) - eval3(far_surface(flat(), c.side), u, v) - d).norm(), 1e-9);
    EXPECT_NEAR(eval_radius(body.skeleton(), u, v), eval_radius(flat().skeleton(), u, v), 1e-12);
    EXPECT_TRUE(all_finite(body));
    if (pr.depth > 0) {
      EXPECT_GT(body.version(), version);
      EXPECT_TRUE(body.awake());
    }
  }
}

// Scheme (b): skeleton by g D, radius by -(1-g) depth, near contour by D (onto the probe),
// far contour by (1 - 2g) depth * outward.
TEST(DeformedBody, CompressionLandsOnTheProbeForEveryShare) {
  for (double g : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    DeformOptions options;
    options.scheme = Scheme::Compression;
    options.g = g;
    for (const Press& pr : presses()) {
      DeformedBody body(flat(), options);
      const Vec3 q = probe_over(flat(), pr.u, pr.v, pr.depth, pr.side);
      const contact::Contact c = contact_on_rest(flat(), q);
      ASSERT_TRUE(c.inside);
      body.press(c, q);
      const double u = c.foot.u, v = c.foot.v;
      const Vec3 d = -c.depth * c.outward;
      EXPECT_LT((eval3(near_surface(body, c.side), u, v) - q).norm(), 1e-9) << "g=" << g << " u=" << u << " v=" << v;
      EXPECT_LT((eval3(body.skeleton(), u, v) - eval3(flat().skeleton(), u, v) - g * d).norm(), 1e-9) << "g=" << g;
      EXPECT_NEAR(eval_radius(body.skeleton(), u, v) - eval_radius(flat().skeleton(), u, v), -(1 - g) * c.depth, 1e-9)
          << "g=" << g;
      const Vec3 far_move = eval3(far_surface(body, c.side), u, v) - eval3(far_surface(flat(), c.side), u, v);
      EXPECT_LT((far_move - (1 - 2 * g) * c.depth * c.outward).norm(), 1e-9) << "g=" << g;
      EXPECT_TRUE(all_finite(body));
    }
  }
}

// g = 0.5: the far contour stays exactly where it was (not only at (u, v): its change is
// zero, so none of its control points move).
TEST(DeformedBody, HalfShareKeepsTheFarContourStill) {
  DeformOptions options;
  options.scheme = Scheme::Compression;
  options.g = 0.5;
  for (const Press& pr : presses()) {
    DeformedBody body(flat(), options);
    const Vec3 q = probe_over(flat(), pr.u, pr.v, pr.depth, pr.side);
    const contact::Contact c = contact_on_rest(flat(), q);
    body.press(c, q);
    EXPECT_LT((eval3(far_surface(body, c.side), c.foot.u, c.foot.v) - eval3(far_surface(flat(), c.side), c.foot.u, c.foot.v)).norm(),
              1e-12);
    const auto& far_now = far_surface(body, c.side).control();
    const auto& far_rest = far_surface(flat(), c.side).control();
    double worst = 0.0;
    for (std::size_t i = 0; i < far_now.size(); ++i) worst = std::max(worst, std::fabs(far_now[i] - far_rest[i]));
    EXPECT_LT(worst, 1e-12);
  }
}

// The control points change exactly as the least-norm modification of the specification
// prescribes, surface by surface (flat body: the contour over (u, v) is exactly M0 there).
TEST(DeformedBody, ControlPointChangesAreTheLeastNormModification) {
  for (const Scheme scheme : {Scheme::SkeletonMoves, Scheme::Compression}) {
    for (double g : {0.3, 0.5}) {
      DeformOptions options;
      options.scheme = scheme;
      options.g = g;
      for (const Press& pr : presses()) {
        if (pr.depth == 0) continue;
        DeformedBody body(flat(), options);
        const Vec3 q = probe_over(flat(), pr.u, pr.v, pr.depth, pr.side);
        const contact::Contact c = contact_on_rest(flat(), q);
        body.press(c, q);
        const double u = c.foot.u, v = c.foot.v;
        const BSplineSurface& sk = flat().skeleton();
        const std::vector<double> nu = all_basis(sk.knots_u(), sk.degree_u(), u);
        const std::vector<double> nv = all_basis(sk.knots_v(), sk.degree_v(), v);
        double su = 0, sv = 0;
        for (double x : nu) su += x * x;
        for (double x : nv) sv += x * x;
        const Vec3 d = -c.depth * c.outward;
        const double gg = scheme == Scheme::SkeletonMoves ? 1.0 : g;
        // Expected change of the 10 components at (u, v).
        std::array<double, 10> change{};
        const Vec3 dsk = gg * d;
        const Vec3 dnear = d;
        const Vec3 dfar = scheme == Scheme::SkeletonMoves ? d : Vec3((1 - 2 * g) * c.depth * c.outward);
        const Vec3 dtop = c.side > 0 ? dnear : dfar;
        const Vec3 dbottom = c.side > 0 ? dfar : dnear;
        for (int a = 0; a < 3; ++a) {
          change[static_cast<std::size_t>(a)] = dsk[a];
          change[static_cast<std::size_t>(4 + a)] = dtop[a];
          change[static_cast<std::size_t>(7 + a)] = dbottom[a];
        }
        change[3] = scheme == Scheme::SkeletonMoves ? 0.0 : -(1 - g) * c.depth;
        double expected_energy = 0.0;
        for (int i = 0; i < sk.rows(); ++i)
          for (int j = 0; j < sk.cols(); ++j) {
            const double w = nu[static_cast<std::size_t>(i)] * nv[static_cast<std::size_t>(j)] / (su * sv);
            const std::array<double, 10> got = displacement(body, i, j);
            const Material mt = material(flat(), i, j);
            for (std::size_t comp = 0; comp < 10; ++comp) {
              // 1e-12 of the press, plus the round-off of coordinates of ~0.05 m.
              ASSERT_NEAR(got[comp], w * change[comp], 1e-12 * c.depth + 1e-16)
                  << "scheme " << static_cast<int>(scheme) << " g=" << g << " control (" << i << ", " << j
                  << ") component " << comp;
              expected_energy += 0.5 * mt.k * got[comp] * got[comp];
            }
            // Material channels never change.
            for (int ch = mat::kStiffness; ch < mat::kSkeletonChannels; ++ch)
              ASSERT_EQ(body.skeleton().control_point(i, j)[static_cast<std::size_t>(ch)],
                        sk.control_point(i, j)[static_cast<std::size_t>(ch)]);
          }
        // Held points are at rest: all their energy is spring energy.
        EXPECT_NEAR(body.energy(), expected_energy, 1e-9 * expected_energy) << "scheme " << static_cast<int>(scheme);
        // max_displacement: at least the largest component change, at most the largest
        // 10-component displacement.
        double max_comp = 0.0, max_vec = 0.0;
        for (int i = 0; i < sk.rows(); ++i)
          for (int j = 0; j < sk.cols(); ++j) {
            const auto dd = displacement(body, i, j);
            for (double x : dd) max_comp = std::max(max_comp, std::fabs(x));
            max_vec = std::max(max_vec, norm(dd));
          }
        EXPECT_GE(body.max_displacement(), max_comp * (1 - 1e-12));
        EXPECT_LE(body.max_displacement(), max_vec * (1 + 1e-12));
      }
    }
  }
}

// The landing holds on a curved, unevenly parameterized body too, where the contour over a
// skeleton point between data sites is not exactly P + R n (the fit's own residual).
TEST(DeformedBody, LandsOnTheProbeOnACurvedBody) {
  const MatBody& rest = curved();
  for (const Scheme scheme : {Scheme::SkeletonMoves, Scheme::Compression}) {
    DeformOptions options;
    options.scheme = scheme;
    for (const Press& pr : presses()) {
      DeformedBody body(rest, options);
      const Vec3 q = probe_over(rest, pr.u, pr.v, std::min(pr.depth, 0.004), pr.side);
      const contact::Contact c = contact_on_rest(rest, q);
      ASSERT_TRUE(c.inside);
      body.press(c, q);
      const Vec3 m0 = c.foot.point + c.radius * c.outward;
      const double fit_gap = (eval3(near_surface(rest, c.side), c.foot.u, c.foot.v) - m0).norm();
      EXPECT_LT((eval3(near_surface(body, c.side), c.foot.u, c.foot.v) - q).norm(), 1e-9)
          << "scheme " << static_cast<int>(scheme) << " u=" << c.foot.u << " v=" << c.foot.v
          << " (|contour - M0| on the rest body there: " << fit_gap << ")";
      if (scheme == Scheme::Compression) {
        EXPECT_LT((eval3(far_surface(body, c.side), c.foot.u, c.foot.v) -
                   eval3(far_surface(rest, c.side), c.foot.u, c.foot.v)).norm(),
                  1e-12);
      }
      EXPECT_TRUE(all_finite(body));
    }
  }
}

// Other points move no more than max |dP| (partition of unity); beyond the pressed
// control points' support nothing moves at all.
TEST(DeformedBody, OtherPointsBoundedAndOutsideSupportStill) {
  for (const Scheme scheme : {Scheme::SkeletonMoves, Scheme::Compression}) {
    for (int influence : {0, 2}) {
      DeformOptions options;
      options.scheme = scheme;
      options.g = 0.3;
      options.influence_u = influence;
      options.influence_v = influence;
      DeformedBody body(flat_fine(), options);
      const Vec3 q = probe_over(flat_fine(), 0.43, 0.56, 0.005, 1);
      const contact::Contact c = contact_on_rest(flat_fine(), q);
      body.press(c, q);
      EXPECT_LT((eval3(body.top(), c.foot.u, c.foot.v) - q).norm(), 1e-9) << "influence " << influence;
      const BSplineSurface& sk = flat_fine().skeleton();
      // Changed control points: a window of at most (p+1) x (q+1) (p' x q' when limited).
      int changed = 0;
      int i_lo = sk.rows(), i_hi = -1, j_lo = sk.cols(), j_hi = -1;
      std::array<double, 4> max_dp{};  // skeleton xyz, radius, top, bottom
      for (int i = 0; i < sk.rows(); ++i)
        for (int j = 0; j < sk.cols(); ++j) {
          const auto d = displacement(body, i, j);
          if (std::any_of(d.begin(), d.end(), [](double x) { return x != 0.0; })) {
            ++changed;
            i_lo = std::min(i_lo, i), i_hi = std::max(i_hi, i), j_lo = std::min(j_lo, j), j_hi = std::max(j_hi, j);
          }
          max_dp[0] = std::max(max_dp[0], norm(std::span<const double>(d.data(), 3)));
          max_dp[1] = std::max(max_dp[1], std::fabs(d[3]));
          max_dp[2] = std::max(max_dp[2], norm(std::span<const double>(d.data() + 4, 3)));
          max_dp[3] = std::max(max_dp[3], norm(std::span<const double>(d.data() + 7, 3)));
        }
      const int wu = influence == 0 ? sk.degree_u() + 1 : influence;
      const int wv = influence == 0 ? sk.degree_v() + 1 : influence;
      EXPECT_LE(i_hi - i_lo + 1, wu);
      EXPECT_LE(j_hi - j_lo + 1, wv);
      EXPECT_LE(changed, wu * wv);
      int still = 0;
      for (int a = 0; a <= 50; ++a) {
        for (int b = 0; b <= 50; ++b) {
          const double u = a / 50.0, v = b / 50.0;
          const Vec3 dsk = eval3(body.skeleton(), u, v) - eval3(sk, u, v);
          const double dr = eval_radius(body.skeleton(), u, v) - eval_radius(sk, u, v);
          const Vec3 dtop = eval3(body.top(), u, v) - eval3(flat_fine().top(), u, v);
          const Vec3 dbot = eval3(body.bottom(), u, v) - eval3(flat_fine().bottom(), u, v);
          ASSERT_LE(dsk.norm(), max_dp[0] * (1 + 1e-12) + 1e-16) << u << ", " << v;
          ASSERT_LE(std::fabs(dr), max_dp[1] * (1 + 1e-12) + 1e-16) << u << ", " << v;
          ASSERT_LE(dtop.norm(), max_dp[2] * (1 + 1e-12) + 1e-16) << u << ", " << v;
          ASSERT_LE(dbot.norm(), max_dp[3] * (1 + 1e-12) + 1e-16) << u << ", " << v;
          const std::vector<double> nu = all_basis(sk.knots_u(), sk.degree_u(), u);
          const std::vector<double> nv = all_basis(sk.knots_v(), sk.degree_v(), v);
          bool touches_u = false, touches_v = false;
          for (int i = i_lo; i <= i_hi; ++i) touches_u = touches_u || nu[static_cast<std::size_t>(i)] != 0.0;
          for (int j = j_lo; j <= j_hi; ++j) touches_v = touches_v || nv[static_cast<std::size_t>(j)] != 0.0;
          if (!(touches_u && touches_v)) {
            ++still;
            ASSERT_EQ(eval_all(body.skeleton(), u, v), eval_all(sk, u, v)) << u << ", " << v;
            ASSERT_EQ(eval_all(body.top(), u, v), eval_all(flat_fine().top(), u, v)) << u << ", " << v;
            ASSERT_EQ(eval_all(body.bottom(), u, v), eval_all(flat_fine().bottom(), u, v)) << u << ", " << v;
          }
        }
      }
      EXPECT_GT(still, 1000);
    }
  }
}

// A probe pressing along a path, one press and one step per haptic tick: the drawn
// surface under it stays on it every tick; with g = 0.5 the far side never moves.
TEST(DeformedBody, SurfaceFollowsAProbePressingAlongAPath) {
  const long ticks = (long_tests() ? 5000L : 400L) / kLoopDivisor;
  struct Case {
    const MatBody* rest;
    Scheme scheme;
    double g;
    int side;
  };
  const std::vector<Case> cases = {{&flat(), Scheme::Compression, 0.5, 1},
                                   {&flat(), Scheme::SkeletonMoves, 0.5, -1},
                                   {&varied(), Scheme::Compression, 0.2, 1},
                                   {&curved(), Scheme::Compression, 0.5, 1},
                                   {&curved(), Scheme::SkeletonMoves, 0.5, -1}};
  for (const Case& cs : cases) {
    const MatBody& rest = *cs.rest;
    DeformOptions options;
    options.scheme = cs.scheme;
    options.g = cs.g;
    DeformedBody body(rest, options);
    const contact::FootPointSearch search(rest.skeleton());
    double u_prev = 0.5, v_prev = 0.5;
    std::uint64_t version = body.version();
    double worst = 0.0, worst_far = 0.0;
    for (long n = 0; n < ticks; ++n) {
      const double s = static_cast<double>(n) / static_cast<double>(ticks);
      const double u = 0.3 + 0.4 * s;
      const double v = 0.5 + 0.15 * std::sin(6 * std::numbers::pi * s);
      const double depth = 0.002 + 0.002 * std::sin(4 * std::numbers::pi * s) * std::sin(4 * std::numbers::pi * s);
      const Vec3 q = probe_over(rest, u, v, depth, cs.side);
      const contact::FootPoint foot = search.closest_from(rest.skeleton(), q, u_prev, v_prev);
      u_prev = foot.u;
      v_prev = foot.v;
      const contact::Contact c = contact::make_contact(rest, foot, q);
      ASSERT_TRUE(c.inside) << n;
      body.press(c, q);
      worst = std::max(worst, (eval3(near_surface(body, c.side), c.foot.u, c.foot.v) - q).norm());
      if (cs.scheme == Scheme::Compression && cs.g == 0.5) {
        worst_far = std::max(worst_far, (eval3(far_surface(body, c.side), c.foot.u, c.foot.v) -
                                         eval3(far_surface(rest, c.side), c.foot.u, c.foot.v)).norm());
      }
      ASSERT_TRUE(all_finite(body)) << "tick " << n;
      EXPECT_GT(body.version(), version) << "tick " << n;
      body.step(1e-3);
      version = body.version();
    }
    EXPECT_LT(worst, 1e-9) << "case " << (&cs - cases.data());
    EXPECT_LT(worst_far, 1e-9) << "case " << (&cs - cases.data());
    // Let go: it settles and sleeps at rest.
    body.release();
    for (int n = 0; n < 2000 && body.awake(); ++n) body.step(1e-3);
    EXPECT_FALSE(body.awake()) << "case " << (&cs - cases.data());
    EXPECT_TRUE(at_rest(body)) << "case " << (&cs - cases.data());
  }
}

}  // namespace
}  // namespace palpa::deform
