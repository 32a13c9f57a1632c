// Piegl's least-norm control-point modification (paper section 3.2, influence_at and
// displace): the surface point lands exactly, the weights are N_k N_l / sum (N N)^2 over all
// or a reduced window of basis products. Truths: basis functions by the Cox-de Boor
// recursion here, on uniform, non-uniform, high-degree, bilinear and fitted surfaces;
// partition of unity and local support; hand-computed amplification ratios on uniform
// cubic knots.
#include "palpa/deform/control_point_modification.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "deform_test_support.hpp"

namespace palpa::deform {
namespace {

using namespace deform_test;

std::vector<double> clamped_knots(int p, const std::vector<double>& interior) {
  std::vector<double> k(static_cast<std::size_t>(p + 1), 0.0);
  k.insert(k.end(), interior.begin(), interior.end());
  k.insert(k.end(), static_cast<std::size_t>(p + 1), 1.0);
  return k;
}

std::vector<double> uniform_interior(int spans) {
  std::vector<double> v;
  for (int i = 1; i < spans; ++i) v.push_back(i / static_cast<double>(spans));
  return v;
}

BSplineSurface make_surface(int p, int q, const std::vector<double>& interior_u, const std::vector<double>& interior_v,
                            int dim, unsigned seed) {
  const std::vector<double> ku = clamped_knots(p, interior_u);
  const std::vector<double> kv = clamped_knots(q, interior_v);
  const int rows = static_cast<int>(ku.size()) - p - 1;
  const int cols = static_cast<int>(kv.size()) - q - 1;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> noise(-0.01, 0.01);
  std::vector<double> control;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j)
      for (int c = 0; c < dim; ++c) {
        const double s = i / static_cast<double>(rows - 1);
        const double t = j / static_cast<double>(cols - 1);
        const double base = c == 0 ? 0.1 * s : c == 1 ? 0.12 * t : 0.02 * std::sin(3 * s + c) * std::cos(2 * t);
        control.push_back(base + noise(rng));
      }
  return BSplineSurface(p, q, ku, kv, rows, cols, dim, control);
}

// Dense weights over all control points from an Influence (zero outside its window).
std::vector<double> dense(const Influence& inf, int rows, int cols) {
  std::vector<double> w(static_cast<std::size_t>(rows * cols), 0.0);
  for (int a = 0; a < inf.rows; ++a)
    for (int b = 0; b < inf.cols; ++b)
      w[static_cast<std::size_t>((inf.i0 + a) * cols + inf.j0 + b)] = inf.weight[static_cast<std::size_t>(a * inf.cols + b)];
  return w;
}

// The window of `width` consecutive non-zero basis functions with the largest sum (and
// whether the choice is clear: unique by a margin, and the same by sum of squares).
struct Window {
  int first = 0;
  bool clear = false;
};

Window best_window(const std::vector<double>& nb, int width) {
  int lo = 0;  // first non-zero index
  while (nb[static_cast<std::size_t>(lo)] == 0.0) ++lo;
  int hi = static_cast<int>(nb.size()) - 1;
  while (nb[static_cast<std::size_t>(hi)] == 0.0) --hi;
  struct Score {
    double sum, sq;
    int first;
  };
  std::vector<Score> scores;
  for (int f = lo; f + width - 1 <= hi; ++f) {
    double s1 = 0, s2 = 0;
    for (int i = f; i < f + width; ++i) {
      s1 += nb[static_cast<std::size_t>(i)];
      s2 += nb[static_cast<std::size_t>(i)] * nb[static_cast<std::size_t>(i)];
    }
    scores.push_back({s1, s2, f});
  }
  Window w;
  if (scores.empty()) return w;
  auto by_sum = scores;
  std::sort(by_sum.begin(), by_sum.end(), [](const Score& a, const Score& b) { return a.sum > b.sum; });
  auto by_sq = scores;
  std::sort(by_sq.begin(), by_sq.end(), [](const Score& a, const Score& b) { return a.sq > b.sq; });
  w.first = by_sum[0].first;
  w.clear = by_sum[0].first == by_sq[0].first &&
            (scores.size() == 1 || (by_sum[0].sum - by_sum[1].sum > 1e-6 && by_sq[0].sq - by_sq[1].sq > 1e-6));
  return w;
}

struct NamedSurface {
  std::string name;
  BSplineSurface surface;
};

std::vector<NamedSurface> cpm_surfaces() {
  std::vector<NamedSurface> s;
  s.push_back({"uniform bicubic", make_surface(3, 3, uniform_interior(10), uniform_interior(8), 3, 1)});
  s.push_back({"cubic x quadratic, non-uniform",
               make_surface(3, 2, {0.05, 0.12, 0.3, 0.31, 0.5, 0.77, 0.9}, {0.1, 0.2, 0.25, 0.4, 0.6, 0.8}, 4, 2)});
  s.push_back({"quintic x quartic",
               make_surface(5, 4, uniform_interior(14), {0.05, 0.1, 0.2, 0.3, 0.35, 0.5, 0.6, 0.7, 0.75, 0.9}, 3, 3)});
  s.push_back({"bilinear", make_surface(1, 1, uniform_interior(6), uniform_interior(5), 3, 4)});
  // A fitted skeleton (7 channels, knots by averaging on chord-length parameters).
  mat::BodyGrid g = test::flat_body(12, 14, 0.05, 0.02, 300.0);
  for (std::size_t i = 0; i < g.medial.size(); ++i) g.medial[i][2] = 0.01 * std::sin(40.0 * g.medial[i][0] + 30.0 * g.medial[i][1]);
  static const MatBody body = MatBody::fit(g);
  s.push_back({"fitted skeleton", body.skeleton()});
  return s;
}

std::vector<std::array<double, 2>> cpm_params(const BSplineSurface& s, unsigned seed, int random_count) {
  std::vector<std::array<double, 2>> uv = {{0.0, 0.0}, {1.0, 1.0}, {0.0, 0.63}, {1.0, 0.21}, {0.37, 1.0}};
  // knots and mid-spans in each direction
  for (std::size_t i = 0; i + 1 < s.knots_u().size(); ++i) {
    const double a = s.knots_u()[i];
    const double b = s.knots_u()[i + 1];
    if (b <= a) continue;
    const double v = s.knots_v()[std::min(s.knots_v().size() - 1, i + 1)];
    uv.push_back({a, std::clamp(v, 0.0, 1.0)});
    uv.push_back({(a + b) / 2, 0.47});
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int n = 0; n < random_count; ++n) uv.push_back({unit(rng), unit(rng)});
  return uv;
}

// The default window is all (p+1) x (q+1) non-zero products, weights N_k N_l / sum (N N)^2.
TEST(ControlPointModification, DefaultWeightsAreLeastNormOverAllNonZeroBasisProducts) {
  for (const NamedSurface& ns : cpm_surfaces()) {
    const BSplineSurface& s = ns.surface;
    const int p = s.degree_u(), q = s.degree_v();
    for (const auto& [u, v] : cpm_params(s, 11, 40)) {
      for (int pu : {0, p + 2}) {  // 0 and more than p+1 both mean "all"
        const Influence inf = influence_at(s, u, v, pu, pu == 0 ? 0 : q + 2);
        ASSERT_EQ(inf.rows, p + 1) << ns.name << " u=" << u << " v=" << v;
        ASSERT_EQ(inf.cols, q + 1) << ns.name;
        ASSERT_GE(inf.i0, 0);
        ASSERT_GE(inf.j0, 0);
        ASSERT_LE(inf.i0 + inf.rows, s.rows());
        ASSERT_LE(inf.j0 + inf.cols, s.cols());
        const std::vector<double> nu = all_basis(s.knots_u(), p, u);
        const std::vector<double> nv = all_basis(s.knots_v(), q, v);
        double su = 0, sv = 0;
        for (double x : nu) su += x * x;
        for (double x : nv) sv += x * x;
        const std::vector<double> got = dense(inf, s.rows(), s.cols());
        for (int i = 0; i < s.rows(); ++i)
          for (int j = 0; j < s.cols(); ++j) {
            const double expected = nu[static_cast<std::size_t>(i)] * nv[static_cast<std::size_t>(j)] / (su * sv);
            EXPECT_NEAR(got[static_cast<std::size_t>(i * s.cols() + j)], expected, 1e-12 * (1 + expected))
                << ns.name << " u=" << u << " v=" << v << " control (" << i << ", " << j << ")";
          }
      }
    }
  }
}

// S(u, v) moves by exactly D for every window size; channels outside [first, first+|D|)
// and control points outside the window do not change at all.
TEST(ControlPointModification, LandsExactlyForEveryWindowAndTouchesNothingElse) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const NamedSurface& ns : cpm_surfaces()) {
    const BSplineSurface& rest = ns.surface;
    const int p = rest.degree_u(), q = rest.degree_v();
    for (const auto& [u, v] : cpm_params(rest, 12, 15)) {
      for (int pu = 1; pu <= p + 1; ++pu) {
        for (int pv = 1; pv <= q + 1; ++pv) {
          for (int first : {0, 1}) {
            const int count = std::min(3, rest.dim() - first);
            std::vector<double> d(static_cast<std::size_t>(count));
            for (double& x : d) x = 0.01 * unit(rng);
            BSplineSurface s = rest;
            const Influence inf = influence_at(s, u, v, pu, pv);
            ASSERT_EQ(inf.rows, pu) << ns.name;
            ASSERT_EQ(inf.cols, pv) << ns.name;
            displace(s, inf, d, first);
            const std::vector<double> before = eval_all(rest, u, v);
            const std::vector<double> after = eval_all(s, u, v);
            for (int c = 0; c < rest.dim(); ++c) {
              const auto cc = static_cast<std::size_t>(c);
              const double expected_move = (c >= first && c < first + count) ? d[static_cast<std::size_t>(c - first)] : 0.0;
              EXPECT_NEAR(after[cc] - before[cc], expected_move, 1e-12 * norm(d) + 1e-15 * std::fabs(before[cc]))
                  << ns.name << " u=" << u << " v=" << v << " window " << pu << "x" << pv << " channel " << c;
            }
            for (int i = 0; i < rest.rows(); ++i)
              for (int j = 0; j < rest.cols(); ++j) {
                const bool in = i >= inf.i0 && i < inf.i0 + inf.rows && j >= inf.j0 && j < inf.j0 + inf.cols;
                const auto a = rest.control_point(i, j);
                const auto b = s.control_point(i, j);
                for (int c = 0; c < rest.dim(); ++c) {
                  const auto cc = static_cast<std::size_t>(c);
                  if (!in || c < first || c >= first + count) {
                    ASSERT_EQ(a[cc], b[cc]) << ns.name << " untouched control (" << i << ", " << j << ") channel " << c;
                  }
                }
              }
          }
        }
      }
    }
  }
}

// Fewer points than (p+1) x (q+1): the window of the largest basis products, with the
// weights renormalized over it. Checked where the choice is unambiguous.
TEST(ControlPointModification, ReducedWindowIsTheMostInfluentialOne) {
  int checked = 0;
  for (const NamedSurface& ns : cpm_surfaces()) {
    const BSplineSurface& s = ns.surface;
    const int p = s.degree_u(), q = s.degree_v();
    for (const auto& [u, v] : cpm_params(s, 13, 60)) {
      const std::vector<double> nu = all_basis(s.knots_u(), p, u);
      const std::vector<double> nv = all_basis(s.knots_v(), q, v);
      int nonzero_u = 0, nonzero_v = 0;
      for (double x : nu) nonzero_u += x > 0 ? 1 : 0;
      for (double x : nv) nonzero_v += x > 0 ? 1 : 0;
      if (nonzero_u != p + 1 || nonzero_v != q + 1) continue;  // on a knot: ties, skip
      for (int pu = 1; pu <= p; ++pu) {
        for (int pv = 1; pv <= q; ++pv) {
          const Window wu = best_window(nu, pu);
          const Window wv = best_window(nv, pv);
          if (!wu.clear || !wv.clear) continue;
          const Influence inf = influence_at(s, u, v, pu, pv);
          EXPECT_EQ(inf.i0, wu.first) << ns.name << " u=" << u << " window " << pu;
          EXPECT_EQ(inf.j0, wv.first) << ns.name << " v=" << v << " window " << pv;
          if (inf.i0 != wu.first || inf.j0 != wv.first) continue;
          double su = 0, sv = 0;
          for (int a = 0; a < pu; ++a) su += nu[static_cast<std::size_t>(wu.first + a)] * nu[static_cast<std::size_t>(wu.first + a)];
          for (int b = 0; b < pv; ++b) sv += nv[static_cast<std::size_t>(wv.first + b)] * nv[static_cast<std::size_t>(wv.first + b)];
          for (int a = 0; a < pu; ++a)
            for (int b = 0; b < pv; ++b) {
              const double expected =
                  nu[static_cast<std::size_t>(wu.first + a)] * nv[static_cast<std::size_t>(wv.first + b)] / (su * sv);
              EXPECT_NEAR(inf.weight[static_cast<std::size_t>(a * pv + b)], expected, 1e-12 * (1 + expected))
                  << ns.name << " u=" << u << " v=" << v;
            }
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 200);
}

// Partition of unity: no point moves more than the largest control-point change, and
// points whose basis functions miss the window (more than p+1 spans away) do not move.
TEST(ControlPointModification, OtherPointsBoundedAndOutsideSupportStill) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  constexpr int samples = kLoopDivisor == 1 ? 40 : 20;
  for (const NamedSurface& ns : cpm_surfaces()) {
    const BSplineSurface& rest = ns.surface;
    const int p = rest.degree_u(), q = rest.degree_v();
    // Sample parameters, their basis functions and the rest surface there, once.
    std::vector<double> ts;
    for (int a = 0; a <= samples; ++a) ts.push_back(a / static_cast<double>(samples));
    std::vector<std::vector<double>> nus, nvs;
    for (double t : ts) {
      nus.push_back(all_basis(rest.knots_u(), p, t));
      nvs.push_back(all_basis(rest.knots_v(), q, t));
    }
    std::vector<std::vector<double>> rest_at;
    for (double uu : ts)
      for (double vv : ts) rest_at.push_back(eval_all(rest, uu, vv));
    std::vector<double> moved(static_cast<std::size_t>(rest.dim()));
    int still = 0;
    for (const auto& [u, v] : cpm_params(rest, 14, 6)) {
      for (int pu : {0, std::max(1, p - 1)}) {
        BSplineSurface s = rest;
        std::vector<double> d = {0.01 * unit(rng), 0.01 * unit(rng), 0.01 * unit(rng)};
        const Influence inf = influence_at(s, u, v, pu, pu == 0 ? 0 : std::max(1, q - 1));
        displace(s, inf, d, 0);
        double max_dp = 0.0;
        for (int i = 0; i < rest.rows(); ++i)
          for (int j = 0; j < rest.cols(); ++j) {
            std::array<double, 3> dp{};
            for (std::size_t c = 0; c < 3; ++c) dp[c] = s.control_point(i, j)[c] - rest.control_point(i, j)[c];
            max_dp = std::max(max_dp, norm(dp));
          }
        for (std::size_t a = 0; a < ts.size(); ++a) {
          // Does any non-zero basis function at ts[a] (ts[b]) belong to the window?
          bool touches_u = false;
          for (int i = inf.i0; i < inf.i0 + inf.rows; ++i) touches_u = touches_u || nus[a][static_cast<std::size_t>(i)] != 0.0;
          for (std::size_t b = 0; b < ts.size(); ++b) {
            bool touches_v = false;
            for (int j = inf.j0; j < inf.j0 + inf.cols; ++j) touches_v = touches_v || nvs[b][static_cast<std::size_t>(j)] != 0.0;
            s.evaluate(ts[a], ts[b], moved);
            const std::vector<double>& s0 = rest_at[a * ts.size() + b];
            const std::array<double, 3> move = {moved[0] - s0[0], moved[1] - s0[1], moved[2] - s0[2]};
            ASSERT_LE(norm(move), max_dp * (1 + 1e-12) + 1e-15) << ns.name << " at " << ts[a] << ", " << ts[b];
            if (!(touches_u && touches_v)) {
              for (std::size_t c = 0; c < s0.size(); ++c) ASSERT_EQ(moved[c], s0[c]) << ns.name << " at " << ts[a] << ", " << ts[b];
              ++still;
            }
          }
        }
      }
    }
    EXPECT_GT(still, samples * samples / 8) << ns.name;
  }
}

// Uniform cubic knots, all 16 points: max|dP|/|D| = (23/48)^2 / (1060/2304)^2
// mid-span (basis 1/48, 23/48, 23/48, 1/48) and (2/3)^2 / (1/2)^2 = 16/9 at a knot.
TEST(ControlPointModification, UniformCubicAmplificationRatios) {
  const BSplineSurface rest = make_surface(3, 3, uniform_interior(10), uniform_interior(10), 3, 9);
  const double mid_basis = 23.0 / 48.0;
  const double mid_sq = 1060.0 / 2304.0;
  struct Case {
    double u, v, ratio;
  };
  for (const Case c : {Case{0.45, 0.55, mid_basis * mid_basis / (mid_sq * mid_sq)}, Case{0.5, 0.4, 16.0 / 9.0}}) {
    BSplineSurface s = rest;
    const std::vector<double> d = {0.003, -0.004, 0.012};
    displace(s, influence_at(s, c.u, c.v), d, 0);
    double max_dp = 0.0;
    for (int i = 0; i < rest.rows(); ++i)
      for (int j = 0; j < rest.cols(); ++j) {
        std::array<double, 3> dp{};
        for (std::size_t k = 0; k < 3; ++k) dp[k] = s.control_point(i, j)[k] - rest.control_point(i, j)[k];
        max_dp = std::max(max_dp, norm(dp));
      }
    EXPECT_NEAR(max_dp / norm(d), c.ratio, 1e-9) << "u=" << c.u << " v=" << c.v;
  }
  EXPECT_NEAR(mid_basis * mid_basis / (mid_sq * mid_sq), 1.0847, 1e-4);  // 1.09 mid-span
}

}  // namespace
}  // namespace palpa::deform
