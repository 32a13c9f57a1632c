#pragma once
// Shared by the contact tests (contact_*_test.cpp): evaluation straight from the splines
// (never through core/src/contact), the bodies whose geometry is known in closed form (a
// flat skeleton, a quarter cylinder) or only by brute force (a wavy saddle), the
// specification's contact formulas evaluated independently, and the force at a probe as
// the library computes it from a cold foot point.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <span>
#include <string>
#include <utility>

#include "palpa/contact/contact.hpp"
#include "palpa/contact/foot_point.hpp"
#include "palpa/contact/force.hpp"
#include "palpa/mat/mat_body.hpp"
#include "palpa/mat/tumour.hpp"
#include "../support/test_grids.hpp"

namespace palpa::contact::contact_test {

using mat::MatBody;
using spline::BSplineSurface;

// The long loops run at full length in optimized builds and at a tenth of it in the
// debug + sanitizer build (the dev preset), where they would otherwise take minutes.
#ifdef NDEBUG
inline constexpr int kLoopScale = 10;
#else
inline constexpr int kLoopScale = 1;
#endif

// ---------------------------------------------------------------------------------------
// Independent evaluation helpers (straight from the spline, never from contact/).

inline std::array<double, 7> sk_at(const BSplineSurface& sk, double u, double v) {
  std::array<double, 7> out{};
  sk.evaluate(u, v, out);
  return out;
}

inline Vec3 sk_point(const BSplineSurface& sk, double u, double v) {
  const auto s = sk_at(sk, u, v);
  return {s[mat::kX], s[mat::kY], s[mat::kZ]};
}

inline Vec3 sk_normal(const BSplineSurface& sk, double u, double v) {
  double n[3];
  EXPECT_TRUE(mat::skeleton_normal(sk, u, v, n));
  return {n[0], n[1], n[2]};
}

inline bool finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

inline double clamp01(double t) { return std::clamp(t, 0.0, 1.0); }

// ---------------------------------------------------------------------------------------
// Bodies.

// test::flat_body: plane z = 0 over [-0.05, 0.05]^2, uniform grid, r = r0 (1-a^2)(1-b^2),
// k constant. x runs along u (rows), y along v (cols), so N = +z and u = (x + 0.05)/0.1.
inline constexpr double kHalf = 0.05;
inline constexpr double kR0 = 0.02;
inline constexpr double kFlatK = 200.0;

inline double flat_radius(double x, double y) {
  const double a = x / kHalf;
  const double b = y / kHalf;
  return kR0 * (1 - a * a) * (1 - b * b);
}

inline const MatBody& flat() {
  static const MatBody body = MatBody::fit(test::flat_body(9, 9, kHalf, kR0, kFlatK));
  return body;
}

// Quarter cylinder of radius Rc about the y axis: u runs with the angle phi in [0, pi/2]
// (from +x towards +z), v along y in [0, 0.12]. Su x Sv points at the axis, so the top
// (+N) side is the inner one.
inline constexpr double kRc = 0.1;
inline constexpr double kCylLength = 0.12;

inline mat::BodyGrid cylinder_grid(int rows = 17, int cols = 9) {
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

inline const MatBody& cylinder() {
  static const MatBody body = MatBody::fit(cylinder_grid());
  return body;
}

// A saddle with a wave on it: curvature radius down to about 3 cm, so probes a few cm
// away have several local minima; radius and stiffness vary over the body.
inline mat::BodyGrid saddle_grid(int n = 11, double k_scale = 1.0) {
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

inline const MatBody& saddle() {
  static const MatBody body = MatBody::fit(saddle_grid());
  return body;
}

inline constexpr double kSaddleKMax = 450.0;  // 300 + 100 + 50 at the stiffest grid point

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

inline Expected expected_contact(const MatBody& body, double u, double v, const Vec3& q) {
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

// The force at q as the library computes it from a fast (cold) foot point.
struct Probe {
  FootPoint foot;
  Contact contact;
  Force force;
};

inline Probe probe(const MatBody& body, const FootPointSearch& search, const Vec3& q,
                   std::span<const mat::Tumour> tumours = {}, const ForceOptions& options = {}) {
  Probe p;
  p.foot = search.closest(body.skeleton(), q);
  p.contact = make_contact(body, p.foot, q);
  p.force = contact_force(body, p.contact, q, tumours, options);
  return p;
}

inline void expect_vec_near(const Vec3& got, const Vec3& want, double tol, const std::string& what) {
  EXPECT_LE((got - want).norm(), tol) << what << ": got (" << got.transpose() << ") want (" << want.transpose()
                                      << ")";
}

}  // namespace palpa::contact::contact_test
