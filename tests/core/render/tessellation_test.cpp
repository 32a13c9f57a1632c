// Tessellation for display: derivative bounds against dense sampling and exact values,
// the mesh's deviation from the surface against its tolerance, mesh structure, normals,
// winding, poles, and re-tessellation of changed bodies only.
#include "palpa/render/tessellation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "palpa/contact/contact.hpp"
#include "palpa/contact/foot_point.hpp"
#include "palpa/deform/deformed_body.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/mat/mat_body.hpp"
#include "../support/test_grids.hpp"

namespace palpa::render {
namespace {

using spline::BSplineSurface;

std::size_t idx(int i) { return static_cast<std::size_t>(i); }

/// Clamped cubic knots with the given interior knots on [0, 1].
std::vector<double> cubic_knots(const std::vector<double>& interior) {
  std::vector<double> k(4, 0.0);
  k.insert(k.end(), interior.begin(), interior.end());
  k.insert(k.end(), 4, 1.0);
  return k;
}

/// A bicubic surface whose coordinates are polynomials of degree <= 2 in u and v:
/// x = ax u, y = ay v, z = cuu u^2 + cuv u v + cvv v^2. Control points are the blossoms
/// (polar forms) of these polynomials at consecutive knots, so the spline reproduces them
/// exactly, and Suu = (0, 0, 2 cuu), Suv = (0, 0, cuv), Svv = (0, 0, 2 cvv) everywhere.
BSplineSurface quadratic_surface(double ax, double ay, double cuu, double cuv, double cvv,
                                 const std::vector<double>& interior_u, const std::vector<double>& interior_v) {
  const auto ku = cubic_knots(interior_u);
  const auto kv = cubic_knots(interior_v);
  const int rows = static_cast<int>(ku.size()) - 4;
  const int cols = static_cast<int>(kv.size()) - 4;
  // Blossoms of 1, t and t^2 at (t1, t2, t3): 1, (t1 + t2 + t3)/3, (t1 t2 + t1 t3 + t2 t3)/3.
  auto lin = [](const std::vector<double>& k, int i) { return (k[idx(i + 1)] + k[idx(i + 2)] + k[idx(i + 3)]) / 3.0; };
  auto sq = [](const std::vector<double>& k, int i) {
    const double a = k[idx(i + 1)], b = k[idx(i + 2)], c = k[idx(i + 3)];
    return (a * b + a * c + b * c) / 3.0;
  };
  std::vector<double> ctrl;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      ctrl.push_back(ax * lin(ku, i));
      ctrl.push_back(ay * lin(kv, j));
      ctrl.push_back(cuu * sq(ku, i) + cuv * lin(ku, i) * lin(kv, j) + cvv * sq(kv, j));
    }
  }
  return BSplineSurface(3, 3, ku, kv, rows, cols, 3, ctrl);
}

/// A bicubic surface with randomly disturbed control points, non-uniform knots and a double knot
/// (C1 there: the second derivatives jump).
BSplineSurface random_surface(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-0.002, 0.002);
  const auto ku = cubic_knots({0.15, 0.4, 0.4, 0.7});
  const auto kv = cubic_knots({0.3, 0.35, 0.8});
  const int rows = static_cast<int>(ku.size()) - 4;
  const int cols = static_cast<int>(kv.size()) - 4;
  std::vector<double> ctrl;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      // Greville abscissae: x ~ 0.1 u and y ~ 0.1 v, disturbed.
      ctrl.push_back(0.1 * (ku[idx(i + 1)] + ku[idx(i + 2)] + ku[idx(i + 3)]) / 3.0 + d(rng));
      ctrl.push_back(0.1 * (kv[idx(j + 1)] + kv[idx(j + 2)] + kv[idx(j + 3)]) / 3.0 + d(rng));
      ctrl.push_back(d(rng));
      ctrl.push_back(7.0);  // a 4th channel must not enter the bounds
    }
  }
  return BSplineSurface(3, 3, ku, kv, rows, cols, 4, ctrl);
}

/// Half a dome over the angles [0, pi]: control row 0 is collapsed to the apex (a pole
/// row: Sv = 0 along u = 0).
BSplineSurface pole_surface() {
  const int rows = 6;
  const int cols = 7;
  std::vector<double> ctrl;
  for (int i = 0; i < rows; ++i) {
    const double rho = 0.06 * i / (rows - 1);
    for (int j = 0; j < cols; ++j) {
      const double theta = std::numbers::pi * j / (cols - 1);
      ctrl.push_back(rho * std::cos(theta));
      ctrl.push_back(rho * std::sin(theta));
      ctrl.push_back(0.04 - 8.0 * rho * rho);
    }
  }
  return BSplineSurface(3, 3, cubic_knots({1.0 / 3, 2.0 / 3}), cubic_knots({0.25, 0.5, 0.75}), rows, cols, 3, ctrl);
}

mat::MatBody default_body() {
  return mat::MatBody::fit(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json").bodies.at(0));
}

double norm3(const double* x) { return std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]); }

/// Largest |Suu|, |Suv|, |Svv| (xyz) on an n x n grid of parameters, plus the knots.
DerivativeBounds sampled_max(const BSplineSurface& s, int n) {
  std::vector<double> us, vs;
  for (int k = 0; k <= n; ++k) {
    us.push_back(static_cast<double>(k) / n);
    vs.push_back(static_cast<double>(k) / n);
  }
  // Both sides of every knot: the second derivatives jump at a double knot.
  for (double t : s.knots_u()) us.insert(us.end(), {std::max(0.0, t - 1e-12), std::min(1.0, t + 1e-12)});
  for (double t : s.knots_v()) vs.insert(vs.end(), {std::max(0.0, t - 1e-12), std::min(1.0, t + 1e-12)});
  DerivativeBounds m;
  std::array<double, 9 * 3> d{};
  for (double u : us) {
    for (double v : vs) {
      s.derivatives(u, v, 2, d, 3);
      m.suu = std::max(m.suu, norm3(&d[spline::derivative_index(2, 0, 2, 3, 0)]));
      m.suv = std::max(m.suv, norm3(&d[spline::derivative_index(1, 1, 2, 3, 0)]));
      m.svv = std::max(m.svv, norm3(&d[spline::derivative_index(0, 2, 2, 3, 0)]));
    }
  }
  return m;
}

/// Independent measurement of the deviation the bound controls: every triangle sampled at
/// the barycentric points (a, b, c) / 4, the linearly interpolated (float) position
/// against S at the linearly interpolated (u, v).
double deviation(const Mesh& m, const BSplineSurface& s) {
  double worst = 0.0;
  const int n = 4;
  for (std::size_t t = 0; t < m.triangles.size(); t += 3) {
    std::array<std::uint32_t, 3> v{m.triangles[t], m.triangles[t + 1], m.triangles[t + 2]};
    for (int a = 0; a <= n; ++a) {
      for (int b = 0; a + b <= n; ++b) {
        const std::array<double, 3> w{static_cast<double>(a) / n, static_cast<double>(b) / n,
                                      static_cast<double>(n - a - b) / n};
        double u = 0.0, vv = 0.0;
        std::array<double, 3> lin{};
        for (std::size_t k = 0; k < 3; ++k) {
          const int i = static_cast<int>(v[k]) / m.cols;
          const int j = static_cast<int>(v[k]) % m.cols;
          u += w[k] * m.us[idx(i)];
          vv += w[k] * m.vs[idx(j)];
          for (std::size_t c = 0; c < 3; ++c) lin[c] += w[k] * static_cast<double>(m.positions[v[k] * 3 + c]);
        }
        std::array<double, 3> S{};
        s.evaluate(u, vv, S, 3);
        const double d[3] = {lin[0] - S[0], lin[1] - S[1], lin[2] - S[2]};
        worst = std::max(worst, norm3(d));
      }
    }
  }
  return worst;
}

void expect_valid_mesh(const Mesh& m) {
  ASSERT_GE(m.rows, 2);
  ASSERT_GE(m.cols, 2);
  const std::size_t n = idx(m.rows) * idx(m.cols);
  EXPECT_EQ(m.vertex_count(), n);
  EXPECT_EQ(m.positions.size(), 3 * n);
  EXPECT_EQ(m.normals.size(), 3 * n);
  EXPECT_EQ(m.triangles.size(), 6 * idx(m.rows - 1) * idx(m.cols - 1));
  ASSERT_EQ(m.us.size(), idx(m.rows));
  ASSERT_EQ(m.vs.size(), idx(m.cols));
  EXPECT_TRUE(std::is_sorted(m.us.begin(), m.us.end()) && std::adjacent_find(m.us.begin(), m.us.end()) == m.us.end());
  EXPECT_TRUE(std::is_sorted(m.vs.begin(), m.vs.end()) && std::adjacent_find(m.vs.begin(), m.vs.end()) == m.vs.end());
  for (std::uint32_t t : m.triangles) EXPECT_LT(t, n);
  for (std::size_t k = 0; k < n; ++k) {
    const float* nrm = &m.normals[3 * k];
    const double len = std::sqrt(static_cast<double>(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]));
    ASSERT_TRUE(std::isfinite(len)) << "vertex " << k;
    EXPECT_NEAR(len, 1.0, 1e-6) << "vertex " << k;
    for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(m.positions[3 * k + idx(c)]));
  }
}

/// Every triangle of positive area faces the side its vertex normals point to; returns
/// the number of such triangles.
int expect_winding_agrees(const Mesh& m) {
  int checked = 0;
  for (std::size_t t = 0; t < m.triangles.size(); t += 3) {
    std::array<std::array<double, 3>, 3> p{};
    std::array<double, 3> nsum{};
    for (std::size_t k = 0; k < 3; ++k) {
      for (std::size_t c = 0; c < 3; ++c) {
        p[k][c] = static_cast<double>(m.positions[m.triangles[t + k] * 3 + c]);
        nsum[c] += static_cast<double>(m.normals[m.triangles[t + k] * 3 + c]);
      }
    }
    const std::array<double, 3> e1{p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const std::array<double, 3> e2{p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const double g[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double area2 = norm3(g);
    if (area2 < 1e-12) continue;  // collapsed at a pole
    EXPECT_GT((g[0] * nsum[0] + g[1] * nsum[1] + g[2] * nsum[2]) / area2, 0.0) << "triangle " << t / 3;
    ++checked;
  }
  return checked;
}

// ---------------------------------------------------------------------------------------
// Derivative bounds

TEST(DerivativeBounds, ExactWhereTheSecondDerivativesAreConstant) {
  // z = 0.3 u^2 - 0.2 u v + 0.05 v^2 on non-uniform knots: Suu, Suv, Svv are constant,
  // so their B-spline coefficients all equal the constant and the bound is exact.
  const auto s = quadratic_surface(0.14, 0.16, 0.3, -0.2, 0.05, {0.2, 0.55}, {0.1, 0.5, 0.6});
  const auto b = second_derivative_bounds(s);
  EXPECT_NEAR(b.suu, 0.6, 1e-12);
  EXPECT_NEAR(b.suv, 0.2, 1e-12);
  EXPECT_NEAR(b.svv, 0.1, 1e-12);
  const auto m = sampled_max(s, 40);  // the surface really has these derivatives
  EXPECT_NEAR(m.suu, 0.6, 1e-9);
  EXPECT_NEAR(m.suv, 0.2, 1e-9);
  EXPECT_NEAR(m.svv, 0.1, 1e-9);
}

TEST(DerivativeBounds, ZeroForAPlane) {
  const auto s = quadratic_surface(0.1, 0.2, 0.0, 0.0, 0.0, {0.5}, {0.3, 0.6});
  const auto b = second_derivative_bounds(s);
  EXPECT_NEAR(b.suu, 0.0, 1e-14);
  EXPECT_NEAR(b.suv, 0.0, 1e-14);
  EXPECT_NEAR(b.svv, 0.0, 1e-14);
}

TEST(DerivativeBounds, BoundTheDenselySampledMaximum) {
  std::vector<BSplineSurface> surfaces;
  for (unsigned seed = 1; seed <= 5; ++seed) surfaces.push_back(random_surface(seed));
  const auto body = default_body();
  surfaces.push_back(body.top());
  surfaces.push_back(body.bottom());
  surfaces.push_back(body.skeleton());  // 7 channels: only xyz count
  surfaces.push_back(pole_surface());
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    const auto b = second_derivative_bounds(surfaces[k]);
    const auto m = sampled_max(surfaces[k], 150);
    EXPECT_GE(b.suu, m.suu * (1 - 1e-12)) << "surface " << k;
    EXPECT_GE(b.suv, m.suv * (1 - 1e-12)) << "surface " << k;
    EXPECT_GE(b.svv, m.svv * (1 - 1e-12)) << "surface " << k;
    EXPECT_GT(m.suu + m.suv + m.svv, 0.0);
  }
}

TEST(DerivativeBounds, DegreeOneDirectionHasNoSecondDerivative) {
  // 2 x 4 control points: linear in u, cubic in v.
  const std::vector<double> ku{0, 0, 1, 1};
  const auto kv = cubic_knots({});
  std::vector<double> ctrl;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 4; ++j) ctrl.insert(ctrl.end(), {0.1 * i, 0.05 * j, 0.01 * j * j + 0.02 * i * j});
  const BSplineSurface s(1, 3, ku, kv, 2, 4, 3, ctrl);
  const auto b = second_derivative_bounds(s);
  EXPECT_EQ(b.suu, 0.0);
  const auto m = sampled_max(s, 60);
  EXPECT_GE(b.suv, m.suv * (1 - 1e-12));
  EXPECT_GE(b.svv, m.svv * (1 - 1e-12));
}

// ---------------------------------------------------------------------------------------
// Grid lines

/// The default breast's drawn top contour (refined to 4 mm spans) with a fingertip dent
/// 6 mm deep near (x, y).
BSplineSurface dented_display_top(double x, double y) {
  const auto rest = default_body();
  deform::DeformOptions o;
  o.display_span = 0.004;
  deform::DeformedBody body(rest, o);
  const contact::FootPointSearch search(rest.skeleton());
  const palpa::Vec3 above(x, y, 0.2);
  const auto foot = search.closest(rest.skeleton(), above);
  const auto c0 = contact::make_contact(rest, foot, above);
  const palpa::Vec3 q = foot.point + (c0.radius - 0.006) * c0.outward;
  const auto c = contact::make_contact(rest, search.closest(rest.skeleton(), q), q);
  EXPECT_TRUE(c.inside);
  body.press(c, q);
  return body.top();
}

/// The fewest cells of a uniform grid whose bound over the global bounds is within tol
/// (the grid the tessellation used before it followed the knots), by brute force.
long uniform_cells(const BSplineSurface& s, double tol, int limit) {
  const auto b = second_derivative_bounds(s);
  long best = -1;
  for (int nu = 1; nu <= limit; ++nu)
    for (int nv = 1; nv <= limit; ++nv)
      if (grid_error_bound(b, 1.0, 1.0, nu, nv) <= tol && (best < 0 || long{nu} * nv < best)) best = long{nu} * nv;
  return best;
}

TEST(Grid, PatchBoundsBoundTheDenselySampledDerivativesOnTheirPatch) {
  std::vector<BSplineSurface> surfaces{random_surface(2), default_body().top(), pole_surface(),
                                       dented_display_top(0.0, -0.01)};
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    const auto& s = surfaces[k];
    GridScratch g;
    patch_bounds(s, g);
    const std::size_t nv = g.knots_v.size() - 1;
    ASSERT_EQ(g.patches.size(), (g.knots_u.size() - 1) * nv);
    std::array<double, 9 * 3> d{};
    bool some_patch_tighter = false;
    const auto global = second_derivative_bounds(s);
    for (std::size_t a = 0; a + 1 < g.knots_u.size(); ++a) {
      for (std::size_t b = 0; b < nv; ++b) {
        const auto& bound = g.patches[a * nv + b];
        some_patch_tighter = some_patch_tighter || bound.suu < 0.5 * global.suu || bound.svv < 0.5 * global.svv;
        for (int i = 0; i <= 6; ++i) {
          for (int j = 0; j <= 6; ++j) {  // inside the patch, its edges approached to 1e-9
            const double u = g.knots_u[a] + (g.knots_u[a + 1] - g.knots_u[a]) * std::clamp(i / 6.0, 1e-9, 1 - 1e-9);
            const double v = g.knots_v[b] + (g.knots_v[b + 1] - g.knots_v[b]) * std::clamp(j / 6.0, 1e-9, 1 - 1e-9);
            s.derivatives(u, v, 2, d, 3);
            EXPECT_LE(norm3(&d[spline::derivative_index(2, 0, 2, 3, 0)]), bound.suu * (1 + 1e-9) + 1e-12) << k;
            EXPECT_LE(norm3(&d[spline::derivative_index(1, 1, 2, 3, 0)]), bound.suv * (1 + 1e-9) + 1e-12) << k;
            EXPECT_LE(norm3(&d[spline::derivative_index(0, 2, 2, 3, 0)]), bound.svv * (1 + 1e-9) + 1e-12) << k;
          }
        }
      }
    }
    if (k == 3) {
      EXPECT_TRUE(some_patch_tighter) << "a dent curves a few patches only";
    }
  }
}

TEST(Grid, EveryKnotIsAGridLineAndEachSpanIsCutEvenly) {
  const auto s = random_surface(4);
  Mesh m;
  TessellationOptions o;
  o.tolerance = 1e-4;
  tessellate(s, o, false, m);
  for (const auto* lines : {&m.us, &m.vs}) {
    const auto& knots = lines == &m.us ? s.knots_u() : s.knots_v();
    for (double t : knots) EXPECT_NE(std::find(lines->begin(), lines->end(), t), lines->end()) << t;
    for (std::size_t k = 1; k + 1 < lines->size(); ++k) {
      if (std::find(knots.begin(), knots.end(), (*lines)[k]) != knots.end()) continue;  // a span ends here
      EXPECT_NEAR((*lines)[k + 1] - (*lines)[k], (*lines)[k] - (*lines)[k - 1], 1e-12) << k;
    }
  }
}

TEST(Grid, ADentMakesOnlyTheLinesThroughItFine) {
  const auto s = dented_display_top(0.0, -0.01);
  const double tol = TessellationOptions{}.tolerance;
  Mesh m;
  tessellate(s, {}, false, m);
  expect_valid_mesh(m);
  EXPECT_LE(deviation(m, s), tol);
  const long uniform = uniform_cells(s, tol, 512);
  ASSERT_GT(uniform, 0);
  const long cells = long{m.rows - 1} * (m.cols - 1);
  std::printf("dented display top: %ld cells following the knots, %ld uniform\n", cells, uniform);
  EXPECT_LT(cells, uniform / 3);
  // The finest rows are where the dent is: the grid's smallest u step brackets the
  // dent's u, and far from it (a quarter of the domain away) steps are 3x wider.
  const contact::FootPointSearch search(default_body().skeleton());
  const double u_dent = search.closest(default_body().skeleton(), palpa::Vec3(0.0, -0.01, 0.2)).u;
  std::size_t finest = 0;
  for (std::size_t k = 1; k + 1 < m.us.size(); ++k)
    if (m.us[k + 1] - m.us[k] < m.us[finest + 1] - m.us[finest]) finest = k;
  EXPECT_NEAR(0.5 * (m.us[finest] + m.us[finest + 1]), u_dent, 0.06);
  for (std::size_t k = 0; k + 1 < m.us.size(); ++k) {
    if (std::abs(m.us[k] - u_dent) > 0.25) {
      EXPECT_GT(m.us[k + 1] - m.us[k], 3 * (m.us[finest + 1] - m.us[finest])) << m.us[k];
    }
  }
}

TEST(Grid, TheToleranceGoesToTheCurvedDirection) {
  // z = c u^2 on 4 x 3 spans: v is straight, so all the tolerance goes to u and v keeps
  // one segment per span.
  const auto s = quadratic_surface(0.1, 0.1, 0.5, 0.0, 0.0, {0.25, 0.5, 0.75}, {0.3, 0.6});
  Mesh m;
  TessellationOptions o;
  o.tolerance = 1e-4;
  tessellate(s, o, false, m);
  EXPECT_EQ(m.cols, 4);
  // The full budget: (1/8) h^2 |Suu| <= tol with |Suu| = 1 gives h <= sqrt(8e-4) = 0.0283,
  // 9 segments per quarter.
  EXPECT_EQ(m.rows, 4 * 9 + 1);
}

TEST(Grid, AtTheSegmentLimitTheGridIsUniform) {
  const auto s = random_surface(5);
  TessellationOptions o;
  o.tolerance = 1e-7;
  o.max_segments = 8;
  GridScratch g;
  std::vector<double> us, vs;
  const double bound = choose_grid(s, o, g, us, vs);
  ASSERT_EQ(us.size(), 9u);
  ASSERT_EQ(vs.size(), 9u);
  for (std::size_t k = 0; k < us.size(); ++k) EXPECT_NEAR(us[k], static_cast<double>(k) / 8.0, 1e-15);
  EXPECT_GT(bound, o.tolerance);
  EXPECT_DOUBLE_EQ(bound, grid_error_bound(second_derivative_bounds(s), 1.0, 1.0, 8, 8));
}

TEST(Grid, AtLeastMinSegmentsWhereTheSurfaceIsFlat) {
  const auto s = quadratic_surface(0.1, 0.2, 0.0, 0.0, 0.0, {0.5}, {});
  TessellationOptions o;
  o.min_segments = 5;
  Mesh m;
  tessellate(s, o, false, m);
  EXPECT_EQ(m.rows, 6);
  EXPECT_EQ(m.cols, 6);
  EXPECT_LT(deviation(m, s), 1e-7);  // float rounding only
}

TEST(Grid, InvalidOptionsThrow) {
  const auto s = pole_surface();
  GridScratch g;
  std::vector<double> us, vs;
  TessellationOptions o;
  o.tolerance = 0.0;
  EXPECT_THROW(choose_grid(s, o, g, us, vs), std::invalid_argument);
  o.tolerance = std::nan("");
  EXPECT_THROW(choose_grid(s, o, g, us, vs), std::invalid_argument);
  o = {};
  o.min_segments = 0;
  EXPECT_THROW(choose_grid(s, o, g, us, vs), std::invalid_argument);
  o = {};
  o.max_segments = 1;
  EXPECT_THROW(choose_grid(s, o, g, us, vs), std::invalid_argument);
  Mesh m;
  o = {};
  o.tolerance = -1.0;
  EXPECT_THROW(tessellate(s, o, false, m), std::invalid_argument);
  o.tolerance = std::nan("");
  EXPECT_THROW(tessellate(s, o, false, m), std::invalid_argument);
}

TEST(Grid, ScreenTolerance) {
  EXPECT_DOUBLE_EQ(object_tolerance_from_screen(0.5, 2500.0), 2e-4);
  EXPECT_THROW(object_tolerance_from_screen(0.0, 100.0), std::invalid_argument);
  EXPECT_THROW(object_tolerance_from_screen(1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(object_tolerance_from_screen(1.0, INFINITY), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------
// The mesh against the surface

TEST(Tessellation, DeviationStaysWithinTheToleranceAndShrinksWithIt) {
  const auto body = default_body();
  struct Case {
    const char* name;
    BSplineSurface s;
    double finest;  // smallest tolerance tried (keeps the test quick under sanitizers)
  };
  const std::vector<Case> surfaces{
      {"default top", body.top(), 1e-5},
      {"default bottom", body.bottom(), 1e-5},
      {"quadratic", quadratic_surface(0.14, 0.16, 0.3, -0.2, 0.05, {0.2, 0.55}, {0.1, 0.5, 0.6}), 1e-5},
      {"random", random_surface(3), 1e-4},
      {"pole", pole_surface(), 1e-4}};
  for (const auto& [name, s, finest] : surfaces) {
    double previous = INFINITY;
    double first = 0.0;
    for (double tol : {1e-2, 1e-3, 2e-4, 1e-4, 1e-5}) {
      if (tol < finest) break;
      TessellationOptions o;
      o.tolerance = tol;
      Mesh m;
      tessellate(s, o, false, m);
      expect_valid_mesh(m);
      ASSERT_LE(m.rows, 512) << name << ": keep the test surfaces within reach of the tolerances";
      ASSERT_LE(m.cols, 512) << name;
      const double d = deviation(m, s);
      EXPECT_LE(d, tol) << name << " tol " << tol << " grid " << m.rows << " x " << m.cols;
      EXPECT_LE(m.error_bound, tol) << name;
      EXPECT_LE(d, m.error_bound) << name;
      EXPECT_LE(d, previous * (1 + 1e-9)) << name << " tol " << tol;  // never worse for a smaller tolerance
      if (tol == 2e-4) {
        EXPECT_NEAR(max_parametric_deviation(m, s, 4), d, 1e-15) << name;
      }
      if (tol == 1e-2) first = d;
      previous = d;
    }
    EXPECT_LT(previous, first / 20) << name;  // 2-3 decades of tolerance buy more than 1 of deviation
  }
}

TEST(Tessellation, TheBoundIsTightForAConstantSecondDerivative) {
  // z = c u^2: linear interpolation over [u, u + h] misses by c h^2 / 4 at the midpoint,
  // exactly the bound (1/8) h^2 |Suu|. The mesh should use most of the tolerance.
  const auto s = quadratic_surface(0.1, 0.1, 0.5, 0.0, 0.0, {0.3}, {0.6});
  for (double tol : {1e-3, 1e-4, 1e-5}) {
    TessellationOptions o;
    o.tolerance = tol;
    Mesh m;
    tessellate(s, o, false, m);
    const double d = deviation(m, s);
    EXPECT_LE(d, tol);
    EXPECT_GT(d, 0.5 * tol) << "grid " << m.rows << " x " << m.cols;
    EXPECT_EQ(m.cols, o.min_segments + 1);  // straight along v
  }
}

TEST(Tessellation, VerticesLieOnTheSurfaceAtTheirGridParameters) {
  const auto s = random_surface(7);
  Mesh m;
  tessellate(s, {}, false, m);
  expect_valid_mesh(m);
  std::array<double, 3> S{};
  std::array<double, 3 * 4> d{};
  for (int i = 0; i < m.rows; ++i) {
    for (int j = 0; j < m.cols; ++j) {
      const std::size_t k = idx(i * m.cols + j);
      s.evaluate(m.us[idx(i)], m.vs[idx(j)], S, 3);
      for (std::size_t c = 0; c < 3; ++c)
        EXPECT_NEAR(static_cast<double>(m.positions[3 * k + c]), S[c], 1e-8) << i << " " << j;
      s.derivatives(m.us[idx(i)], m.vs[idx(j)], 1, d, 3);
      const double* su = &d[spline::derivative_index(1, 0, 1, 3, 0)];
      const double* sv = &d[spline::derivative_index(0, 1, 1, 3, 0)];
      const double n[3] = {su[1] * sv[2] - su[2] * sv[1], su[2] * sv[0] - su[0] * sv[2], su[0] * sv[1] - su[1] * sv[0]};
      const double len = norm3(n);
      for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(static_cast<double>(m.normals[3 * k + c]), n[c] / len, 1e-6);
    }
  }
}

TEST(Tessellation, FlatBodyNormalsPointOutwardAndWindingAgrees) {
  const auto body = mat::MatBody::fit(test::flat_body(9, 9));
  for (double tol : {1e-3, 2e-4, 1e-5}) {
    TessellationOptions o;
    o.tolerance = tol;
    Mesh top, bottom;
    tessellate(body.top(), o, false, top);
    tessellate(body.bottom(), o, true, bottom);
    expect_valid_mesh(top);
    expect_valid_mesh(bottom);
    EXPECT_FALSE(top.outward_is_minus_normal);
    EXPECT_TRUE(bottom.outward_is_minus_normal);
    // The skeleton is the plane z = 0 with N = +z: the top's outside is up, the bottom's down.
    for (std::size_t k = 0; k < top.vertex_count(); ++k) EXPECT_GT(top.normals[3 * k + 2], 0.0f) << k;
    for (std::size_t k = 0; k < bottom.vertex_count(); ++k) EXPECT_LT(bottom.normals[3 * k + 2], 0.0f) << k;
    EXPECT_GT(expect_winding_agrees(top), 0);
    EXPECT_GT(expect_winding_agrees(bottom), 0);
    // The same grid, opposite winding: every bottom triangle is a top triangle reversed.
    if (top.rows == bottom.rows && top.cols == bottom.cols) {
      for (std::size_t t = 0; t < top.triangles.size(); t += 3) {
        EXPECT_EQ(top.triangles[t], bottom.triangles[t]);
        EXPECT_EQ(top.triangles[t + 1], bottom.triangles[t + 2]);
        EXPECT_EQ(top.triangles[t + 2], bottom.triangles[t + 1]);
      }
    }
  }
}

TEST(Tessellation, DefaultCaseWindingAgreesWithTheNormals) {
  const auto body = default_body();
  for (double tol : {1e-2, 2e-4}) {
    TessellationOptions o;
    o.tolerance = tol;
    Mesh top, bottom;
    tessellate(body.top(), o, false, top);
    tessellate(body.bottom(), o, true, bottom);
    expect_valid_mesh(top);
    expect_valid_mesh(bottom);
    EXPECT_GT(expect_winding_agrees(top), 0);
    EXPECT_GT(expect_winding_agrees(bottom), 0);
  }
}

TEST(Tessellation, PoleRowGivesFiniteNormalsAlongTheLimitDirection) {
  const auto s = pole_surface();
  for (bool flip : {false, true}) {
    Mesh m;
    TessellationOptions o;
    o.tolerance = 1e-4;
    tessellate(s, o, flip, m);
    expect_valid_mesh(m);
    // Row 0 is the apex: one point, Sv = 0. Its normals are the limit from the interior,
    // which for this dome is about +z (-z when flipped), and agree with row 1's.
    const float sign = flip ? -1.0f : 1.0f;
    for (int j = 0; j < m.cols; ++j) {
      const float* pole = &m.normals[idx(j) * 3];
      const float* next = &m.normals[idx(m.cols + j) * 3];
      EXPECT_GT(sign * pole[2], 0.99f) << j;
      EXPECT_GT(pole[0] * next[0] + pole[1] * next[1] + pole[2] * next[2], 0.99f) << j;
    }
    EXPECT_GT(expect_winding_agrees(m), 0);
  }
}

TEST(Tessellation, FullyCollapsedSurfaceStillHasUnitNormals) {
  // Every control point the same: no tangent anywhere, no limit direction.
  std::vector<double> ctrl;
  for (int k = 0; k < 16; ++k) ctrl.insert(ctrl.end(), {0.01, 0.02, 0.03});
  const BSplineSurface s(3, 3, cubic_knots({}), cubic_knots({}), 4, 4, 3, ctrl);
  Mesh m;
  tessellate(s, {}, true, m);
  expect_valid_mesh(m);
  EXPECT_EQ(m.rows, 3);  // min_segments + 1
}

TEST(Tessellation, ReusesStorageAndRebuildsIndicesOnlyWhenTheGridChanges) {
  const auto body = default_body();
  TessellationOptions o;
  Mesh m;
  tessellate(body.top(), o, false, m);
  const auto* tri = m.triangles.data();
  const auto* pos = m.positions.data();
  const auto triangles = m.triangles;
  tessellate(body.top(), o, false, m);
  EXPECT_EQ(m.triangles.data(), tri);
  EXPECT_EQ(m.positions.data(), pos);
  EXPECT_EQ(m.triangles, triangles);
  // A finer grid, then the original again: the same indices as the first time.
  o.tolerance = 1e-5;
  tessellate(body.top(), o, false, m);
  EXPECT_GT(m.triangles.size(), triangles.size());
  o.tolerance = TessellationOptions{}.tolerance;
  tessellate(body.top(), o, false, m);
  EXPECT_EQ(m.triangles, triangles);
  // Same grid, other side: the winding is rebuilt.
  tessellate(body.top(), o, true, m);
  EXPECT_NE(m.triangles, triangles);
  EXPECT_EQ(m.triangles.size(), triangles.size());
}

// ---------------------------------------------------------------------------------------
// Only bodies that changed

TEST(BodyMeshes, ReTessellatesOnlyWhenTheBodyOrTheOptionsChange) {
  const auto rest = mat::MatBody::fit(test::flat_body(9, 9));
  deform::DeformedBody body(rest);
  BodyMeshes meshes;
  TessellationOptions o;
  EXPECT_TRUE(meshes.update(body, o));  // first call
  expect_valid_mesh(meshes.top());
  expect_valid_mesh(meshes.bottom());
  EXPECT_FALSE(meshes.top().outward_is_minus_normal);
  EXPECT_TRUE(meshes.bottom().outward_is_minus_normal);
  EXPECT_FALSE(meshes.update(body, o));
  EXPECT_FALSE(meshes.update(body, o));

  // Press the top 5 mm in at the centre: the version changes, the meshes follow.
  const contact::FootPointSearch search(rest.skeleton());
  const palpa::Vec3 q(0.0, 0.0, 0.015);
  const auto c = contact::make_contact(rest, search.closest(rest.skeleton(), q), q);
  ASSERT_TRUE(c.inside);
  const auto before = body.version();
  body.press(c, q);
  ASSERT_NE(body.version(), before);
  EXPECT_TRUE(meshes.update(body, o));
  EXPECT_FALSE(meshes.update(body, o));
  Mesh direct;
  tessellate(body.top(), o, false, direct);
  EXPECT_EQ(meshes.top().positions, direct.positions);
  EXPECT_EQ(meshes.top().normals, direct.normals);
  // The pressed top passes (near) the probe: the mesh shows the dent.
  float lowest_centre = 1.0f;
  for (std::size_t k = 0; k < direct.vertex_count(); ++k) {
    const float* p = &direct.positions[3 * k];
    if (std::abs(p[0]) < 0.01f && std::abs(p[1]) < 0.01f) lowest_centre = std::min(lowest_centre, p[2]);
  }
  EXPECT_LT(lowest_centre, 0.0175f);

  body.step(1e-3);  // a static hold changes nothing
  EXPECT_FALSE(meshes.update(body, o));
  body.release();
  body.step(1e-3);  // springing back changes the surfaces
  EXPECT_TRUE(meshes.update(body, o));
  EXPECT_FALSE(meshes.update(body, o));

  o.tolerance = 1e-4;  // other options
  EXPECT_TRUE(meshes.update(body, o));
  EXPECT_FALSE(meshes.update(body, o));

  deform::DeformedBody other(rest);  // another body
  EXPECT_TRUE(meshes.update(other, o));
  EXPECT_FALSE(meshes.update(other, o));
}

}  // namespace
}  // namespace palpa::render
