// Search-pattern classes (after Azari et al. 2015) on synthetic paths over the flat case:
// parallel strips, a cross-hatch, random jumps, a small circle, and no contact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>
#include <cstdint>
#include <numbers>

#include "palpa/score/score.hpp"
#include "score_fixture.hpp"

namespace palpa::score {
namespace {

using test::flat_radius;
constexpr double kSpeed = 0.05;  // m/s
constexpr double kDepth = 0.004;

// Strips along y at x = -45, -30, ..., 45 mm (15 mm apart), joined in contact.
void strips_along_y(test::SessionBuilder& b) {
  for (int k = 0; k < 7; ++k) {
    const double x = -0.045 + 0.015 * k;
    const double y0 = k % 2 == 0 ? -0.045 : 0.045;
    b.slide(x, y0, x, -y0, kSpeed, kDepth, 4.0);
    if (k < 6) b.slide(x, -y0, x + 0.015, -y0, kSpeed, kDepth, 4.0);
  }
}

// Top-contour length of the straight line from (x0, y0) to (x1, y1), by fine steps.
double top_length(double x0, double y0, double x1, double y1) {
  double length = 0.0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const double a = k / double(n), c = (k + 1) / double(n);
    const double xa = x0 + a * (x1 - x0), ya = y0 + a * (y1 - y0);
    const double xc = x0 + c * (x1 - x0), yc = y0 + c * (y1 - y0);
    length += std::sqrt((xc - xa) * (xc - xa) + (yc - ya) * (yc - ya) +
                        std::pow(flat_radius(xc, yc) - flat_radius(xa, ya), 2));
  }
  return length;
}

// The gap between strips at x0 and x1 (both along y over [-45, 45] mm) measured on the
// skin, as docs/scoring.md defines it: the median over points of the first of the 3-D
// distance to the nearest point of the second; over pairs, the median again.
double skin_gap(double x0, double x1) {
  std::vector<double> nearest;
  for (int i = 0; i <= 90; ++i) {
    const double y = -0.045 + 0.001 * i;
    double closest = 1e9;
    for (int j = 0; j <= 900; ++j) {
      const double yq = -0.045 + 0.0001 * j;
      closest = std::min(closest, std::hypot(x1 - x0, yq - y, flat_radius(x1, yq) - flat_radius(x0, y)));
    }
    nearest.push_back(closest);
  }
  std::sort(nearest.begin(), nearest.end());
  return nearest[nearest.size() / 2];
}

TEST(ScorePattern, ParallelStripsAreEfficient) {
  test::SessionBuilder b(test::flat_case());
  strips_along_y(b);
  const Score s = score_session(b.finish(), "strips.session");
  EXPECT_EQ(to_string(s.pattern.kind), "efficient") << "coverage " << s.coverage;
  EXPECT_GE(s.coverage, 0.9);
  // 15 mm apart in x; on the dome's skin the gaps are 15.0 to ~15.9 mm.
  std::vector<double> gaps;
  for (int k = 0; k < 6; ++k) gaps.push_back(skin_gap(-0.045 + 0.015 * k, -0.03 + 0.015 * k));
  std::sort(gaps.begin(), gaps.end());
  const double expected_mm = 1000.0 * 0.5 * (gaps[2] + gaps[3]);
  EXPECT_GT(expected_mm, 15.2);  // the skin measure differs from the top-down one here
  EXPECT_NEAR(s.pattern.strip_spacing_mm, expected_mm, 0.3);
  // Along the strips: 7 x 90 mm of 7 x 90 + 6 x 15 mm (the dome lengthens both a little).
  EXPECT_NEAR(s.pattern.strip_fraction, 630.0 / 720.0, 0.02);
  EXPECT_LE(s.pattern.revisit_fraction, 0.05);
  double length = 0.0;
  for (int k = 0; k < 7; ++k) {
    const double x = -0.045 + 0.015 * k;
    length += top_length(x, -0.045, x, 0.045);
    if (k < 6) length += top_length(x, 0.045, x + 0.015, 0.045);
  }
  EXPECT_NEAR(s.pattern.path_length_m, length, 0.005 * length);
  // Area covered over path length times the pad's width: strips one pad apart waste
  // only the connectors and the rim.
  EXPECT_GT(s.pattern.efficiency, 0.8);
  EXPECT_LE(s.pattern.efficiency, 1.0);
  EXPECT_EQ(s.subscores[5].value, 1.0);
}

TEST(ScorePattern, StripSpacingFollowsTheStrips) {
  // Strips along x this time, 10 mm apart: the dominant axis turns with them.
  test::SessionBuilder b(test::flat_case());
  for (int k = 0; k < 5; ++k) {
    const double y = -0.02 + 0.01 * k;
    const double x0 = k % 2 == 0 ? -0.04 : 0.04;
    b.slide(x0, y, -x0, y, kSpeed, kDepth, 4.0);
    if (k < 4) b.slide(-x0, y, -x0, y + 0.01, kSpeed, kDepth, 4.0);
  }
  const Score s = score_session(b.finish(), "strips-x.session");
  EXPECT_NEAR(s.pattern.strip_spacing_mm, 10.0, 0.5);
  EXPECT_GT(s.pattern.strip_fraction, 0.85);
}

TEST(ScorePattern, CrossHatchIsThorough) {
  // Strips along y, then again along x over the same ground: complete but not one
  // direction, and the second pass runs over ground already covered.
  test::SessionBuilder b(test::flat_case());
  strips_along_y(b);
  for (int k = 0; k < 7; ++k) {
    const double y = -0.045 + 0.015 * k;
    const double x0 = k % 2 == 0 ? -0.045 : 0.045;
    b.slide(x0, y, -x0, y, kSpeed, kDepth, 4.0);
    if (k < 6) b.slide(-x0, y, -x0, y + 0.015, kSpeed, kDepth, 4.0);
  }
  const Score s = score_session(b.finish(), "hatch.session");
  EXPECT_EQ(to_string(s.pattern.kind), "thorough");
  EXPECT_GE(s.coverage, 0.9);
  EXPECT_GT(s.pattern.revisit_fraction, 0.4);  // the second half of the path
  EXPECT_LT(s.pattern.strip_fraction, 0.6);
  EXPECT_DOUBLE_EQ(s.subscores[5].value, 0.75);
}

TEST(ScorePattern, RandomJumpsAreSporadic) {
  // 25 short strokes (10 mm, random direction) at random spots, lifting in between.
  test::SessionBuilder b(test::flat_case());
  std::uint32_t seed = 12345;
  auto next = [&seed] {
    seed = seed * 1664525u + 1013904223u;
    return (seed >> 8) / double(1u << 24);
  };
  for (int k = 0; k < 25; ++k) {
    const double x = -0.035 + 0.07 * next(), y = -0.035 + 0.07 * next();
    const double a = std::numbers::pi * 2 * next();
    b.slide(x, y, x + 0.01 * std::cos(a), y + 0.01 * std::sin(a), kSpeed, kDepth, 4.0);
    for (int j = 0; j < 50; ++j) b.air();
  }
  const Score s = score_session(b.finish(), "random.session");
  EXPECT_EQ(to_string(s.pattern.kind), "sporadic") << "coverage " << s.coverage << ", strips " << s.pattern.strip_fraction;
  EXPECT_LT(s.pattern.strip_fraction, 0.5);
  EXPECT_LT(s.coverage, 0.9);
  EXPECT_DOUBLE_EQ(s.pattern.strip_spacing_mm, 0.0);  // no stroke is a 20 mm strip
  EXPECT_DOUBLE_EQ(s.subscores[5].value, 0.25);
}

TEST(ScorePattern, SmallCircleIsLocalized) {
  // Three times round a 5 mm circle: one compact patch, passed over again and again.
  test::SessionBuilder b(test::flat_case());
  const double r = 0.005;
  const int n = 3 * 2000;
  for (int k = 0; k <= n; ++k) {
    const double a = 2 * std::numbers::pi * k / 2000.0;
    b.flat_contact(0.01 + r * std::cos(a), 0.01 + r * std::sin(a), kDepth, 4.0);
  }
  const Score s = score_session(b.finish(), "circle.session");
  EXPECT_EQ(to_string(s.pattern.kind), "localized");
  EXPECT_LT(s.coverage, 0.1);
  // After the first lap the path only goes over ground covered before.
  EXPECT_GT(s.pattern.revisit_fraction, 0.5);
  EXPECT_NEAR(s.pattern.path_length_m, 3 * 2 * std::numbers::pi * r, 0.03 * 3 * 2 * std::numbers::pi * r);
}

TEST(ScorePattern, NoContactIsNone) {
  test::SessionBuilder b(test::flat_case());
  for (int k = 0; k < 100; ++k) b.air();
  const Score s = score_session(b.finish(), "air.session");
  EXPECT_EQ(to_string(s.pattern.kind), "none");
  EXPECT_DOUBLE_EQ(s.pattern.path_length_m, 0.0);
  EXPECT_DOUBLE_EQ(s.coverage, 0.0);
  EXPECT_DOUBLE_EQ(s.contact_time_s, 0.0);
  EXPECT_DOUBLE_EQ(s.subscores[5].value, 0.0);
  EXPECT_DOUBLE_EQ(s.subscores[6].value, 0.0);
}

TEST(ScorePattern, LiftingOffAndComingBackIsARevisit) {
  // Two passes along the same line, lifted between them: the second is all revisit.
  test::SessionBuilder b(test::flat_case());
  b.slide(0.0, -0.04, 0.0, 0.04, kSpeed, kDepth, 4.0);
  for (int k = 0; k < 100; ++k) b.air();
  b.slide(0.0, -0.04, 0.0, 0.04, kSpeed, kDepth, 4.0);
  const Score s = score_session(b.finish(), "twice.session");
  EXPECT_NEAR(s.pattern.revisit_fraction, 0.5, 0.02);
  // One strip passed twice is one strip: no spacing.
  EXPECT_DOUBLE_EQ(s.pattern.strip_spacing_mm, 0.0);
}

}  // namespace
}  // namespace palpa::score
