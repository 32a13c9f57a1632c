// Coverage of the exam region on the flat case, against the analytic area of its top
// contour z = R(x, y) and the disc a stationary finger pad covers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "palpa/score/score.hpp"
#include "score_fixture.hpp"

namespace palpa::score {
namespace {

using test::flat_radius;
constexpr double kPi = std::numbers::pi;

double map_area(const BodyMap& m) {
  double a = 0.0;
  for (double x : m.area) a += x;
  return a;
}

Score stationary(double x, double y, const nlohmann::json& extra = nlohmann::json::object(), double seconds = 1.0) {
  test::SessionBuilder b(test::flat_case({}, extra));
  const int n = static_cast<int>(std::lround(seconds * 1000));
  for (int k = 0; k < n; ++k) b.flat_contact(x, y, 0.002, 4.0);
  return score_session(b.finish(), "coverage.session");
}

// Strips along y every 10 mm from x = -45 to 45 mm, joined in contact, pressing 60 % of
// the local thickness 2 R (deep). Every point of the top contour lies within 7.1 mm
// (3-D) of the path, inside the 7.5 mm pad: the strips' ends 5 mm from the rim, where
// the dome falls away, are at most hypot(5, 5) mm plus the rim's drop of 0.7 mm away.
Score full_raster(const nlohmann::json& extra = nlohmann::json::object()) {
  test::SessionBuilder b(test::flat_case({}, extra));
  for (int strip = 0; strip <= 9; ++strip) {
    const double x = -0.045 + 0.01 * strip;
    for (int k = 0; k <= 450; ++k) {
      const double a = k / 450.0;
      const double y = strip % 2 == 0 ? -0.045 + 0.09 * a : 0.045 - 0.09 * a;
      b.flat_contact(x, y, 0.6 * 2 * flat_radius(x, y), 5.0);
    }
  }
  return score_session(b.finish(), "raster.session");
}

TEST(ScoreCoverage, RegionAreaIsTheTopContourArea) {
  const Score s = stationary(0.0, 0.0);
  ASSERT_EQ(s.maps.size(), 1u);
  const BodyMap& m = s.maps[0];
  // Cells of about 2 mm on a contour about 108 mm long each way.
  EXPECT_GE(m.rows, 50);
  EXPECT_LE(m.rows, 60);
  EXPECT_EQ(m.area.size(), static_cast<std::size_t>(m.rows * m.cols));
  // Quads through the cell corners: second order in the cell size (2 mm cells on a
  // surface of curvature <= 16 /m: well under 0.5 %).
  EXPECT_NEAR(map_area(m), test::flat_top_area(), 0.005 * test::flat_top_area());
}

TEST(ScoreCoverage, StationaryContactCoversOnePadDisc) {
  const Score s = stationary(0.0, 0.0);
  const BodyMap& m = s.maps[0];
  const double r = 0.0075;
  const double region = test::flat_top_area();
  // The covered cells are those whose centre lies within r: their union lies between the
  // discs of radius r - d and r + d, d the half diagonal of a cell (about 1.4 mm), so
  // this bound is all the grid guarantees for one position.
  const double d = 0.5 * std::hypot(0.1 / m.rows, 0.1 / m.cols);
  EXPECT_GT(s.coverage, kPi * (r - d) * (r - d) / region);
  EXPECT_LT(s.coverage, kPi * (r + d) * (r + d) / region);
  EXPECT_NEAR(s.coverage, kPi * r * r / region, 0.25 * kPi * r * r / region);
  EXPECT_DOUBLE_EQ(s.deep_coverage, 0.0);  // 2 mm of 40 mm: light
}

TEST(ScoreCoverage, AveragedOverPositionsTheDiscAreaIsExact) {
  // Averaged over positions uniformly spread across a cell, the lattice count of cell
  // centres within r equals the disc area (up to the 4 x 4 average's residue and the
  // dome's curvature, a few tenths of a percent): 3 % covers it.
  const double cell = 0.1 / stationary(0.0, 0.0).maps[0].rows;
  double sum = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) sum += stationary((i + 0.5) / 4 * cell, (j + 0.5) / 4 * cell, {}, 0.01).coverage;
  const double r = 0.0075;
  EXPECT_NEAR(sum / 16, kPi * r * r / test::flat_top_area(), 0.03 * kPi * r * r / test::flat_top_area());
}

TEST(ScoreCoverage, FullRasterCoversTheRegion) {
  const Score s = full_raster();
  EXPECT_GT(s.coverage, 0.99);
  EXPECT_GT(s.deep_coverage, 0.99);
  EXPECT_TRUE(s.gates[2].passed);
  EXPECT_TRUE(s.gates[3].passed);
}

// A coverage just short of its pass mark must not read as reaching it ("80.0% of the
// region (80.0% needed)", failed): the message rounds the share down to a tenth of a percent.
TEST(ScoreCoverage, AFailedGateNeverReadsAsReachingItsMark) {
  int tried = 0;
  for (double x = 0.0; x < 0.01; x += 0.0005) {
    const double c = stationary(x, 0.0).coverage;
    const double permille = 1000.0 * c;
    if (permille - std::floor(permille) < 0.5) continue;  // would round down anyway
    ++tried;
    const double mark = std::ceil(permille) / 1000.0;  // the next tenth of a percent: just out of reach
    const Score s = stationary(x, 0.0, {{"scoring", {{"min_coverage", mark}}}});
    const Gate& g = s.gates[2];
    ASSERT_EQ(g.name, "coverage");
    EXPECT_FALSE(g.passed);
    char shown[64];
    std::snprintf(shown, sizeof shown, "Covered %.1f%%", std::floor(permille) / 10.0);
    EXPECT_EQ(g.message.rfind(shown, 0), 0u) << g.message << " for a coverage of " << permille / 10.0 << " %";
  }
  EXPECT_GT(tried, 0) << "no position gave a coverage whose tenth of a percent rounds up";
}

TEST(ScoreCoverage, ExamRegionHalfTheBody) {
  const nlohmann::json half = {{"exam_region", {{{"body", "flat"}, {"u", {0.0, 0.5}}}}}};
  const Score whole = stationary(-0.025, 0.0);
  const Score s = stationary(-0.025, 0.0, half);
  const BodyMap& m = s.maps[0];
  ASSERT_EQ(m.rows % 2, 0) << "rows even, so the region's edge u = 0.5 falls between cells";
  // The region x <= 0 holds half the (symmetric) top contour.
  EXPECT_NEAR(map_area(m), test::flat_top_area(-0.05, 0.0), 0.005 * test::flat_top_area(-0.05, 0.0));
  // The same pad inside the region covers the same cells: twice the share.
  EXPECT_NEAR(s.coverage, 2.0 * whole.coverage, 1e-9);
  // A contact outside the region covers nothing of it; a raster covers all of it.
  EXPECT_DOUBLE_EQ(stationary(0.025, 0.0, half).coverage, 0.0);
  EXPECT_GT(full_raster(half).coverage, 0.99);
}

TEST(ScoreCoverage, DwellAddsUpToContactTime) {
  // A 1 s press at the centre: the cell under it was under the pad all that second.
  const Score s = stationary(0.0, 0.0);
  const BodyMap& m = s.maps[0];
  const int centre = (m.rows / 2) * m.cols + m.cols / 2;
  EXPECT_NEAR(m.dwell_s[static_cast<std::size_t>(centre)], 1.0, 1e-3);
  EXPECT_FLOAT_EQ(m.peak_force_n[static_cast<std::size_t>(centre)], 4.0f);
  EXPECT_EQ(m.level[static_cast<std::size_t>(centre)], 1);
  EXPECT_NEAR(s.contact_time_s, 1.0, 1e-9);
}

TEST(ScoreCoverage, DwellOfASlidingPad) {
  // Slide along y = 0 at 10 mm/s: a cell is under the pad while the contact's top point
  // is within r = 7.5 mm of its centre (3-D, on the dome z = R(x, y)).
  test::SessionBuilder b(test::flat_case());
  b.slide(0.0, -0.04, 0.0, 0.04, 0.01, 0.002, 3.0);
  const Score s = score_session(b.finish(), "slide.session");
  const BodyMap& m = s.maps[0];
  const int cell = (m.rows / 2) * m.cols + m.cols / 2;
  const auto& cf = m.center[static_cast<std::size_t>(cell)];
  const double c[3] = {double(cf[0]), double(cf[1]), double(cf[2])};
  // Time the path spends within r of the centre, by fine steps along it.
  double inside = 0.0;
  const double step = 1e-6;
  for (double y = -0.04; y < 0.04; y += step) {
    const double dx = 0.0 - c[0], dy = y - c[1], dz = flat_radius(0.0, y) - c[2];
    if (dx * dx + dy * dy + dz * dz <= 0.0075 * 0.0075) inside += step / 0.01;
  }
  EXPECT_NEAR(inside, 1.49, 0.02);
  // Stamps every 0.5 mm of motion: up to one stamp interval (0.05 s) at each end.
  EXPECT_NEAR(m.dwell_s[static_cast<std::size_t>(cell)], inside, 0.1);
}

}  // namespace
}  // namespace palpa::score
