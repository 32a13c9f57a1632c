// The foot point (paper section 3.1): the closest point of the skeleton to a probe, by the
// fast search (cold and warm), the paper's bisection and raw Newton. Truths: the vertical
// projection in closed form on a flat skeleton, the circle on a quarter cylinder (convex
// side, concave side and the axis, where the distance's Hessian degenerates), a brute-force
// projection written here (dense sampling plus a derivative-free compass search) on a wavy
// saddle, and the first-order conditions of a minimum over the parameter box.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "contact_test_support.hpp"

namespace palpa::contact {
namespace {

using namespace contact_test;

// dS/du and dS/dv (xyz) at (u, v).
std::pair<Vec3, Vec3> sk_tangents(const BSplineSurface& sk, double u, double v) {
  std::array<double, 4 * 3> d{};
  sk.derivatives(u, v, 1, d, 3);
  const auto at = [&](int k, int l, int c) { return d[spline::derivative_index(k, l, 1, 3, c)]; };
  return {Vec3(at(1, 0, 0), at(1, 0, 1), at(1, 0, 2)), Vec3(at(0, 1, 0), at(0, 1, 1), at(0, 1, 2))};
}

// ---------------------------------------------------------------------------------------
// Brute-force foot point: |SK(u, v) - Q| on a dense (n+1) x (n+1) parameter grid; every
// sampled local minimum (no neighbour strictly smaller) is refined by a compass search
// (8 directions, step halved when no neighbour improves, down to 1e-14), which needs no
// derivatives and respects the box by clamping; the smallest refined value wins.
class BruteForce {
 public:
  explicit BruteForce(const BSplineSurface& sk, int n = 128) : sk_(sk), n_(n) {
    points_.reserve(static_cast<std::size_t>((n + 1) * (n + 1)));
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) points_.push_back(sk_point(sk, i / double(n), j / double(n)));
  }

  struct Result {
    double u = 0.0;
    double v = 0.0;
    double distance = 0.0;
  };

  Result closest(const Vec3& q, std::size_t max_refined = 400) const {
    const auto n1 = static_cast<std::size_t>(n_ + 1);
    std::vector<double> d2(points_.size());
    for (std::size_t k = 0; k < points_.size(); ++k) d2[k] = (points_[k] - q).squaredNorm();
    std::vector<std::pair<double, std::size_t>> minima;
    for (std::size_t i = 0; i < n1; ++i) {
      for (std::size_t j = 0; j < n1; ++j) {
        const double here = d2[i * n1 + j];
        bool local = true;
        for (int di = -1; di <= 1 && local; ++di) {
          for (int dj = -1; dj <= 1 && local; ++dj) {
            const auto ii = static_cast<long>(i) + di;
            const auto jj = static_cast<long>(j) + dj;
            if (ii < 0 || jj < 0 || ii >= static_cast<long>(n1) || jj >= static_cast<long>(n1)) continue;
            if (d2[static_cast<std::size_t>(ii) * n1 + static_cast<std::size_t>(jj)] < here) local = false;
          }
        }
        if (local) minima.emplace_back(here, i * n1 + j);
      }
    }
    std::sort(minima.begin(), minima.end());
    if (minima.size() > max_refined) minima.resize(max_refined);
    Result best;
    best.distance = std::numeric_limits<double>::infinity();
    for (const auto& [value, index] : minima) {
      (void)value;
      const double u0 = static_cast<double>(index / n1) / n_;
      const double v0 = static_cast<double>(index % n1) / n_;
      const Result r = refine(q, u0, v0);
      if (r.distance < best.distance) best = r;
    }
    return best;
  }

  Result refine(const Vec3& q, double u, double v) const {
    double f = (sk_point(sk_, u, v) - q).squaredNorm();
    double h = 1.0 / n_;
    for (int guard = 0; h > 1e-14 && guard < 100000; ++guard) {
      double best_f = f;
      double best_u = u;
      double best_v = v;
      for (int du = -1; du <= 1; ++du) {
        for (int dv = -1; dv <= 1; ++dv) {
          if (du == 0 && dv == 0) continue;
          const double uu = clamp01(u + du * h);
          const double vv = clamp01(v + dv * h);
          const double ff = (sk_point(sk_, uu, vv) - q).squaredNorm();
          if (ff < best_f) {
            best_f = ff;
            best_u = uu;
            best_v = vv;
          }
        }
      }
      if (best_f < f) {
        f = best_f;
        u = best_u;
        v = best_v;
      } else {
        h *= 0.5;
      }
    }
    return {u, v, std::sqrt(f)};
  }

 private:
  const BSplineSurface& sk_;
  int n_;
  std::vector<Vec3> points_;
};

// Largest | |SK_xz| - Rc | of the spline, measured on a dense grid: the spline's own
// deviation from the exact circle, used in the closed-form tolerances.
double cylinder_deviation() {
  static const double dev = [] {
    double worst = 0.0;
    for (int a = 0; a <= 400; ++a) {
      for (int b = 0; b <= 8; ++b) {
        const Vec3 p = sk_point(cylinder().skeleton(), a / 400.0, b / 8.0);
        worst = std::max(worst, std::abs(std::hypot(p.x(), p.z()) - kRc));
      }
    }
    return worst;
  }();
  return dev;
}

const BruteForce& saddle_brute() {
  static const BruteForce brute(saddle().skeleton());
  return brute;
}

// ======================================================================================
// Foot point on a flat skeleton: the vertical projection, in closed form.

TEST(FootPoint, FlatSkeletonFootPointIsTheVerticalProjection) {
  const MatBody& body = flat();
  const FootPointSearch search(body.skeleton());
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> xy(-0.049, 0.049);
  std::uniform_real_distribution<double> zz(-0.03, 0.03);
  std::uniform_real_distribution<double> start(0.0, 1.0);
  for (int n = 0; n < 200; ++n) {
    const Vec3 q(xy(rng), xy(rng), zz(rng));
    const double u = (q.x() + kHalf) / (2 * kHalf);
    const double v = (q.y() + kHalf) / (2 * kHalf);
    const FootPoint cold = search.closest(body.skeleton(), q);
    const FootPoint warm = search.closest_from(body.skeleton(), q, start(rng), start(rng));
    const FootPoint newton = newton_foot_point(body.skeleton(), q, 0.5, 0.5);
    for (const FootPoint* f : {&cold, &warm, &newton}) {
      EXPECT_NEAR(f->u, u, 1e-10) << q.transpose();
      EXPECT_NEAR(f->v, v, 1e-10) << q.transpose();
      EXPECT_NEAR(f->distance, std::abs(q.z()), 1e-12) << q.transpose();
      expect_vec_near(f->point, Vec3(q.x(), q.y(), 0.0), 1e-11, "foot point");
    }
    EXPECT_TRUE(cold.converged);
    EXPECT_TRUE(warm.converged);
  }
}

TEST(FootPoint, ReportsThePointAndTangentsAtItsParameters) {
  const MatBody& body = saddle();
  const FootPointSearch search(body.skeleton());
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> box(-0.06, 0.06);
  for (int n = 0; n < 50; ++n) {
    const Vec3 q(box(rng), box(rng), 0.5 * box(rng));
    const FootPoint f = search.closest(body.skeleton(), q);
    ASSERT_GE(f.u, 0.0);
    ASSERT_LE(f.u, 1.0);
    ASSERT_GE(f.v, 0.0);
    ASSERT_LE(f.v, 1.0);
    const auto [su, sv] = sk_tangents(body.skeleton(), f.u, f.v);
    expect_vec_near(f.point, sk_point(body.skeleton(), f.u, f.v), 1e-15, "point");
    expect_vec_near(f.su, su, 1e-12 * su.norm(), "su");
    expect_vec_near(f.sv, sv, 1e-12 * sv.norm(), "sv");
    EXPECT_NEAR(f.distance, (q - f.point).norm(), 1e-15);
  }
}

// Beyond the domain the closest skeleton point lies on its edge or corner: the parameter
// there must be exactly 0 or 1 (no 1 - 1e-9 left by a clamped Newton).
TEST(FootPoint, BeyondAnEdgeOrCornerTheFootPointIsExactlyOnIt) {
  const MatBody& body = flat();
  const FootPointSearch search(body.skeleton());
  struct Case {
    Vec3 q;
    double x;  // foot point x, y (closed form)
    double y;
  };
  const Case cases[] = {
      {{0.07, 0.01, 0.003}, 0.05, 0.01},     // beyond x = +0.05: u = 1
      {{-0.09, -0.02, -0.01}, -0.05, -0.02},  // beyond x = -0.05: u = 0
      {{0.013, 0.0501, 0.0}, 0.013, 0.05},    // just beyond y = +0.05, in the plane: v = 1
      {{0.0, -0.08, 0.02}, 0.0, -0.05},       // v = 0
      {{-0.06, 0.065, -0.002}, -0.05, 0.05},  // corner u = 0, v = 1
      {{0.2, 0.3, 0.1}, 0.05, 0.05},          // far corner u = 1, v = 1
      {{-0.05000001, -0.05000001, 0.0}, -0.05, -0.05},
  };
  for (const auto& c : cases) {
    const double u = (c.x + kHalf) / (2 * kHalf);
    const double v = (c.y + kHalf) / (2 * kHalf);
    const double distance = (c.q - Vec3(c.x, c.y, 0.0)).norm();
    const FootPoint cold = search.closest(body.skeleton(), c.q);
    const FootPoint warm_centre = search.closest_from(body.skeleton(), c.q, 0.5, 0.5);
    const FootPoint warm_far = search.closest_from(body.skeleton(), c.q, 1.0 - u, 1.0 - v);
    const FootPoint newton = newton_foot_point(body.skeleton(), c.q, 0.5, 0.5);
    for (const FootPoint* f : {&cold, &warm_centre, &warm_far, &newton}) {
      const std::string where = "probe " + std::to_string(c.q.x()) + "," + std::to_string(c.q.y());
      if (u == 0.0 || u == 1.0)
        EXPECT_EQ(f->u, u) << where;
      else
        EXPECT_NEAR(f->u, u, 1e-10) << where;
      if (v == 0.0 || v == 1.0)
        EXPECT_EQ(f->v, v) << where;
      else
        EXPECT_NEAR(f->v, v, 1e-10) << where;
      EXPECT_NEAR(f->distance, distance, 1e-12) << where;
    }
    // The radius is 0 on the boundary: the probe is outside by its whole distance.
    const Contact ct = make_contact(body, cold, c.q);
    EXPECT_FALSE(ct.inside);
    EXPECT_NEAR(ct.radius, 0.0, 1e-15);
    EXPECT_NEAR(ct.depth, -distance, 1e-12);
    const Force f = contact_force(body, ct, c.q, {});
    EXPECT_EQ(f.total, Vec3::Zero());
  }
}

// The bisection of the paper converges to 2^-levels where the problem separates (a flat
// or cylindrical skeleton: the sign of (Q - S).Su does not depend on v).
TEST(FootPoint, BisectionIsWithinTwoToTheMinusLevelsOnConvexSkeletons) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(0.02, 0.98);
  const BruteForce cyl_brute(cylinder().skeleton());
  for (int levels : {6, 10, 14}) {
    const double tol = 2.0 * std::ldexp(1.0, -levels);
    for (int n = 0; n < 20; ++n) {
      // Flat: closed form.
      const Vec3 q(-kHalf + 2 * kHalf * unit(rng), -kHalf + 2 * kHalf * unit(rng), 0.03 * (unit(rng) - 0.5));
      const FootPoint b = bisect_foot_point(flat().skeleton(), q, levels);
      EXPECT_NEAR(b.u, (q.x() + kHalf) / (2 * kHalf), tol) << "flat, levels " << levels;
      EXPECT_NEAR(b.v, (q.y() + kHalf) / (2 * kHalf), tol) << "flat, levels " << levels;
      // Cylinder, convex (outer) side: brute force.
      const double theta = 0.5 * std::numbers::pi * unit(rng);
      const double rho = kRc + 0.03 * unit(rng);
      const Vec3 qc(rho * std::cos(theta), kCylLength * unit(rng), rho * std::sin(theta));
      const FootPoint bc = bisect_foot_point(cylinder().skeleton(), qc, levels);
      const auto truth = cyl_brute.closest(qc);
      EXPECT_NEAR(bc.u, truth.u, tol) << "cylinder, levels " << levels;
      EXPECT_NEAR(bc.v, truth.v, tol) << "cylinder, levels " << levels;
      EXPECT_GE(bc.distance, truth.distance - 1e-12);
    }
  }
}

// ======================================================================================
// Cylinder: convex and concave side, and the neighbourhood of the axis (the skeleton's
// radius of curvature), where the Hessian of the distance degenerates.

TEST(FootPoint, CylinderConvexSideMatchesTheCircleAndBruteForce) {
  const MatBody& body = cylinder();
  const FootPointSearch search(body.skeleton());
  const BruteForce brute(body.skeleton());
  const double dev = cylinder_deviation();
  ASSERT_LT(dev, 1e-6);  // 17 rows through a quarter circle
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> angle(0.05, 0.5 * std::numbers::pi - 0.05);
  std::uniform_real_distribution<double> along(0.005, kCylLength - 0.005);
  for (double rho : {kRc + 1e-6, 0.1005, 0.11, 0.13, 0.2, 0.5}) {
    for (int n = 0; n < 8; ++n) {
      const double theta = angle(rng);
      const Vec3 q(rho * std::cos(theta), along(rng), rho * std::sin(theta));
      const FootPoint f = search.closest(body.skeleton(), q);
      const auto truth = brute.closest(q);
      EXPECT_NEAR(f.distance, rho - kRc, dev + 1e-12) << "rho " << rho;
      EXPECT_NEAR(f.point.y(), q.y(), 1e-9) << "rho " << rho;
      EXPECT_NEAR(f.distance, truth.distance, 1e-9) << "rho " << rho;
      EXPECT_LE(f.distance, truth.distance + 1e-12) << "rho " << rho;
      // Outer side = bottom (N points at the axis).
      EXPECT_EQ(make_contact(body, f, q).side, -1) << "rho " << rho;
    }
  }
}

// The concave side: between the skeleton and the axis (rho > 0), and past the axis
// (rho < 0), where the nearest skeleton point is an end of the arc with a second local
// minimum at the other end.
void check_cylinder_concave(const std::vector<double>& rhos, std::uint64_t seed) {
  const MatBody& body = cylinder();
  const FootPointSearch search(body.skeleton());
  const BruteForce brute(body.skeleton());
  const double dev = cylinder_deviation();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> angle(0.05, 0.5 * std::numbers::pi - 0.05);
  std::uniform_real_distribution<double> along(0.005, kCylLength - 0.005);
  for (double rho : rhos) {
    for (int n = 0; n < 6; ++n) {
      const double theta = angle(rng);
      const Vec3 q(rho * std::cos(theta), along(rng), rho * std::sin(theta));
      const auto truth = brute.closest(q);
      const std::string where = "rho " + std::to_string(rho) + " theta " + std::to_string(theta) + " y " +
                                std::to_string(q.y()) + " (brute force " + std::to_string(truth.distance) +
                                " at u " + std::to_string(truth.u) + ")";
      const FootPoint cold = search.closest(body.skeleton(), q);
      const FootPoint warm0 = search.closest_from(body.skeleton(), q, 0.0, 0.5);
      const FootPoint warm1 = search.closest_from(body.skeleton(), q, 1.0, 0.5);
      for (const FootPoint* f : {&cold, &warm0, &warm1}) {
        const std::string which = f == &cold ? "cold: " : f == &warm0 ? "warm from u = 0: " : "warm from u = 1: ";
        EXPECT_NEAR(f->distance, truth.distance, 1e-9) << which << where << " got u " << f->u;
        EXPECT_LE(f->distance - truth.distance, 1e-12) << which << where;
        if (truth.u == 0.0 || truth.u == 1.0) {
          EXPECT_EQ(f->u, truth.u) << which << where;
        }
        if (rho >= 1e-3) {
          EXPECT_NEAR(f->distance, kRc - rho, dev + 1e-12) << which << where;
          EXPECT_NEAR(f->point.y(), q.y(), 1e-9) << which << where;
        }
      }
      if (rho > 0.0) {
        EXPECT_EQ(make_contact(body, cold, q).side, 1) << where;  // inner side = top
      }
      if (rho <= -1e-3) {
        // Past the axis: the nearer end of the arc is the one at the smaller angle from
        // the probe's direction theta + pi.
        EXPECT_EQ(cold.u, theta < 0.25 * std::numbers::pi ? 1.0 : 0.0) << where;
      }
    }
  }
}

TEST(FootPoint, CylinderConcaveSideFindsTheGlobalMinimum) {
  check_cylinder_concave({0.0999, 0.09, 0.05, 0.01, 1e-3, -1e-3, -0.01, -0.05, -0.2}, 5);
}

// Within 0.1 mm of the axis (the skeleton's centre of curvature) every arc point is
// nearly equidistant (the distance varies by |rho| (1 - cos) plus the spline's own
// deviation from the circle, ~2.6e-7 m), the Hessian is nearly singular or indefinite,
// and there can be many local minima: the answer must still be the global one.
TEST(FootPoint, CylinderNearTheAxisFindsTheGlobalMinimum) {
  check_cylinder_concave({1e-4, 1e-5, 1e-7, 0.0, -1e-7, -1e-5, -1e-4}, 55);
}

// ======================================================================================
// A wavy saddle: 1000 probes (100 in debug builds) along a random walk (with jumps),
// cold and warm.

TEST(FootPoint, SaddleColdAndWarmAgreeWithBruteForce) {
  const MatBody& body = saddle();
  const FootPointSearch search(body.skeleton());
  const BruteForce& brute = saddle_brute();
  std::mt19937_64 rng(6);
  std::normal_distribution<double> step(0.0, 0.003);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto random_point = [&] {
    return Vec3(-0.08 + 0.16 * unit(rng), -0.08 + 0.16 * unit(rng), -0.06 + 0.12 * unit(rng));
  };
  Vec3 q(0.0, 0.0, 0.01);
  FootPoint warm = search.closest(body.skeleton(), q);
  int cold_bad = 0;
  int warm_bad = 0;
  double worst = 0.0;
  for (int n = 0; n < 100 * kLoopScale; ++n) {
    if (unit(rng) < 0.05)
      q = random_point();
    else
      q += Vec3(step(rng), step(rng), step(rng));
    q = q.cwiseMax(Vec3(-0.08, -0.08, -0.06)).cwiseMin(Vec3(0.08, 0.08, 0.06));
    const auto truth = brute.closest(q);
    const FootPoint cold = search.closest(body.skeleton(), q);
    const double u0 = warm.u;
    const double v0 = warm.v;
    warm = search.closest_from(body.skeleton(), q, u0, v0);
    worst = std::max({worst, cold.distance - truth.distance, warm.distance - truth.distance});
    if (std::abs(cold.distance - truth.distance) > 1e-9 || cold.distance > truth.distance + 1e-12) {
      if (++cold_bad <= 5)
        ADD_FAILURE() << "cold: probe (" << q.transpose() << ") distance " << cold.distance << " at (" << cold.u
                      << ", " << cold.v << "), brute force " << truth.distance << " at (" << truth.u << ", "
                      << truth.v << ")";
    }
    if (std::abs(warm.distance - truth.distance) > 1e-9 || warm.distance > truth.distance + 1e-12) {
      if (++warm_bad <= 5)
        ADD_FAILURE() << "warm from (" << u0 << ", " << v0 << "): probe (" << q.transpose() << ") distance "
                      << warm.distance << " at (" << warm.u
                      << ", " << warm.v << "), brute force " << truth.distance << " at (" << truth.u << ", "
                      << truth.v << ")";
    }
  }
  EXPECT_EQ(cold_bad, 0);
  EXPECT_EQ(warm_bad, 0) << "worst excess distance " << worst;
}

// The paper's bisection may be wrong on a concave skeleton (documented, not tested); the
// robust search is never farther than it.
TEST(FootPoint, FastIsNeverFartherThanBisection) {
  const MatBody& body = saddle();
  const FootPointSearch search(body.skeleton());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> box(-0.07, 0.07);
  int bisect_wrong = 0;
  for (int n = 0; n < 300; ++n) {
    const Vec3 q(box(rng), box(rng), 0.6 * box(rng));
    const FootPoint fast = search.closest(body.skeleton(), q);
    const FootPoint slow = bisect_foot_point(body.skeleton(), q, 10);
    EXPECT_LE(fast.distance, slow.distance + 1e-12) << q.transpose();
    if (slow.distance > fast.distance + 1e-4) ++bisect_wrong;
  }
  RecordProperty("bisect_off_by_more_than_0.1mm", bisect_wrong);
}

// Raw Newton: f = |S - Q|^2 / 2 never increases from the start, and a converged result
// satisfies the first-order conditions of a minimum over the box: (S - Q).Su = 0 inside,
// >= 0 at u = 0, <= 0 at u = 1 (same for v). "= 0" is checked as Piegl's zero-cosine
// test: the angle between QS and the normal plane below 1e-7 rad (1e-7 |QS| sideways),
// which moves the distance by a second-order amount only.
TEST(FootPoint, NewtonNeverIncreasesTheDistanceAndConvergesToAStationaryPoint) {
  const MatBody& body = saddle();
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> box(-0.07, 0.07);
  int converged = 0;
  for (int n = 0; n < 300; ++n) {
    const Vec3 q(box(rng), box(rng), 0.6 * box(rng));
    const double u0 = unit(rng);
    const double v0 = unit(rng);
    const FootPoint f = newton_foot_point(body.skeleton(), q, u0, v0);
    ASSERT_TRUE(f.u >= 0.0 && f.u <= 1.0 && f.v >= 0.0 && f.v <= 1.0);
    EXPECT_LE(f.distance, (sk_point(body.skeleton(), u0, v0) - q).norm() + 1e-15);
    if (!f.converged) continue;
    ++converged;
    const auto [su, sv] = sk_tangents(body.skeleton(), f.u, f.v);
    const Vec3 r = sk_point(body.skeleton(), f.u, f.v) - q;
    const double gu = r.dot(su) / su.norm();  // m
    const double gv = r.dot(sv) / sv.norm();
    const double tol = 1e-7 * f.distance + 1e-12;
    const auto check = [&](double t, double g, const char* name) {
      if (t == 0.0)
        EXPECT_GE(g, -tol) << name << " at 0, probe " << q.transpose();
      else if (t == 1.0)
        EXPECT_LE(g, tol) << name << " at 1, probe " << q.transpose();
      else
        EXPECT_NEAR(g, 0.0, tol) << name << " = " << t << ", probe " << q.transpose();
    };
    check(f.u, gu, "u");
    check(f.v, gv, "v");
  }
  EXPECT_GT(converged, 250);
}

}  // namespace
}  // namespace palpa::contact
