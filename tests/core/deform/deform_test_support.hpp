#pragma once
// Shared by the deformation tests (deform_*_test.cpp): the reference oscillator (textbook
// closed forms in long double) and the extreme grid of materials and time steps, B-spline
// basis functions by the Cox-de Boor recursion (never through core/src/spline or deform),
// and the bodies a probe presses: flat ones whose surfaces are known in closed form, one
// with varying materials, a curved and unevenly spaced one, with what the tests read off a
// DeformedBody (displacements, materials, rest).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <span>
#include <string>
#include <vector>

#include "palpa/contact/contact.hpp"
#include "palpa/contact/foot_point.hpp"
#include "palpa/deform/deformed_body.hpp"
#include "palpa/mat/mat_body.hpp"
#include "../support/test_grids.hpp"

namespace palpa::deform::deform_test {

using mat::MatBody;
using spline::BSplineSurface;
using LD = long double;

// The longest loops run 10x shorter without NDEBUG (the debug + sanitizer build).
#ifdef NDEBUG
inline constexpr long kLoopDivisor = 1;
#else
inline constexpr long kLoopDivisor = 10;
#endif

inline bool long_tests() {
  const char* env = std::getenv("PALPA_LONG_TESTS");
  return env != nullptr && std::string(env) == "1";
}

// =======================================================================================
// Reference oscillator: m x'' + b x' + k x = 0, closed forms in long double.
//
// With a = b / 2m, w2 = k / m and disc = a^2 - w2, every regime is
//   x(t) = e^{-at} [x0 C + (v0 + a x0) S],   v(t) = e^{-at} [v0 C - (w2 x0 + a v0) S]
// where C = cosh(sqrt(disc) t), S = sinh(sqrt(disc) t) / sqrt(disc) (cos / sin for
// disc < 0, C = 1 and S = t at disc = 0): summed as power series in z = disc t^2 near
// critical damping; the overdamped case far from it uses the two decaying exponentials
// (the slow rate -w2 / (a + beta) without cancellation) so nothing overflows.

struct State {
  LD x;
  LD v;
};

inline State reference(LD k, LD b, LD m, LD t, LD x0, LD v0) {
  if (t == 0) return {x0, v0};
  if (k == 0) {
    if (b == 0) return {x0 + v0 * t, v0};
    const LD r = b / m;
    return {x0 + v0 * (-std::expm1(-r * t)) / r, v0 * std::exp(-r * t)};
  }
  const LD a = b / (2 * m);
  const LD w2 = k / m;
  const LD w0 = std::sqrt(w2);
  const LD disc = (a - w0) * (a + w0);
  const LD z = disc * t * t;
  LD c = 0;
  LD s = 0;
  if (std::fabs(z) < 1) {
    LD term_c = 1;  // z^n / (2n)!
    LD term_s = t;  // t z^n / (2n+1)!
    for (int n = 0; n < 30; ++n) {
      c += term_c;
      s += term_s;
      term_c *= z / static_cast<LD>((2 * n + 1) * (2 * n + 2));
      term_s *= z / static_cast<LD>((2 * n + 2) * (2 * n + 3));
    }
  } else if (z < 0) {
    const LD wd = std::sqrt(-disc);
    c = std::cos(wd * t);
    s = std::sin(wd * t) / wd;
  } else {
    const LD beta = std::sqrt(disc);
    const LD r1 = -w2 / (a + beta);  // slow
    const LD r2 = -(a + beta);       // fast
    const LD c1 = (v0 - r2 * x0) / (2 * beta);
    const LD c2 = (r1 * x0 - v0) / (2 * beta);
    const LD e1 = std::exp(r1 * t);
    const LD e2 = std::exp(r2 * t);
    return {c1 * e1 + c2 * e2, r1 * c1 * e1 + r2 * c2 * e2};
  }
  const LD e = std::exp(-a * t);
  return {e * (x0 * c + (v0 + a * x0) * s), e * (v0 * c - (w2 * x0 + a * v0) * s)};
}

inline LD energy(LD k, LD m, LD x, LD v) { return (m * v * v + k * x * x) / 2; }

inline std::string params(double k, double b, double m, double dt) {
  return "k=" + std::to_string(k) + " b=" + std::to_string(b) + " m=" + std::to_string(m) +
         " dt=" + std::to_string(dt);
}

inline constexpr std::array<double, 5> kGridK = {1e-3, 1.0, 1e3, 1e6, 1e9};
inline constexpr std::array<double, 4> kGridM = {1e-6, 1e-3, 1.0, 10.0};
inline constexpr std::array<double, 5> kGridB = {0.0, 1e-3, 1.0, 1e2, 1e4};
inline constexpr std::array<double, 4> kGridDt = {1e-5, 1e-3, 1e-2, 0.1};

// ---------------------------------------------------------------------------------------
// Independent evaluation, never through core/src/spline or core/src/deform.

// All basis functions N_0..N_{n-1} of degree p at u by the Cox-de Boor recursion (for
// u = 1 the last non-empty span, so N_{n-1}(1) = 1).
inline std::vector<double> all_basis(const std::vector<double>& knots, int p, double u) {
  const std::size_t nk = knots.size();
  const std::size_t n = nk - static_cast<std::size_t>(p) - 1;
  std::vector<double> nb(nk - 1, 0.0);
  std::size_t span = n - 1;
  if (u < knots[n]) {
    for (std::size_t s = static_cast<std::size_t>(p); s < n; ++s) {
      if (knots[s] <= u && u < knots[s + 1]) {
        span = s;
        break;
      }
    }
  }
  nb[span] = 1.0;
  for (std::size_t d = 1; d <= static_cast<std::size_t>(p); ++d) {
    for (std::size_t i = 0; i + d + 1 < nk; ++i) {
      const double den_l = knots[i + d] - knots[i];
      const double den_r = knots[i + d + 1] - knots[i + 1];
      const double left = den_l > 0 ? (u - knots[i]) / den_l : 0.0;
      const double right = den_r > 0 ? (knots[i + d + 1] - u) / den_r : 0.0;
      nb[i] = left * nb[i] + right * nb[i + 1];
    }
  }
  nb.resize(n);
  return nb;
}

inline std::vector<double> eval_all(const BSplineSurface& s, double u, double v) {
  std::vector<double> out(static_cast<std::size_t>(s.dim()));
  s.evaluate(u, v, out);
  return out;
}

inline double norm(std::span<const double> d) {
  double s = 0;
  for (double x : d) s += x * x;
  return std::sqrt(s);
}

// ---------------------------------------------------------------------------------------
// Bodies a probe presses, and what the tests read off a DeformedBody.

inline constexpr double kHalf = 0.05;
inline constexpr double kR0 = 0.02;

inline double flat_radius(double x, double y) {
  const double a = x / kHalf;
  const double b = y / kHalf;
  return kR0 * (1 - a * a) * (1 - b * b);
}

// test::flat_body: plane z = 0, N = +z, k = 200, default damping ratio 0.7 and mass 1 g.
inline const MatBody& flat() {
  static const MatBody body = MatBody::fit(test::flat_body(9, 9, kHalf, kR0, 200.0));
  return body;
}

// The same on a finer grid (17 x 17 points, 14 knot spans): room beyond a press's support.
inline const MatBody& flat_fine() {
  static const MatBody body = MatBody::fit(test::flat_body(17, 17, kHalf, kR0, 200.0));
  return body;
}

// The flat body with stiffness, damping and mass varying over it: damping ratios from
// about 0.25 (underdamped) to 2.4 (overdamped), so released points follow different laws.
inline const MatBody& varied() {
  static const MatBody body = [] {
    mat::BodyGrid g = test::flat_body(9, 9, kHalf, kR0, 0.0);
    g.stiffness.clear();
    for (const auto& p : g.medial) {
      const double a = p[0] / kHalf, b = p[1] / kHalf;
      g.stiffness.push_back(300.0 + 100.0 * a + 50.0 * b);
      g.damping.push_back(0.3 + 1.2 * (a + 1.0));
      g.mass.push_back(1e-3 * (1.0 + 0.3 * b));
    }
    return MatBody::fit(g);
  }();
  return body;
}

// A curved, unevenly spaced body: a skewed dome with a ripple.
inline const MatBody& curved() {
  static const MatBody body = [] {
    mat::BodyGrid g;
    g.id = "curved";
    g.rows = 11;
    g.cols = 10;
    for (int i = 0; i < g.rows; ++i) {
      for (int j = 0; j < g.cols; ++j) {
        const double s = i / (g.rows - 1.0), t = j / (g.cols - 1.0);
        const double a = 2 * s - 1, b = 2 * t - 1;
        g.medial.push_back({0.06 * (s + 0.2 * s * s) + 0.01 * t, 0.08 * (t + 0.1 * std::sin(2 * t)),
                            0.015 * (1 - a * a) * (1 - 0.5 * b * b) + 0.003 * std::sin(3 * a + 2 * b)});
        g.radius.push_back(0.015 * (1 - a * a) * (1 - b * b));
        g.stiffness.push_back(250.0 + 80.0 * s);
      }
    }
    return MatBody::fit(g);
  }();
  return body;
}

inline Vec3 eval3(const BSplineSurface& s, double u, double v) {
  std::array<double, 8> out{};
  s.evaluate(u, v, std::span<double>(out.data(), static_cast<std::size_t>(s.dim())));
  return {out[0], out[1], out[2]};
}

inline double eval_radius(const BSplineSurface& skeleton, double u, double v) {
  std::array<double, 8> out{};
  skeleton.evaluate(u, v, std::span<double>(out.data(), static_cast<std::size_t>(skeleton.dim())));
  return out[mat::kRadius];
}

// Probe at depth `depth` below the surface over the skeleton point (u, v) on `side`.
inline Vec3 probe_over(const MatBody& rest, double u, double v, double depth, int side) {
  double n[3];
  EXPECT_TRUE(mat::skeleton_normal(rest.skeleton(), u, v, n));
  const Vec3 normal(n[0], n[1], n[2]);
  const double r = eval_radius(rest.skeleton(), u, v);
  return eval3(rest.skeleton(), u, v) + side * (r - depth) * normal;
}

inline contact::Contact contact_on_rest(const MatBody& rest, const Vec3& q) {
  const contact::FootPointSearch search(rest.skeleton());
  const contact::FootPoint foot = search.closest(rest.skeleton(), q);
  return contact::make_contact(rest, foot, q);
}

inline const BSplineSurface& near_surface(const DeformedBody& body, int side) { return side > 0 ? body.top() : body.bottom(); }
inline const BSplineSurface& far_surface(const DeformedBody& body, int side) { return side > 0 ? body.bottom() : body.top(); }
inline const BSplineSurface& near_surface(const MatBody& body, int side) { return side > 0 ? body.top() : body.bottom(); }
inline const BSplineSurface& far_surface(const MatBody& body, int side) { return side > 0 ? body.bottom() : body.top(); }

inline bool all_finite(const BSplineSurface& s) {
  return std::all_of(s.control().begin(), s.control().end(), [](double x) { return std::isfinite(x); });
}

inline bool all_finite(const DeformedBody& b) { return all_finite(b.skeleton()) && all_finite(b.top()) && all_finite(b.bottom()); }

inline bool at_rest(const DeformedBody& b) {
  return b.skeleton().control() == b.rest().skeleton().control() && b.top().control() == b.rest().top().control() &&
         b.bottom().control() == b.rest().bottom().control();
}

// Displacement of control point (i, j) in the 10 components (SK x y z r, top xyz, bottom xyz).
inline std::array<double, 10> displacement(const DeformedBody& b, int i, int j) {
  std::array<double, 10> d{};
  for (std::size_t c = 0; c < 4; ++c) d[c] = b.skeleton().control_point(i, j)[c] - b.rest().skeleton().control_point(i, j)[c];
  for (std::size_t c = 0; c < 3; ++c) d[4 + c] = b.top().control_point(i, j)[c] - b.rest().top().control_point(i, j)[c];
  for (std::size_t c = 0; c < 3; ++c) d[7 + c] = b.bottom().control_point(i, j)[c] - b.rest().bottom().control_point(i, j)[c];
  return d;
}

struct Material {
  double k, b, m;
};

inline Material material(const MatBody& rest, int i, int j) {
  const auto c = rest.skeleton().control_point(i, j);
  return {c[mat::kStiffness], c[mat::kDamping], c[mat::kMass]};
}

struct Press {
  double u, v, depth;
  int side;
};

inline const std::vector<Press>& presses() {
  static const std::vector<Press> p = {
      {0.5, 0.5, 0.004, 1}, {0.31, 0.62, 0.002, 1}, {0.44, 0.27, 0.006, -1},
      {0.7, 0.55, 0.001, -1}, {0.5, 0.5, 1e-5, 1},   {0.58, 0.41, 0.008, 1},
  };
  return p;
}

}  // namespace palpa::deform::deform_test
