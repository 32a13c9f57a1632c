// The MAT body (paper section 2.1) against analytic shapes.
#include "palpa/mat/mat_body.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "palpa/mat/fit_residual.hpp"
#include "test_grids.hpp"

namespace palpa::mat {
namespace {

TEST(MatBody, FlatSkeletonGivesContoursAtPlusMinusTheRadiusInClosedForm) {
  const auto grid = test::flat_body(5, 5);
  const auto body = MatBody::fit(grid);
  std::vector<double> sk(7);
  std::vector<double> top(3);
  std::vector<double> bottom(3);
  for (double u = 0.0; u <= 1.0; u += 0.05) {
    for (double v = 0.0; v <= 1.0; v += 0.05) {
      const double a = -1.0 + 2.0 * u;
      const double b = -1.0 + 2.0 * v;
      const double r = 0.02 * (1 - a * a) * (1 - b * b);
      body.skeleton().evaluate(u, v, sk);
      body.top().evaluate(u, v, top);
      body.bottom().evaluate(u, v, bottom);
      EXPECT_NEAR(sk[kX], 0.05 * a, 1e-15);
      EXPECT_NEAR(sk[kZ], 0.0, 1e-15);
      EXPECT_NEAR(sk[kRadius], r, 1e-15);
      EXPECT_NEAR(top[0], 0.05 * a, 1e-15);  // a contour point lies over the skeleton point
      EXPECT_NEAR(top[1], 0.05 * b, 1e-15);
      EXPECT_NEAR(top[2], r, 1e-15);  // "top" is the +N side: u along x, v along y, N = +z
      EXPECT_NEAR(bottom[2], -r, 1e-15);
    }
  }
}

TEST(MatBody, CylinderSkeletonContoursSitAtTheOffsetRadius) {
  // Skeleton on a cylinder of radius 0.1 about the y axis; the MAT radius pushes the
  // contours to 0.1 +- r from the axis at the data sites.
  BodyGrid g;
  g.id = "cyl";
  g.rows = 7;
  g.cols = 9;
  for (int i = 0; i < g.rows; ++i) {
    for (int j = 0; j < g.cols; ++j) {
      const double phi = 0.5 * std::numbers::pi * i / (g.rows - 1);
      const double y = 0.12 * j / (g.cols - 1);
      const bool edge = i == 0 || j == 0 || i == g.rows - 1 || j == g.cols - 1;
      g.medial.push_back({0.1 * std::cos(phi), y, 0.1 * std::sin(phi)});
      g.radius.push_back(edge ? 0.0 : 0.01 + 0.002 * std::sin(phi));
      g.stiffness.push_back(300.0);
    }
  }
  const auto body = MatBody::fit(g);
  std::vector<double> top(3);
  std::vector<double> bottom(3);
  for (int i = 1; i < g.rows - 1; ++i) {
    for (int j = 1; j < g.cols - 1; ++j) {
      const auto k = static_cast<std::size_t>(i * g.cols + j);
      body.top().evaluate(body.u_params()[static_cast<std::size_t>(i)], body.v_params()[static_cast<std::size_t>(j)], top);
      body.bottom().evaluate(body.u_params()[static_cast<std::size_t>(i)], body.v_params()[static_cast<std::size_t>(j)], bottom);
      const double rt = std::hypot(top[0], top[2]);
      const double rb = std::hypot(bottom[0], bottom[2]);
      // u runs with phi (towards +z), v along +y: Su x Sv points towards the axis... either way
      // the two contours are 0.1 +- r from it, to the accuracy of the skeleton's normal.
      EXPECT_NEAR(std::max(rt, rb), 0.1 + g.radius[k], 2e-4);
      EXPECT_NEAR(std::min(rt, rb), 0.1 - g.radius[k], 2e-4);
      EXPECT_NEAR(top[1], g.medial[k][1], 1e-6);
    }
  }
}

TEST(MatBody, TopIsThePlusNormalSide) {
  const auto grid = test::flat_body(6, 4);
  const auto body = MatBody::fit(grid);
  double n[3];
  ASSERT_TRUE(skeleton_normal(body.skeleton(), 0.5, 0.5, n));
  std::vector<double> sk(7);
  std::vector<double> top(3);
  body.skeleton().evaluate(0.5, 0.5, sk);
  body.top().evaluate(0.5, 0.5, top);
  const double along = (top[0] - sk[0]) * n[0] + (top[1] - sk[1]) * n[1] + (top[2] - sk[2]) * n[2];
  EXPECT_GT(along, 0.0);
  EXPECT_NEAR(along, sk[kRadius], 1e-12);
}

TEST(MatBody, DefaultsFillDampingAndMass) {
  const auto grid = test::flat_body(4, 4, 0.05, 0.02, 250.0);
  const auto body = MatBody::fit(grid);
  std::vector<double> sk(7);
  body.skeleton().evaluate(0.3, 0.6, sk);
  EXPECT_NEAR(sk[kMass], 1e-3, 1e-15);
  EXPECT_NEAR(sk[kDamping], 2.0 * 0.7 * std::sqrt(250.0 * 1e-3), 1e-12);
}

TEST(MatBody, AuthoredDampingAndMassAreKept) {
  auto grid = test::flat_body(4, 5);
  grid.damping.assign(grid.point_count(), 0.4);
  grid.mass.assign(grid.point_count(), 2e-3);
  const auto body = MatBody::fit(grid);
  const auto res = fit_residual(body, grid);
  std::vector<double> sk(7);
  body.skeleton().evaluate(0.7, 0.2, sk);
  EXPECT_NEAR(sk[kDamping], 0.4, 1e-14);
  EXPECT_NEAR(sk[kMass], 2e-3, 1e-16);
  EXPECT_LT(res.skeleton[kDamping], 1e-14);
}

TEST(MatBody, ResidualAtTheDataSitesIsRoundOff) {
  const auto grid = test::flat_body(9, 11);
  const auto body = MatBody::fit(grid);
  const auto res = fit_residual(body, grid);
  for (int c = 0; c < kSkeletonChannels; ++c) EXPECT_LT(res.skeleton[static_cast<std::size_t>(c)], 1e-12);
  EXPECT_LT(res.top, 1e-15);
  EXPECT_LT(res.bottom, 1e-15);
}

TEST(MatBody, PoleRowHasALimitNormal) {
  // A dome-like cap whose row 0 is the apex.
  BodyGrid g;
  g.id = "cap";
  g.rows = 6;
  g.cols = 8;
  for (int i = 0; i < g.rows; ++i) {
    for (int j = 0; j < g.cols; ++j) {
      const double rho = 0.04 * i / (g.rows - 1);
      const double phi = 2.0 * j / (g.cols - 1);
      const bool edge = i == 0 || j == 0 || i == g.rows - 1 || j == g.cols - 1;
      g.medial.push_back({rho * std::cos(phi), rho * std::sin(phi), 0.02 - 5.0 * rho * rho});
      g.radius.push_back(edge ? 0.0 : 0.004);
      g.stiffness.push_back(200.0);
    }
  }
  const auto body = MatBody::fit(g);
  double at_pole[3];
  double near_pole[3];
  ASSERT_TRUE(skeleton_normal(body.skeleton(), 0.0, 0.5, at_pole));
  ASSERT_TRUE(skeleton_normal(body.skeleton(), 1e-5, 0.5, near_pole));
  const double dot = at_pole[0] * near_pole[0] + at_pole[1] * near_pole[1] + at_pole[2] * near_pole[2];
  EXPECT_GT(dot, 0.999);
}

TEST(MatBody, ModelIsCompact) {
  // 13 channels (7 skeleton + 3 + 3) of doubles per MAT point, plus knots and bookkeeping.
  const auto grid = test::flat_body(31, 30);  // 930 points, about the paper's largest scene
  const auto body = MatBody::fit(grid);
  const std::size_t payload = grid.point_count() * 13 * sizeof(double);
  EXPECT_GE(body.memory_bytes(), payload);
  EXPECT_LT(body.memory_bytes(), payload + 4096);
}

TEST(MatBody, SizeMismatchIsRejected) {
  auto grid = test::flat_body(4, 4);
  grid.radius.pop_back();
  EXPECT_THROW((void)MatBody::fit(grid), spline::InterpolationError);
}

}  // namespace
}  // namespace palpa::mat
