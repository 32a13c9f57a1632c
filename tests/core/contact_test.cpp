// The contact model (paper sections 3.1 and 3.4): foot point, contact and force, each
// checked against a truth that does not come from the implementation: closed forms on a
// flat and a cylindrical skeleton, a brute-force projection written here (dense sampling
// plus a derivative-free local refinement), the formulas of the specification evaluated
// independently, and physical properties (monotone, outward, Lipschitz, capped, finite).
#include "palpa/contact/contact.hpp"
#include "palpa/contact/foot_point.hpp"
#include "palpa/contact/force.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "palpa/mat/mat_body.hpp"
#include "palpa/mat/tumour.hpp"
#include "test_grids.hpp"

namespace palpa::contact {
namespace {

using mat::MatBody;
using spline::BSplineSurface;

// The long loops run at full length in optimized builds and at a tenth of it in the
// debug + sanitizer build (the dev preset), where they would otherwise take minutes.
#ifdef NDEBUG
constexpr int kLoopScale = 10;
#else
constexpr int kLoopScale = 1;
#endif

// ---------------------------------------------------------------------------------------
// Independent evaluation helpers (straight from the spline, never from contact/).

std::array<double, 7> sk_at(const BSplineSurface& sk, double u, double v) {
  std::array<double, 7> out{};
  sk.evaluate(u, v, out);
  return out;
}

Vec3 sk_point(const BSplineSurface& sk, double u, double v) {
  const auto s = sk_at(sk, u, v);
  return {s[mat::kX], s[mat::kY], s[mat::kZ]};
}

Vec3 contour_point(const BSplineSurface& contour, double u, double v) {
  std::array<double, 3> out{};
  contour.evaluate(u, v, out);
  return {out[0], out[1], out[2]};
}

Vec3 sk_normal(const BSplineSurface& sk, double u, double v) {
  double n[3];
  EXPECT_TRUE(mat::skeleton_normal(sk, u, v, n));
  return {n[0], n[1], n[2]};
}

// dS/du and dS/dv (xyz) at (u, v).
std::pair<Vec3, Vec3> sk_tangents(const BSplineSurface& sk, double u, double v) {
  std::array<double, 4 * 3> d{};
  sk.derivatives(u, v, 1, d, 3);
  const auto at = [&](int k, int l, int c) { return d[spline::derivative_index(k, l, 1, 3, c)]; };
  return {Vec3(at(1, 0, 0), at(1, 0, 1), at(1, 0, 2)), Vec3(at(0, 1, 0), at(0, 1, 1), at(0, 1, 2))};
}

bool finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

double clamp01(double t) { return std::clamp(t, 0.0, 1.0); }

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

// ---------------------------------------------------------------------------------------
// Bodies.

// test::flat_body: plane z = 0 over [-0.05, 0.05]^2, uniform grid, r = r0 (1-a^2)(1-b^2),
// k constant. x runs along u (rows), y along v (cols), so N = +z and u = (x + 0.05)/0.1.
constexpr double kHalf = 0.05;
constexpr double kR0 = 0.02;
constexpr double kFlatK = 200.0;

double flat_radius(double x, double y) {
  const double a = x / kHalf;
  const double b = y / kHalf;
  return kR0 * (1 - a * a) * (1 - b * b);
}

const MatBody& flat() {
  static const MatBody body = MatBody::fit(test::flat_body(9, 9, kHalf, kR0, kFlatK));
  return body;
}

// Quarter cylinder of radius Rc about the y axis: u runs with the angle phi in [0, pi/2]
// (from +x towards +z), v along y in [0, 0.12]. Su x Sv points at the axis, so the top
// (+N) side is the inner one.
constexpr double kRc = 0.1;
constexpr double kCylLength = 0.12;

mat::BodyGrid cylinder_grid(int rows = 17, int cols = 9) {
  mat::BodyGrid g;
  g.id = "cyl";
  g.rows = rows;
  g.cols = cols;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      const double s = i / double(rows - 1);
      const double t = j / double(cols - 1);
      const double phi = 0.5 * std::numbers::pi * s;
      const bool edge = i == 0 || j == 0 || i == rows - 1 || j == cols - 1;
      g.medial.push_back({kRc * std::cos(phi), kCylLength * t, kRc * std::sin(phi)});
      g.radius.push_back(edge ? 0.0 : 0.01 * std::sin(std::numbers::pi * s) * std::sin(std::numbers::pi * t));
      g.stiffness.push_back(300.0);
    }
  }
  return g;
}

const MatBody& cylinder() {
  static const MatBody body = MatBody::fit(cylinder_grid());
  return body;
}

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

// A saddle with a wave on it: curvature radius down to about 3 cm, so probes a few cm
// away have several local minima; radius and stiffness vary over the body.
mat::BodyGrid saddle_grid(int n = 11, double k_scale = 1.0) {
  mat::BodyGrid g;
  g.id = "saddle";
  g.rows = n;
  g.cols = n;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double a = -1.0 + 2.0 * i / double(n - 1);
      const double b = -1.0 + 2.0 * j / double(n - 1);
      g.medial.push_back({kHalf * a, kHalf * b, 0.025 * (a * a - b * b) + 0.004 * std::sin(3 * a + 1) * std::cos(2 * b)});
      g.radius.push_back(0.02 * (1 - a * a) * (1 - b * b) * (1 + 0.2 * std::sin(2 * a + b)));
      g.stiffness.push_back(k_scale * (300.0 + 100.0 * a + 50.0 * b * b));
    }
  }
  return g;
}

const MatBody& saddle() {
  static const MatBody body = MatBody::fit(saddle_grid());
  return body;
}

const BruteForce& saddle_brute() {
  static const BruteForce brute(saddle().skeleton());
  return brute;
}

constexpr double kSaddleKMax = 450.0;  // 300 + 100 + 50 at the stiffest grid point

// ---------------------------------------------------------------------------------------
// The specification's formulas, evaluated here from the splines.

struct Expected {
  Vec3 p;
  double radius;
  double stiffness;
  double depth;
  Vec3 outward;
  int side;
};

Expected expected_contact(const MatBody& body, double u, double v, const Vec3& q) {
  const auto s = sk_at(body.skeleton(), u, v);
  Expected e{};
  e.p = Vec3(s[mat::kX], s[mat::kY], s[mat::kZ]);
  e.radius = std::max(0.0, s[mat::kRadius]);
  e.stiffness = std::max(0.0, s[mat::kStiffness]);
  const double d = (q - e.p).norm();
  e.depth = e.radius - d;
  const Vec3 n = sk_normal(body.skeleton(), u, v);
  e.side = (q - e.p).dot(n) >= 0.0 ? 1 : -1;
  // At an interior foot point Q - P is parallel to N (the foot point's first-order
  // condition), so the outward direction is +-N exactly; (Q - P) / |Q - P| at a computed
  // foot point carries the search's round-off, which near the skeleton is no direction.
  const bool interior = u > 0.0 && u < 1.0 && v > 0.0 && v < 1.0;
  e.outward = interior ? Vec3(e.side * n) : (d > 0.0 ? Vec3((q - e.p) / d) : n);
  return e;
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

// The force at q as the library computes it from a fast (cold) foot point.
struct Probe {
  FootPoint foot;
  Contact contact;
  Force force;
};

Probe probe(const MatBody& body, const FootPointSearch& search, const Vec3& q,
            std::span<const mat::Tumour> tumours = {}, const ForceOptions& options = {}) {
  Probe p;
  p.foot = search.closest(body.skeleton(), q);
  p.contact = make_contact(body, p.foot, q);
  p.force = contact_force(body, p.contact, q, tumours, options);
  return p;
}

void expect_vec_near(const Vec3& got, const Vec3& want, double tol, const std::string& what) {
  EXPECT_LE((got - want).norm(), tol) << what << ": got (" << got.transpose() << ") want (" << want.transpose()
                                      << ")";
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

// ======================================================================================
// Stress: random probes everywhere around a curved body, including the hard places
// (exactly on the skeleton, on its boundary and corners, near the focal distance, far
// away). 1e5 probes (1e4 in debug builds); 1e7 with PALPA_LONG_TESTS=1.

TEST(Stress, RandomProbesGiveFiniteResultsCappedForcesAndDepthAtMostTheRadius) {
  const char* long_tests = std::getenv("PALPA_LONG_TESTS");
  const long count = long_tests != nullptr && std::string(long_tests) == "1" ? 10'000'000 : 10'000L * kLoopScale;
  const MatBody stiff = MatBody::fit(saddle_grid(11, 100.0));
  const MatBody* bodies[] = {&saddle(), &stiff, &cylinder()};
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  long failures = 0;
  const auto fail = [&](const std::string& what, const Vec3& q) {
    if (++failures <= 10) ADD_FAILURE() << what << " at probe (" << q.transpose() << ")";
  };
  for (const MatBody* body : bodies) {
    const FootPointSearch search(body->skeleton());
    const Vec3 centre = sk_point(body->skeleton(), 0.5, 0.5);
    const Vec3 p_mid = centre + 0.3 * sk_at(body->skeleton(), 0.5, 0.5)[mat::kRadius] * sk_normal(body->skeleton(), 0.5, 0.5);
    const std::vector<mat::Tumour> tumours{{body->id(), {p_mid.x(), p_mid.y(), p_mid.z()}, 0.003, 3000.0}};
    ForceOptions options;
    FootPoint warm = search.closest(body->skeleton(), centre);
    for (long n = 0; n < count / 3; ++n) {
      Vec3 q;
      const double u = unit(rng);
      const double v = unit(rng);
      switch (n % 6) {
        case 0:  // anywhere in a box around the body
          q = centre + Vec3(0.15 * (2 * unit(rng) - 1), 0.15 * (2 * unit(rng) - 1), 0.15 * (2 * unit(rng) - 1));
          break;
        case 1:  // exactly on the skeleton (to round-off)
          q = sk_point(body->skeleton(), u, v);
          break;
        case 2:  // on the boundary or a corner of the parameter domain, a little off
          q = sk_point(body->skeleton(), std::round(u), n % 12 == 2 ? std::round(v) : v) +
              1e-3 * unit(rng) * Vec3(gauss(rng), gauss(rng), gauss(rng));
          break;
        case 3:  // inside, near the surface
          q = sk_point(body->skeleton(), u, v) + (2 * unit(rng) - 1) * sk_at(body->skeleton(), u, v)[mat::kRadius] *
                                                      sk_normal(body->skeleton(), u, v);
          break;
        case 4:  // a few cm off the skeleton along its normal (focal distances)
          q = sk_point(body->skeleton(), u, v) + 0.1 * (2 * unit(rng) - 1) * sk_normal(body->skeleton(), u, v);
          break;
        default:  // tiny offsets around the skeleton (|PQ| ~ 1e-300 .. 1e-6)
          q = sk_point(body->skeleton(), u, v) +
              std::pow(10.0, -6.0 - 294.0 * unit(rng)) * Vec3(gauss(rng), gauss(rng), gauss(rng));
          break;
      }
      const bool use_warm = n % 2 == 1;
      const FootPoint f = use_warm ? search.closest_from(body->skeleton(), q, warm.u, warm.v)
                                   : search.closest(body->skeleton(), q);
      warm = f;
      if (!(f.u >= 0.0 && f.u <= 1.0 && f.v >= 0.0 && f.v <= 1.0)) fail("(u, v) outside [0, 1]^2", q);
      if (!finite(f.point) || !finite(f.su) || !finite(f.sv) || !std::isfinite(f.distance) || f.distance < 0.0)
        fail("foot point not finite", q);
      const Contact c = make_contact(*body, f, q);
      if (!std::isfinite(c.depth) || !std::isfinite(c.radius) || !std::isfinite(c.stiffness) || !finite(c.outward))
        fail("contact not finite", q);
      if (!(c.depth <= c.radius)) fail("depth " + std::to_string(c.depth) + " > radius", q);
      if (std::abs(c.outward.norm() - 1.0) > 1e-9) fail("outward not a unit vector", q);
      if (c.inside != (c.depth >= 0.0)) fail("inside != (depth >= 0)", q);
      if (c.radius < 0.0 || c.stiffness < 0.0) fail("negative radius or stiffness", q);
      const Force force = contact_force(*body, c, q, tumours, options);
      if (!finite(force.total) || !finite(force.normal) || !finite(force.shear) || !finite(force.tumour))
        fail("force not finite", q);
      if (force.total.norm() > options.max_force * (1.0 + 1e-12))
        fail("|F| = " + std::to_string(force.total.norm()) + " above the cap", q);
      if (!c.inside && force.total != Vec3::Zero()) fail("force outside", q);
    }
  }
  EXPECT_EQ(failures, 0);
}

}  // namespace
}  // namespace palpa::contact
