// The MAT body (paper section 2.1) against analytic shapes.
#include "palpa/mat/mat_body.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "palpa/mat/fit_residual.hpp"
#include "../support/test_grids.hpp"

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

BodyGrid cylinder_body() {
  // Skeleton on a cylinder of radius 0.1 m about the y axis: u runs with the angle phi
  // (from +x towards +z), v along +y.
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
  return g;
}

TEST(MatBody, CylinderNormalsPointAtTheAxisAndTheTopContourIsTheInnerOne) {
  // Su = (-sin, 0, cos) phi', Sv = (0, 1, 0) y': Su x Sv = -(cos, 0, sin), towards the
  // axis. So "top" (+N) is the inner contour at 0.1 - r, "bottom" the outer at 0.1 + r.
  const auto g = cylinder_body();
  const auto body = MatBody::fit(g);
  std::vector<double> top(3);
  std::vector<double> bottom(3);
  double worst_angle = 0.0;
  for (int i = 0; i < g.rows; ++i) {
    for (int j = 0; j < g.cols; ++j) {
      const auto k = static_cast<std::size_t>(i * g.cols + j);
      const double u = body.u_params()[static_cast<std::size_t>(i)];
      const double v = body.v_params()[static_cast<std::size_t>(j)];
      double n[3];
      ASSERT_TRUE(skeleton_normal(body.skeleton(), u, v, n));
      const double phi = 0.5 * std::numbers::pi * i / (g.rows - 1);
      const double dot = -(n[0] * std::cos(phi) + n[2] * std::sin(phi));
      worst_angle = std::max(worst_angle, std::acos(std::min(1.0, dot)));
      body.top().evaluate(u, v, top);
      body.bottom().evaluate(u, v, bottom);
      // |P + r N| from the axis with N within worst_angle of radial: 0.1 - r to O(r angle^2).
      EXPECT_NEAR(std::hypot(top[0], top[2]), 0.1 - g.radius[k], 1e-7) << i << "," << j;
      EXPECT_NEAR(std::hypot(bottom[0], bottom[2]), 0.1 + g.radius[k], 1e-7) << i << "," << j;
      EXPECT_NEAR(top[1], g.medial[k][1], 1e-15 + 1e-2 * g.radius[k]);
    }
  }
  // A 7-point cubic through a quarter circle: its tangent is off by 3.1e-3 rad at most
  // (at the end rows, where the end conditions bite).
  EXPECT_LT(worst_angle, 5e-3);
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

TEST(MatBody, PoleAtTheFarEndAndCollapsedColumnHaveLimitNormals) {
  // A cap whose apex is the LAST row (u = 1), and its transpose whose apex is the last
  // column (v = 1): the limit normal must agree with the normal just inside the domain.
  for (bool transpose : {false, true}) {
    BodyGrid g;
    g.id = "cap";
    g.rows = transpose ? 8 : 6;
    g.cols = transpose ? 6 : 8;
    for (int i = 0; i < g.rows; ++i) {
      for (int j = 0; j < g.cols; ++j) {
        const int a = transpose ? j : i;  // along the apex direction
        const int b = transpose ? i : j;
        const int na = transpose ? g.cols : g.rows;
        const int nb = transpose ? g.rows : g.cols;
        const double rho = 0.04 * (na - 1 - a) / (na - 1);
        const double phi = 2.0 * b / (nb - 1);
        const bool edge = i == 0 || j == 0 || i == g.rows - 1 || j == g.cols - 1;
        g.medial.push_back({rho * std::cos(phi), rho * std::sin(phi), 0.02 - 5.0 * rho * rho});
        g.radius.push_back(edge ? 0.0 : 0.004);
        g.stiffness.push_back(200.0);
      }
    }
    const auto body = MatBody::fit(g);
    double at_pole[3];
    double near_pole[3];
    const double u = transpose ? 0.5 : 1.0;
    const double v = transpose ? 1.0 : 0.5;
    ASSERT_TRUE(skeleton_normal(body.skeleton(), u, v, at_pole));
    ASSERT_TRUE(skeleton_normal(body.skeleton(), transpose ? u : u - 1e-5, transpose ? v - 1e-5 : v, near_pole));
    const double dot = at_pole[0] * near_pole[0] + at_pole[1] * near_pole[1] + at_pole[2] * near_pole[2];
    EXPECT_GT(dot, 0.999) << (transpose ? "collapsed column" : "pole row at u = 1");
  }
}

TEST(MatBody, AnOvershootingMaterialFieldIsRejectedWithItsPlace) {
  // Stiffness stepping 200 -> 2000 N/m between two rows only 0.1 mm apart (the others are
  // 10 mm apart): the interpolant swings far below zero between the sites, which would
  // make forces pull into the body.
  BodyGrid g;
  g.id = "step";
  g.rows = 7;
  g.cols = 5;
  for (int i = 0; i < g.rows; ++i) {
    for (int j = 0; j < g.cols; ++j) {
      const bool edge = i == 0 || j == 0 || i == g.rows - 1 || j == g.cols - 1;
      g.medial.push_back({i < 3 ? 0.01 * i : 0.0201 + 0.01 * (i - 3), 0.01 * j, 0.0});
      g.radius.push_back(edge ? 0.0 : 0.002);
      g.stiffness.push_back(i < 3 ? 200.0 : 2000.0);
    }
  }
  try {
    (void)MatBody::fit(g);
    FAIL() << "expected FitError";
  } catch (const FitError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("stiffness falls to"), std::string::npos) << what;
    EXPECT_NE(what.find("body 'step'"), std::string::npos) << what;
  }
  // The same rise spread smoothly over the body (linear in x) fits.
  for (std::size_t k = 0; k < g.point_count(); ++k) g.stiffness[k] = 200.0 + 30000.0 * g.medial[k][0];
  EXPECT_NO_THROW((void)MatBody::fit(g));
}

TEST(MatBody, SizeMismatchIsRejected) {
  auto grid = test::flat_body(4, 4);
  grid.radius.pop_back();
  EXPECT_THROW((void)MatBody::fit(grid), FitError);
}

}  // namespace
}  // namespace palpa::mat
