// The springback of a released DeformedBody (paper section 3.3): pressed points are held,
// released ones follow their own oscillators (k, b, m of their control point), the body
// returns to rest when its slowest envelope predicts and sleeps, and without dynamics it
// rests at once. Truths: the long-double reference oscillator and the underdamped envelope.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "deform_test_support.hpp"

namespace palpa::deform {
namespace {

using namespace deform_test;

// Pressed points are held: stepping the clock does not move them off the probe.
TEST(DeformedBody, PressedPointsAreHeldWhileSteppingTheClock) {
  DeformedBody body(varied());
  const Vec3 q = probe_over(varied(), 0.47, 0.52, 0.006, 1);
  const contact::Contact c = contact_on_rest(varied(), q);
  body.press(c, q);
  const std::vector<double> top = body.top().control();
  for (int n = 0; n < 20; ++n) {
    body.step(1e-3);
    ASSERT_LT((eval3(body.top(), c.foot.u, c.foot.v) - q).norm(), 1e-9) << "step " << n;
  }
  EXPECT_EQ(body.top().control(), top);
}

// Released, every component of every control point follows its own oscillator (k, b, m:
// that control point's channels of the rest skeleton) from rest at its pressed
// displacement, whatever the sequence of time steps; energy() is the oscillators' energy.
TEST(DeformedBody, ReleasedPointsFollowTheirOwnOscillators) {
  const MatBody& rest = varied();
  const BSplineSurface& sk = rest.skeleton();
  for (int i = 0; i < sk.rows(); ++i)
    for (int j = 0; j < sk.cols(); ++j) {
      const Material mt = material(rest, i, j);
      ASSERT_GT(mt.k, 0.0);
      ASSERT_GT(mt.b, 0.0);
      ASSERT_GT(mt.m, 0.0);
    }
  for (const Scheme scheme : {Scheme::SkeletonMoves, Scheme::Compression}) {
    DeformOptions options;
    options.scheme = scheme;
    options.g = 0.35;
    // One press on a body at rest: every displaced point starts from rest (v = 0).
    DeformedBody fresh(rest, options);
    const Vec3 q = probe_over(rest, 0.6, 0.45, 0.007, -1);
    const contact::Contact c = contact_on_rest(rest, q);
    fresh.press(c, q);
    std::vector<std::array<double, 10>> x0;
    for (int i = 0; i < sk.rows(); ++i)
      for (int j = 0; j < sk.cols(); ++j) x0.push_back(displacement(fresh, i, j));
    fresh.release();
    EXPECT_TRUE(fresh.awake());
    const std::vector<double> dts = {1e-3, 1e-3, 1e-3, 2e-3, 2e-3, 5e-4, 5e-4, 5e-4, 3e-3, 1e-3, 1e-3};
    LD t = 0;
    std::uint64_t version = fresh.version();
    for (double dt : dts) {
      fresh.step(dt);
      t += dt;
      ASSERT_TRUE(fresh.awake()) << "fell asleep too early at t=" << static_cast<double>(t);
      EXPECT_GT(fresh.version(), version);
      version = fresh.version();
      LD expected_energy = 0;
      double worst = 0.0, scale = 0.0;
      int snapped = 0;
      for (int i = 0; i < sk.rows(); ++i)
        for (int j = 0; j < sk.cols(); ++j) {
          const Material mt = material(rest, i, j);
          const State unit = reference(mt.k, mt.b, mt.m, t, 1, 0);
          const auto& start = x0[static_cast<std::size_t>(i * sk.cols() + j)];
          const auto now = displacement(fresh, i, j);
          for (std::size_t comp = 0; comp < 10; ++comp) {
            const LD x = start[comp] * unit.x;
            const LD v = start[comp] * unit.v;
            scale = std::max(scale, std::fabs(start[comp]));
            // A point may be put to rest on its own once it is within the sleep thresholds
            // (it then deviates from x(t) by less than sleep_displacement).
            if (now[comp] == 0.0 && start[comp] != 0.0 && std::fabs(x) < options.sleep_displacement &&
                std::fabs(v) < 2 * options.sleep_velocity) {
              ++snapped;
              continue;
            }
            worst = std::max(worst, std::fabs(now[comp] - static_cast<double>(x)));
            expected_energy += energy(mt.k, mt.m, x, v);
          }
        }
      if (snapped > 0) RecordProperty("snapped_components_t" + std::to_string(static_cast<double>(t)), snapped);
      EXPECT_LT(worst, 1e-10 * scale) << "scheme " << static_cast<int>(scheme) << " t=" << static_cast<double>(t);
      EXPECT_NEAR(fresh.energy(), static_cast<double>(expected_energy), 1e-8 * static_cast<double>(expected_energy))
          << "t=" << static_cast<double>(t);
      EXPECT_TRUE(all_finite(fresh));
    }
  }
}

// A released body returns to rest in the time the envelope of its slowest oscillator
// predicts, falls asleep exactly at rest, and stays still until pressed again.
TEST(DeformedBody, ReleasedBodyReturnsToRestAndSleeps) {
  const MatBody& rest = flat();
  const BSplineSurface& sk = rest.skeleton();
  DeformOptions options;
  DeformedBody body(rest, options);
  const Vec3 q = probe_over(rest, 0.5, 0.5, 0.008, 1);
  const contact::Contact c = contact_on_rest(rest, q);
  body.press(c, q);
  // Envelope of an underdamped point released from x0 at rest:
  //   |x| <= x0 (w0/wd) e^{-a t},   |v| <= x0 (w0^2/wd) e^{-a t}.
  double t_pred = 0.0;
  std::vector<std::array<double, 10>> x0;
  for (int i = 0; i < sk.rows(); ++i)
    for (int j = 0; j < sk.cols(); ++j) {
      const auto d = displacement(body, i, j);
      x0.push_back(d);
      double amp = 0.0;
      for (double x : d) amp = std::max(amp, std::fabs(x));
      if (amp == 0.0) continue;
      const Material mt = material(rest, i, j);
      const double a = mt.b / (2 * mt.m), w0 = std::sqrt(mt.k / mt.m);
      ASSERT_LT(a, w0) << "the default material is underdamped";
      const double wd = std::sqrt(w0 * w0 - a * a);
      const double tx = std::log(amp * w0 / wd / options.sleep_displacement) / a;
      const double tv = std::log(amp * w0 * w0 / wd / options.sleep_velocity) / a;
      t_pred = std::max({t_pred, tx, tv});
    }
  ASSERT_GT(t_pred, 0.0);
  const double dt = 1e-3;
  body.release();
  const auto max_steps = static_cast<int>(std::ceil(t_pred / dt)) + 2;
  int slept_at = -1;
  std::uint64_t version = body.version();
  for (int n = 1; n <= max_steps + 50; ++n) {
    body.step(dt);
    ASSERT_TRUE(all_finite(body));
    if (!body.awake()) {
      slept_at = n;
      break;
    }
    EXPECT_GT(body.version(), version);
    version = body.version();
  }
  ASSERT_GT(slept_at, 0) << "never fell asleep";
  EXPECT_LE(slept_at, max_steps) << "predicted rest within " << t_pred << " s";
  // It may not fall asleep before every point is within the thresholds (at the step it
  // fell asleep or the one before, depending on when it checks).
  const auto within = [&](double t) {
    bool ok = true;
    for (int i = 0; i < sk.rows(); ++i)
      for (int j = 0; j < sk.cols(); ++j) {
        const Material mt = material(rest, i, j);
        const State unit = reference(mt.k, mt.b, mt.m, t, 1, 0);
        for (double x : x0[static_cast<std::size_t>(i * sk.cols() + j)]) {
          ok = ok && std::fabs(x * unit.x) < options.sleep_displacement * (1 + 1e-6) &&
               std::fabs(x * unit.v) < options.sleep_velocity * (1 + 1e-6);
        }
      }
    return ok;
  };
  EXPECT_TRUE(within(slept_at * dt) || within((slept_at - 1) * dt)) << "fell asleep at step " << slept_at;
  EXPECT_TRUE(at_rest(body));
  EXPECT_EQ(body.max_displacement(), 0.0);
  EXPECT_EQ(body.energy(), 0.0);
  const std::uint64_t asleep_version = body.version();
  for (int n = 0; n < 100; ++n) body.step(dt);
  EXPECT_FALSE(body.awake());
  EXPECT_EQ(body.version(), asleep_version);
  EXPECT_TRUE(at_rest(body));
  // A press wakes it.
  body.press(c, q);
  EXPECT_TRUE(body.awake());
  EXPECT_GT(body.version(), asleep_version);
  EXPECT_LT((eval3(body.top(), c.foot.u, c.foot.v) - q).norm(), 1e-9);
}

TEST(DeformedBody, WithoutDynamicsReleaseRestsAtOnce) {
  DeformOptions options;
  options.dynamics = false;
  for (const Scheme scheme : {Scheme::SkeletonMoves, Scheme::Compression}) {
    options.scheme = scheme;
    DeformedBody body(varied(), options);
    const Vec3 q = probe_over(varied(), 0.55, 0.4, 0.006, 1);
    const contact::Contact c = contact_on_rest(varied(), q);
    body.press(c, q);
    EXPECT_LT((eval3(body.top(), c.foot.u, c.foot.v) - q).norm(), 1e-9);
    const std::uint64_t pressed = body.version();
    body.release();
    EXPECT_TRUE(at_rest(body));
    EXPECT_GT(body.version(), pressed);
    EXPECT_EQ(body.energy(), 0.0);
    EXPECT_EQ(body.max_displacement(), 0.0);
    body.step(1e-3);
    EXPECT_FALSE(body.awake());
    const std::uint64_t v = body.version();
    for (int n = 0; n < 10; ++n) body.step(1e-3);
    EXPECT_EQ(body.version(), v);
    EXPECT_TRUE(at_rest(body));
  }
}

}  // namespace
}  // namespace palpa::deform
