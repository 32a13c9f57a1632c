// The exact oscillator of each control point (paper section 3.3, OscillatorStep::exact) and
// the damping helpers. Truths: textbook closed forms per regime written out in double, a
// long-double reference (itself checked first against a long-double RK4) over an extreme
// grid of stiffness, mass, damping and time step, the semigroup property, and energy that
// never grows (conserved without damping, also over 10^6 steps).
#include "palpa/deform/oscillator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "deform_test_support.hpp"

namespace palpa::deform {
namespace {

using namespace deform_test;

// Classical RK4 in long double with n substeps: a check of the closed forms of reference().
State rk4(LD k, LD b, LD m, LD t, LD x0, LD v0, int n) {
  const LD h = t / n;
  LD x = x0;
  LD v = v0;
  const auto acc = [&](LD xx, LD vv) { return -(k * xx + b * vv) / m; };
  for (int i = 0; i < n; ++i) {
    const LD k1x = v, k1v = acc(x, v);
    const LD k2x = v + h / 2 * k1v, k2v = acc(x + h / 2 * k1x, v + h / 2 * k1v);
    const LD k3x = v + h / 2 * k2v, k3v = acc(x + h / 2 * k2x, v + h / 2 * k2v);
    const LD k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v);
    x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
  }
  return {x, v};
}

struct Map {
  LD xx, xv, vx, vv;
};

Map reference_map(LD k, LD b, LD m, LD dt) {
  const State c1 = reference(k, b, m, dt, 1, 0);
  const State c2 = reference(k, b, m, dt, 0, 1);
  return {c1.x, c2.x, c1.v, c2.v};
}

Map to_map(const OscillatorStep& s) { return {s.xx, s.xv, s.vx, s.vv}; }

// The map in scaled coordinates, where entries are O(1) in every regime: (sqrt(k) x,
// sqrt(m) v) for k > 0 (the energy norm, in which the map is a contraction, so every
// scaled entry is at most 1 in magnitude), (x / dt, v) for k = 0.
Map scaled(const Map& a, LD k, LD m, LD dt) {
  if (k > 0) {
    const LD w0 = std::sqrt(k / m);
    return {a.xx, a.xv * w0, a.vx / w0, a.vv};
  }
  if (dt > 0) return {a.xx, a.xv / dt, a.vx * dt, a.vv};
  return a;
}

LD map_distance(const Map& a, const Map& b) {
  return std::max({std::fabs(a.xx - b.xx), std::fabs(a.xv - b.xv), std::fabs(a.vx - b.vx), std::fabs(a.vv - b.vv)});
}

// Phase swept in a step (radians) for underdamped oscillators: double round-off in the
// frequency costs about 1e-16 of it, an error no implementation can avoid.
LD phase(LD k, LD b, LD m, LD dt) {
  if (k <= 0) return 0;
  const LD a = b / (2 * m);
  const LD disc = a * a - k / m;
  return disc < 0 ? std::sqrt(-disc) * dt : 0;
}

// ---------------------------------------------------------------------------------------
// The reference itself, before anything is measured against it.

TEST(OscillatorReference, ClosedFormsAgreeWithLongDoubleRk4) {
  struct Case {
    LD k, b, m, t;
  };
  const std::vector<Case> cases = {
      {1, 0.1L, 1, 2},      // underdamped
      {1, 2, 1, 1.5L},      // critical
      {1, 2.0001L, 1, 1},   // just overdamped (series branch)
      {1, 1.9999L, 1, 1},   // just underdamped (series branch)
      {1, 10, 1, 3},        // overdamped, two exponentials
      {400, 0.6L, 1e-3L, 0.02L},
      {0, 0.5L, 2, 1},      // k = 0
      {0, 0, 1, 0.7L},      // free particle
      {4, 0, 1, 5},         // undamped
  };
  for (const Case& c : cases) {
    for (const auto& [x0, v0] : std::vector<std::pair<LD, LD>>{{1, 0}, {0, 1}, {0.3L, -0.8L}}) {
      const State a = reference(c.k, c.b, c.m, c.t, x0, v0);
      const State r = rk4(c.k, c.b, c.m, c.t, x0, v0, 40000);
      EXPECT_NEAR(static_cast<double>(a.x), static_cast<double>(r.x), 1e-12)
          << params(static_cast<double>(c.k), static_cast<double>(c.b), static_cast<double>(c.m), static_cast<double>(c.t));
      EXPECT_NEAR(static_cast<double>(a.v), static_cast<double>(r.v), 1e-12)
          << params(static_cast<double>(c.k), static_cast<double>(c.b), static_cast<double>(c.m), static_cast<double>(c.t));
    }
  }
}

// =======================================================================================
// OscillatorStep::exact

TEST(OscillatorStep, ZeroStepIsIdentity) {
  for (double k : kGridK)
    for (double m : kGridM)
      for (double b : kGridB) {
        const OscillatorStep s = OscillatorStep::exact(k, b, m, 0.0);
        EXPECT_EQ(s.xx, 1.0) << params(k, b, m, 0.0);
        EXPECT_EQ(s.xv, 0.0) << params(k, b, m, 0.0);
        EXPECT_EQ(s.vx, 0.0) << params(k, b, m, 0.0);
        EXPECT_EQ(s.vv, 1.0) << params(k, b, m, 0.0);
      }
}

TEST(OscillatorStep, ApplyIsTheMatrixProduct) {
  OscillatorStep s;
  s.xx = 0.5;
  s.xv = 2.0;
  s.vx = -3.0;
  s.vv = 0.25;
  double x = 1.0;
  double v = 4.0;
  s.apply(x, v);
  EXPECT_DOUBLE_EQ(x, 0.5 * 1.0 + 2.0 * 4.0);
  EXPECT_DOUBLE_EQ(v, -3.0 * 1.0 + 0.25 * 4.0);
}

// Textbook closed forms per regime, written out in double here (not through reference()).
TEST(OscillatorStep, MatchesTextbookClosedFormsPerRegime) {
  const double x0 = 0.7;
  const double v0 = -1.3;
  const auto check = [&](double k, double b, double m, double dt, double x_true, double v_true) {
    const OscillatorStep s = OscillatorStep::exact(k, b, m, dt);
    double x = x0;
    double v = v0;
    s.apply(x, v);
    EXPECT_NEAR(x, x_true, 1e-13 * (1 + std::fabs(x_true))) << params(k, b, m, dt);
    EXPECT_NEAR(v, v_true, 1e-13 * (1 + std::fabs(v_true))) << params(k, b, m, dt);
  };
  {  // underdamped: x = e^{-at}(x0 cos wd t + (v0 + a x0)/wd sin wd t)
    const double k = 3.0, b = 0.4, m = 1.5, t = 0.8;
    const double a = b / (2 * m), wd = std::sqrt(k / m - a * a);
    const double x = std::exp(-a * t) * (x0 * std::cos(wd * t) + (v0 + a * x0) / wd * std::sin(wd * t));
    const double v = std::exp(-a * t) * (v0 * std::cos(wd * t) - (k / m * x0 + a * v0) / wd * std::sin(wd * t));
    check(k, b, m, t, x, v);
  }
  {  // critically damped: x = e^{-at}(x0 + (v0 + a x0) t), v = e^{-at}(v0 - a (v0 + a x0) t)
    const double k = 4.0, m = 1.0, b = 4.0, t = 0.6;  // b^2 = 4 k m exactly
    const double a = 2.0;
    check(k, b, m, t, std::exp(-a * t) * (x0 + (v0 + a * x0) * t), std::exp(-a * t) * (v0 - a * (v0 + a * x0) * t));
  }
  {  // overdamped: x = c1 e^{r1 t} + c2 e^{r2 t}
    const double k = 2.0, b = 5.0, m = 0.5, t = 0.9;
    const double a = b / (2 * m), beta = std::sqrt(a * a - k / m);
    const double r1 = -a + beta, r2 = -a - beta;
    const double c1 = (v0 - r2 * x0) / (r1 - r2), c2 = (r1 * x0 - v0) / (r1 - r2);
    check(k, b, m, t, c1 * std::exp(r1 * t) + c2 * std::exp(r2 * t),
          r1 * c1 * std::exp(r1 * t) + r2 * c2 * std::exp(r2 * t));
  }
  {  // k = 0: v = v0 e^{-bt/m}, x = x0 + v0 m/b (1 - e^{-bt/m})
    const double b = 0.8, m = 2.0, t = 1.7;
    check(0.0, b, m, t, x0 + v0 * m / b * (1 - std::exp(-b * t / m)), v0 * std::exp(-b * t / m));
  }
  // k = 0 and b = 0: free flight.
  check(0.0, 0.0, 3.0, 2.5, x0 + v0 * 2.5, v0);
  {  // b = 0: x = x0 cos wt + v0/w sin wt
    const double k = 9.0, m = 0.25, t = 0.31, w = 6.0;
    check(k, 0.0, m, t, x0 * std::cos(w * t) + v0 / w * std::sin(w * t), -x0 * w * std::sin(w * t) + v0 * std::cos(w * t));
  }
}

// Near critical damping the implementation must not lose accuracy (a naive overdamped
// formula divides by beta -> 0; a naive underdamped one by wd -> 0).
TEST(OscillatorStep, NearCriticalDampingIsContinuous) {
  for (double k : {1.0, 200.0, 1e6}) {
    for (double m : {1e-3, 1.0}) {
      for (double detune : {-1e-4, -1e-8, -1e-12, 0.0, 1e-12, 1e-8, 1e-4}) {
        for (double dt : {1e-4, 1e-2, 1.0}) {
          const double b = 2.0 * std::sqrt(k * m) * (1.0 + detune);
          const Map ref = scaled(reference_map(k, b, m, dt), k, m, dt);
          const Map got = scaled(to_map(OscillatorStep::exact(k, b, m, dt)), k, m, dt);
          EXPECT_LT(map_distance(got, ref), 1e-10L) << params(k, b, m, dt) << " detune=" << detune;
        }
      }
    }
  }
}

// The map against the reference over the whole extreme grid (plus k = 0), in scaled
// coordinates: 1e-12 plus the unavoidable phase round-off of fast undamped oscillators.
TEST(OscillatorStep, MatchesReferenceOverTheExtremeGrid) {
  std::vector<double> ks(kGridK.begin(), kGridK.end());
  ks.push_back(0.0);
  int checked = 0;
  for (double k : ks)
    for (double m : kGridM)
      for (double b : kGridB)
        for (double dt : kGridDt) {
          const Map ref = scaled(reference_map(k, b, m, dt), k, m, dt);
          const OscillatorStep s = OscillatorStep::exact(k, b, m, dt);
          ASSERT_TRUE(std::isfinite(s.xx) && std::isfinite(s.xv) && std::isfinite(s.vx) && std::isfinite(s.vv))
              << params(k, b, m, dt);
          const Map got = scaled(to_map(s), k, m, dt);
          const LD tol = 1e-12L + 4e-15L * phase(k, b, m, dt);
          EXPECT_LT(map_distance(got, ref), tol) << params(k, b, m, dt);
          ++checked;
        }
  EXPECT_EQ(checked, 6 * 4 * 5 * 4);
}

TEST(OscillatorStep, TwoStepsEqualOneDoubleStep) {
  std::vector<double> ks(kGridK.begin(), kGridK.end());
  ks.push_back(0.0);
  for (double k : ks)
    for (double m : kGridM)
      for (double b : kGridB)
        for (double dt : kGridDt) {
          const OscillatorStep one = OscillatorStep::exact(k, b, m, dt);
          const OscillatorStep two = OscillatorStep::exact(k, b, m, 2 * dt);
          // one * one in long double
          const Map sq = {static_cast<LD>(one.xx) * one.xx + static_cast<LD>(one.xv) * one.vx,
                          static_cast<LD>(one.xx) * one.xv + static_cast<LD>(one.xv) * one.vv,
                          static_cast<LD>(one.vx) * one.xx + static_cast<LD>(one.vv) * one.vx,
                          static_cast<LD>(one.vx) * one.xv + static_cast<LD>(one.vv) * one.vv};
          const LD d = map_distance(scaled(sq, k, m, 2 * dt), scaled(to_map(two), k, m, 2 * dt));
          EXPECT_LT(d, 1e-12L + 4e-15L * phase(k, b, m, 2 * dt)) << params(k, b, m, dt);
        }
}

// Stress case 10: no NaN, no growth of energy, |x| within its energy bound, E strictly
// decreasing with damping and conserved without, over the whole extreme grid.
TEST(OscillatorStep, EnergyNeverGrowsOverTheExtremeGrid) {
  const int steps = long_tests() ? 2000 : 100;
  for (double k : kGridK)
    for (double m : kGridM)
      for (double b : kGridB)
        for (double dt : kGridDt) {
          const OscillatorStep s = OscillatorStep::exact(k, b, m, dt);
          const double w0 = std::sqrt(k / m);
          const double x0 = 1e-3;
          const std::array<std::array<double, 2>, 5> starts = {{
              {x0, 0.0},
              {0.0, x0 * w0},
              {x0, x0 * w0},
              {-x0, 0.7 * x0 * w0},
              {x0, -3.0 * x0 * w0},
          }};
          for (const auto& start : starts) {
            double x = start[0];
            double v = start[1];
            const LD e0 = energy(k, m, x, v);
            const LD xbound = std::sqrt(2 * e0 / k);
            LD e_prev = e0;
            bool ok = true;
            for (int n = 1; n <= steps && ok; ++n) {
              s.apply(x, v);
              const LD e = energy(k, m, x, v);
              if (!std::isfinite(x) || !std::isfinite(v)) {
                ADD_FAILURE() << "non-finite state at step " << n << ": " << params(k, b, m, dt);
                ok = false;
              } else if (e > e_prev * (1 + 1e-12L) + e0 * 1e-200L) {
                ADD_FAILURE() << "energy grew at step " << n << " by " << static_cast<double>(e / e_prev - 1)
                              << " relative: " << params(k, b, m, dt) << " x0=" << start[0] << " v0=" << start[1];
                ok = false;
              } else if (std::fabs(x) > xbound * (1 + 1e-12L * n) + 1e-300L) {
                ADD_FAILURE() << "|x| " << x << " beyond its energy bound " << static_cast<double>(xbound)
                              << " at step " << n << ": " << params(k, b, m, dt);
                ok = false;
              } else if (b == 0.0 && std::fabs(e / e0 - 1) > 1e-12L * n) {
                ADD_FAILURE() << "undamped energy drifted by " << static_cast<double>(e / e0 - 1) << " at step " << n
                              << ": " << params(k, b, m, dt);
                ok = false;
              }
              e_prev = e;
            }
            // With damping and motion, energy strictly decreases (detectably so when the
            // start carries kinetic energy: the first states below do).
            if (ok && b > 0 && start[1] != 0.0) {
              EXPECT_LT(e_prev, e0) << params(k, b, m, dt) << " x0=" << start[0] << " v0=" << start[1];
            }
          }
        }
}

// 10^6 steps of an undamped oscillator at dt = 1e-3 (10^7 with PALPA_LONG_TESTS=1, 10^5
// without NDEBUG): no drift of E, phase of cos(w t).
TEST(OscillatorStep, UndampedMillionStepsKeepEnergyAndPhase) {
  const long steps = (long_tests() ? 10'000'000L : 1'000'000L) / kLoopDivisor;
  const double dt = 1e-3;
  struct Case {
    double k, m;
  };
  const double two_pi = 2 * std::numbers::pi;
  for (const Case c : {Case{two_pi * two_pi, 1.0}, Case{400.0, 1e-3}}) {
    const OscillatorStep s = OscillatorStep::exact(c.k, 0.0, c.m, dt);
    const LD w = std::sqrt(static_cast<LD>(c.k) / c.m);
    double x = 1.0;
    double v = 0.0;
    const LD e0 = energy(c.k, c.m, x, v);
    LD worst_e = 0;
    LD worst_x = 0;
    LD worst_v = 0;
    for (long n = 1; n <= steps; ++n) {
      s.apply(x, v);
      worst_e = std::max(worst_e, std::fabs(energy(c.k, c.m, x, v) / e0 - 1));
      if (n % 997 == 0 || n == steps) {
        const LD t = static_cast<LD>(n) * static_cast<LD>(dt);
        worst_x = std::max(worst_x, std::fabs(x - std::cos(w * t)));
        worst_v = std::max(worst_v, std::fabs(v / w + std::sin(w * t)));
      }
    }
    // 1e-9 and 1e-6 per 10^6 steps: round-off of ~1e-16 per step may accumulate linearly.
    const LD per_million = std::max<LD>(1, static_cast<LD>(steps) / 1e6L);
    EXPECT_LT(worst_e, 1e-9L * per_million) << "k=" << c.k << " m=" << c.m;
    EXPECT_LT(worst_x, 1e-6L * per_million) << "k=" << c.k << " m=" << c.m;
    EXPECT_LT(worst_v, 1e-6L * per_million) << "k=" << c.k << " m=" << c.m;
  }
}

TEST(DampingHelpers, FormulasAsStated) {
  for (double k : {0.0, 1e-3, 200.0, 1e9})
    for (double m : {1e-6, 1e-3, 10.0})
      for (double zeta : {0.0, 0.3, 0.7, 1.0, 2.5}) {
        const double expected = 2.0 * zeta * std::sqrt(k * m);
        EXPECT_NEAR(damping_for_ratio(k, m, zeta), expected, 1e-14 * expected) << k << " " << m << " " << zeta;
      }
  for (double m : {1e-6, 1e-3, 10.0})
    for (double t : {0.01, 0.2, 3.0})
      for (double f : {0.5, 0.02, 1e-4}) {
        const double expected = -2.0 * m * std::log(f) / t;
        EXPECT_NEAR(damping_for_settling(m, t, f), expected, 1e-14 * expected);
      }
  EXPECT_DOUBLE_EQ(damping_for_settling(1e-3, 0.2), damping_for_settling(1e-3, 0.2, 0.02));
}

// After one damped period Td = 2 pi / wd every state is scaled by exactly e^{-zeta w0 Td}:
// the ratio the helper promises, seen through the oscillator.
TEST(DampingHelpers, RatioGivesItsLogarithmicDecrementThroughTheOscillator) {
  for (double k : {1.0, 200.0, 1e6})
    for (double m : {1e-3, 1.0})
      for (double zeta : {0.05, 0.3, 0.7, 0.95}) {
        const double b = damping_for_ratio(k, m, zeta);
        const double w0 = std::sqrt(k / m);
        const double td = 2 * std::numbers::pi / (w0 * std::sqrt(1 - zeta * zeta));
        const Map got = scaled(to_map(OscillatorStep::exact(k, b, m, td)), k, m, td);
        const LD decay = std::exp(-static_cast<LD>(zeta) * w0 * td);
        EXPECT_LT(map_distance(got, Map{decay, 0, 0, decay}), 1e-12L) << k << " " << m << " " << zeta;
      }
  // zeta = 1 is critical: x(t) = (1 + w0 t) e^{-w0 t} from rest at x = 1, never crossing 0;
  // zeta > 1 does not cross either.
  for (double zeta : {1.0, 1.5, 4.0}) {
    const double k = 200.0, m = 1e-3, dt = 1e-4;
    const double w0 = std::sqrt(k / m);
    const OscillatorStep s = OscillatorStep::exact(k, damping_for_ratio(k, m, zeta), m, dt);
    double x = 1.0;
    double v = 0.0;
    for (int n = 1; n <= 2000; ++n) {
      s.apply(x, v);
      ASSERT_GT(x, 0.0) << "zeta=" << zeta << " crossed zero at step " << n;
      if (zeta == 1.0) {
        const double t = n * dt;
        ASSERT_NEAR(x, (1 + w0 * t) * std::exp(-w0 * t), 1e-12) << n;
      }
    }
  }
}

// An underdamped point from x = 1, v = -a (so x(t) = e^{-at} cos(wd t), envelope 1) has,
// after settling_time, an envelope of `fraction`: no |x| beyond it over the next period,
// and the peak within that period is the envelope itself (not a much smaller one).
TEST(DampingHelpers, SettlingTimeReachesTheFractionThroughTheOscillator) {
  struct Case {
    double k, m, t, f;
  };
  for (const Case c : {Case{200.0, 1e-3, 0.2, 0.02}, Case{5e3, 1e-2, 0.5, 0.05}, Case{1.0, 1.0, 20.0, 0.1}}) {
    const double b = damping_for_settling(c.m, c.t, c.f);
    const double a = b / (2 * c.m);
    const double w0 = std::sqrt(c.k / c.m);
    ASSERT_LT(a, w0) << "case must be underdamped";
    const double wd = std::sqrt(w0 * w0 - a * a);
    const double td = 2 * std::numbers::pi / wd;
    const double dt = td / 400;
    const OscillatorStep s = OscillatorStep::exact(c.k, b, c.m, dt);
    double x = 1.0;
    double v = -a;
    const auto n_settle = static_cast<long>(std::ceil(c.t / dt));
    for (long n = 0; n < n_settle; ++n) s.apply(x, v);
    const double t_settle = static_cast<double>(n_settle) * dt;
    double peak = 0.0;
    for (int n = 0; n < 400; ++n) {
      peak = std::max(peak, std::fabs(x));
      s.apply(x, v);
    }
    EXPECT_LE(peak, c.f * (1 + 1e-9)) << "k=" << c.k;
    // The envelope at t_settle is f e^{-a (t_settle - T)}; the sampled peak lies within
    // one period and half a sample of phase below it.
    EXPECT_GE(peak, c.f * std::exp(-a * (t_settle - c.t + td)) * std::cos(wd * dt)) << "k=" << c.k;
  }
}

}  // namespace
}  // namespace palpa::deform
