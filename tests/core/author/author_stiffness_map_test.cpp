// Stiffness maps: a map laid over a body's skeleton grid gives each point the stiffness
// of its normalized position, and the result always fits.
#include <gtest/gtest.h>

#include <algorithm>

#include "palpa/author/presets.hpp"
#include "palpa/author/stiffness_map.hpp"
#include "palpa/mat/mat_body.hpp"

namespace palpa::author {
namespace {

// A linear ramp along the map's columns (horizontal = true) or rows.
StiffnessMap ramp(int rows, int cols, bool horizontal) {
  StiffnessMap m{rows, cols, {}};
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      m.values.push_back(horizontal ? static_cast<double>(c) / (cols - 1) : static_cast<double>(r) / (rows - 1));
    }
  }
  return m;
}

TEST(AuthorStiffnessMap, HorizontalGradientGivesLinearStiffnessAlongColumns) {
  mat::BodyGrid g = make_preset_body(preset_defaults(Preset::Slab));  // 11 x 11
  const double k_min = 100.0, k_max = 600.0;
  // 37 x 53 pixels: the grid points fall between pixels, the ramp is still exact.
  EXPECT_EQ(apply_stiffness_map(g, ramp(37, 53, true), k_min, k_max), 0);
  for (int i = 0; i < g.rows; ++i) {
    for (int j = 0; j < g.cols; ++j) {
      // Hand-computed: column j of 11 sits at j/10 of the map.
      EXPECT_NEAR(g.stiffness[static_cast<std::size_t>(i * g.cols + j)], 100.0 + 500.0 * j / 10.0, 1e-9) << i << "," << j;
    }
  }
}

TEST(AuthorStiffnessMap, VerticalGradientGivesLinearStiffnessAlongRows) {
  mat::BodyGrid g = make_preset_body(preset_defaults(Preset::Breast));  // 9 x 11
  const auto k = map_stiffness(g, ramp(20, 8, false), 0.0, 800.0);
  for (int i = 0; i < g.rows; ++i) {
    for (int j = 0; j < g.cols; ++j) EXPECT_NEAR(k[static_cast<std::size_t>(i * g.cols + j)], 800.0 * i / 8.0, 1e-9);
  }
}

TEST(AuthorStiffnessMap, ConstantMapAndTinyMap) {
  mat::BodyGrid g = make_preset_body(preset_defaults(Preset::Prostate));
  StiffnessMap one{1, 1, {0.25}};
  const auto k = map_stiffness(g, one, 400.0, 800.0);
  for (double x : k) EXPECT_DOUBLE_EQ(x, 500.0);
}

// One stiff spot the size of a grid cell in tissue of stiffness 0: as point values the
// spline rings far below zero around it; the smoothing passes make it fit.
TEST(AuthorStiffnessMap, HarshMapIsSmoothedUntilItFits) {
  mat::BodyGrid g = make_preset_body(preset_defaults(Preset::Slab));  // 11 x 11
  StiffnessMap m{101, 101, std::vector<double>(101 * 101, 0.0)};
  for (int r = 45; r <= 55; ++r) {
    for (int c = 45; c <= 55; ++c) m.values[static_cast<std::size_t>(r * 101 + c)] = 1.0;
  }
  mat::BodyGrid raw = g;
  raw.stiffness = map_stiffness(g, m, 0.0, 1000.0);
  ASSERT_THROW((void)mat::MatBody::fit(raw), mat::FitError) << "the map is not harsh enough to test smoothing";
  const int passes = apply_stiffness_map(g, m, 0.0, 1000.0);
  EXPECT_GT(passes, 0);
  EXPECT_NO_THROW((void)mat::MatBody::fit(g));
  for (double k : g.stiffness) {
    EXPECT_GE(k, 0.0);
    EXPECT_LE(k, 1000.0);
  }
  // Still a spot: stiffest at the centre.
  EXPECT_EQ(std::max_element(g.stiffness.begin(), g.stiffness.end()) - g.stiffness.begin(), 5 * 11 + 5);
}

TEST(AuthorStiffnessMap, BadMapsAreRejected) {
  mat::BodyGrid g = make_preset_body(preset_defaults(Preset::Slab));
  EXPECT_THROW((void)map_stiffness(g, StiffnessMap{}, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW((void)map_stiffness(g, StiffnessMap{2, 2, {0.0, 0.5, 1.0}}, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW((void)map_stiffness(g, StiffnessMap{1, 2, {0.0, 1.5}}, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW((void)map_stiffness(g, StiffnessMap{1, 1, {0.5}}, 10.0, 1.0), std::invalid_argument);
  EXPECT_THROW((void)map_stiffness(g, StiffnessMap{1, 1, {0.5}}, -1.0, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace palpa::author
