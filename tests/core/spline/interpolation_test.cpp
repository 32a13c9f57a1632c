// A9.4 global surface interpolation: data reproduction, polynomial reproduction, an
// independent dense reference, and numerical stress cases (duplicates, poles, mixed units).
#include "palpa/spline/interpolation.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "palpa/spline/basis.hpp"
#include "../support/test_grids.hpp"

namespace palpa::spline {
namespace {

using test::make_grid;
using test::wavy_grid;

// Cox-de Boor recursion, written independently of A2.2, with the closed right end.
double cox_de_boor(int i, int p, double u, const std::vector<double>& U) {
  const auto k = [&](int a) { return U[static_cast<std::size_t>(a)]; };
  if (p == 0) {
    if (u == U.back()) return (k(i) < u && u <= k(i + 1)) ? 1.0 : 0.0;
    return (k(i) <= u && u < k(i + 1)) ? 1.0 : 0.0;
  }
  double a = 0.0;
  double b = 0.0;
  if (k(i + p) > k(i)) a = (u - k(i)) / (k(i + p) - k(i)) * cox_de_boor(i, p - 1, u, U);
  if (k(i + p + 1) > k(i + 1)) b = (k(i + p + 1) - u) / (k(i + p + 1) - k(i + 1)) * cox_de_boor(i + 1, p - 1, u, U);
  return a + b;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// Max |S(ubar_i, vbar_j) - Q_ij| per channel, relative to the channel's magnitude.
double data_residual(const GridInterpolator& g, const BSplineSurface& s, const std::vector<double>& data, int dim) {
  std::vector<double> scale(static_cast<std::size_t>(dim), 0.0);
  for (std::size_t k = 0; k < data.size(); ++k) {
    scale[k % static_cast<std::size_t>(dim)] = std::max(scale[k % static_cast<std::size_t>(dim)], std::abs(data[k]));
  }
  double worst = 0.0;
  std::vector<double> out(static_cast<std::size_t>(dim));
  for (int i = 0; i < g.rows(); ++i) {
    for (int j = 0; j < g.cols(); ++j) {
      s.evaluate(g.u_params()[static_cast<std::size_t>(i)], g.v_params()[static_cast<std::size_t>(j)], out);
      for (int c = 0; c < dim; ++c) {
        const double d = std::abs(out[static_cast<std::size_t>(c)] -
                                  data[static_cast<std::size_t>((i * g.cols() + j) * dim + c)]);
        worst = std::max(worst, d / std::max(scale[static_cast<std::size_t>(c)], 1e-300));
      }
    }
  }
  return worst;
}

TEST(Interpolation, PassesThroughTheDataTo1e12Relative) {
  for (auto [rows, cols] : {std::pair{2, 2}, std::pair{2, 7}, std::pair{3, 9}, std::pair{9, 3}, std::pair{4, 4},
                            std::pair{7, 9}, std::pair{16, 16}, std::pair{64, 64}}) {
    const auto data = wavy_grid(rows, cols);
    const auto g = GridInterpolator::from_grid(data, rows, cols, 7);
    const auto s = g.interpolate(data, 7);
    EXPECT_EQ(s.degree_u(), std::min(3, rows - 1));
    EXPECT_EQ(s.degree_v(), std::min(3, cols - 1));
    EXPECT_LT(data_residual(g, s, data, 7), 1e-12) << rows << "x" << cols;
  }
}

TEST(Interpolation, AgreesWithADenseKroneckerSolveOfTheSameSystem) {
  // Independent path: the full (m n) x (m n) tensor collocation matrix from Cox-de Boor
  // values, solved densely with pivoting; the banded, separable solve must match it.
  for (auto [rows, cols] : {std::pair{3, 5}, std::pair{6, 4}, std::pair{7, 9}}) {
    const int dim = 7;
    const auto data = wavy_grid(rows, cols, dim);
    const auto g = GridInterpolator::from_grid(data, rows, cols, dim);
    const auto s = g.interpolate(data, dim);
    const int n = rows * cols;
    Eigen::MatrixXd a(n, n);
    for (int i = 0; i < rows; ++i)
      for (int j = 0; j < cols; ++j)
        for (int k = 0; k < rows; ++k)
          for (int l = 0; l < cols; ++l)
            a(i * cols + j, k * cols + l) = cox_de_boor(k, g.degree_u(), g.u_params()[static_cast<std::size_t>(i)], g.knots_u()) *
                                            cox_de_boor(l, g.degree_v(), g.v_params()[static_cast<std::size_t>(j)], g.knots_v());
    Eigen::MatrixXd b(n, dim);
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < dim; ++c) b(r, c) = data[static_cast<std::size_t>(r * dim + c)];
    const Eigen::MatrixXd x = a.fullPivLu().solve(b);
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < dim; ++c) {
        const double got = s.control()[static_cast<std::size_t>(r * dim + c)];
        EXPECT_NEAR(got, x(r, c), 1e-10 * std::max(1.0, std::abs(x(r, c)))) << rows << "x" << cols;
      }
    }
  }
}

TEST(Interpolation, ReproducesPolynomialsOfTheDegreeOnUniformGrids) {
  // A uniform planar grid gets uniform parameters, so x and y are linear in u and v and
  // f(x, y) of degree <= (p, q) is a polynomial in (u, v) the spline space contains.
  const int rows = 8;
  const int cols = 6;
  auto f = [](double x, double y) { return 1.0 + 2 * x - 3 * y + x * x * y - 4 * x * x * x * y * y * y + y * y; };
  const auto data = make_grid(rows, cols, 4, [&](int i, int j, int c) {
    const double x = 0.5 * i;
    const double y = -1.0 + 0.25 * j;
    return c == 0 ? x : c == 1 ? y : c == 2 ? 0.0 : f(x, y);
  });
  const auto g = GridInterpolator::from_grid(data, rows, cols, 4);
  const auto s = g.interpolate(data, 4);
  std::vector<double> out(4);
  for (double u = 0.0; u <= 1.0; u += 0.0625) {
    for (double v = 0.0; v <= 1.0; v += 0.05) {
      s.evaluate(u, v, out);
      const double x = 0.5 * (rows - 1) * u;
      const double y = -1.0 + 0.25 * (cols - 1) * v;
      EXPECT_NEAR(out[0], x, 1e-13);
      EXPECT_NEAR(out[1], y, 1e-13);
      EXPECT_NEAR(out[3], f(x, y), 1e-11);
    }
  }
}

TEST(Interpolation, ParametersAreAveragedOverLinesAndSkipCollapsedOnes) {
  // 3 rows x 2 cols. Column 0 along u: x = 0, 1, 3 -> 0, 1/3, 1. Column 1: x = 0, 3, 4 -> 0, 3/4, 1.
  const std::vector<double> two_cols{0, 0, 0, 0, 5, 0, 1, 0, 0, 3, 5, 0, 3, 0, 0, 4, 5, 0};
  const auto u = grid_parameters_u(two_cols, 3, 2, 3, Parameterization::ChordLength);
  EXPECT_DOUBLE_EQ(u[1], (1.0 / 3.0 + 0.75) / 2.0);
  // Column 1 collapsed to one point: only column 0 counts.
  const std::vector<double> pole_col{0, 0, 0, 9, 9, 9, 1, 0, 0, 9, 9, 9, 3, 0, 0, 9, 9, 9};
  const auto u2 = grid_parameters_u(pole_col, 3, 2, 3, Parameterization::ChordLength);
  EXPECT_DOUBLE_EQ(u2[1], 1.0 / 3.0);
}

TEST(Interpolation, ParametersIgnoreTheMaterialChannels) {
  auto data = wavy_grid(7, 9);
  const auto g1 = GridInterpolator::from_grid(data, 7, 9, 7);
  for (std::size_t k = 3; k < data.size(); k += 7) {
    data[k + 1] *= 1e6;  // stiffness in wildly different units must not move the parameters
  }
  const auto g2 = GridInterpolator::from_grid(data, 7, 9, 7);
  EXPECT_EQ(g1.u_params(), g2.u_params());
  EXPECT_EQ(g1.v_params(), g2.v_params());
}

TEST(Interpolation, KnotsByAveragingByHand) {
  const std::vector<double> params{0, 0.2, 0.5, 0.6, 1};
  const auto knots = averaging_knots(params, 2);
  const std::vector<double> expected{0, 0, 0, 0.35, 0.55, 1, 1, 1};
  ASSERT_EQ(knots.size(), expected.size());
  for (std::size_t i = 0; i < knots.size(); ++i) EXPECT_DOUBLE_EQ(knots[i], expected[i]);
}

TEST(Interpolation, CollocationStaysInsideTheDegreeBand) {
  const auto data = wavy_grid(32, 20);
  const auto u = grid_parameters_u(data, 32, 20, 7, Parameterization::ChordLength);
  const auto knots = averaging_knots(u, 3);
  const CollocationSolver solver(u, knots, 3);
  EXPECT_LE(solver.lower_bandwidth(), 3);
  EXPECT_LE(solver.upper_bandwidth(), 3);
}

TEST(Interpolation, CornersAndEdgesAtParametersZeroAndOne) {
  const int rows = 5;
  const int cols = 6;
  const auto data = wavy_grid(rows, cols);
  const auto g = GridInterpolator::from_grid(data, rows, cols, 7);
  const auto s = g.interpolate(data, 7);
  std::vector<double> out(7);
  for (int i : {0, rows - 1}) {
    for (int j : {0, cols - 1}) {
      s.evaluate(i == 0 ? 0.0 : 1.0, j == 0 ? 0.0 : 1.0, out);
      for (int c = 0; c < 7; ++c)
        EXPECT_NEAR(out[static_cast<std::size_t>(c)], data[static_cast<std::size_t>((i * cols + j) * 7 + c)],
                    1e-14 * (1 + std::abs(out[static_cast<std::size_t>(c)])));
    }
  }
}

TEST(Interpolation, PoleRowIsFiniteAndCollapsesToThePole) {
  // Row 0 is a single point (a pole, as at the tip of a dome).
  const int rows = 6;
  const int cols = 7;
  const auto data = make_grid(rows, cols, 3, [&](int i, int j, int c) {
    const double rho = 0.05 * i / (rows - 1);
    const double phi = 1.5 * j / (cols - 1);
    return c == 0 ? rho * std::cos(phi) : c == 1 ? rho * std::sin(phi) : 0.03 - 10 * rho * rho;
  });
  const auto g = GridInterpolator::from_grid(data, rows, cols, 3);
  const auto s = g.interpolate(data, 3);
  std::vector<double> out(3);
  for (double v = 0.0; v <= 1.0; v += 0.1) {
    s.evaluate(0.0, v, out);
    EXPECT_NEAR(out[0], 0.0, 1e-15);
    EXPECT_NEAR(out[1], 0.0, 1e-15);
    EXPECT_NEAR(out[2], 0.03, 1e-15);
  }
  EXPECT_LT(data_residual(g, s, data, 3), 1e-12);
}

class NearDuplicate : public ::testing::TestWithParam<double> {};

TEST_P(NearDuplicate, StaysFiniteAndPassesThroughTheData) {
  // Row 3 sits `gap` after row 2 (a near-duplicate row).
  const double gap = GetParam();
  const int rows = 7;
  const int cols = 5;
  const auto data = make_grid(rows, cols, 4, [&](int i, int j, int c) {
    const double x = i <= 2 ? 0.01 * i : 0.02 + gap + 0.01 * (i - 3);
    return c == 0 ? x : c == 1 ? 0.01 * j : c == 2 ? 0.001 * std::sin(30 * x) : 100.0 + x;
  });
  const auto g = GridInterpolator::from_grid(data, rows, cols, 4);
  const auto s = g.interpolate(data, 4);
  for (double c : s.control()) ASSERT_TRUE(std::isfinite(c));
  // The collocation conditioning grows like 1/gap, yet elimination on a totally positive
  // matrix is backward stable: the data are still met to round-off.
  EXPECT_LT(data_residual(g, s, data, 4), 1e-12) << "gap " << gap;
}

INSTANTIATE_TEST_SUITE_P(Gaps, NearDuplicate, ::testing::Values(1e-3, 1e-6, 1e-9));

TEST(Interpolation, NearDuplicateWithAJumpInAnotherCoordinateStaysFinite) {
  // Rows 2 and 3 nearly coincide in x but jump in z: chord length overshoots, centripetal less so.
  const auto data = make_grid(6, 4, 3, [](int i, int j, int c) {
    const double x = i <= 2 ? 0.01 * i : 0.02 + 1e-6 + 0.01 * (i - 3);
    return c == 0 ? x : c == 1 ? 0.01 * j : (i >= 3 ? 0.01 : 0.0);
  });
  for (auto method : {Parameterization::ChordLength, Parameterization::Centripetal}) {
    const auto g = GridInterpolator::from_grid(data, 6, 4, 3, {method, 3});
    const auto s = g.interpolate(data, 3);
    for (double c : s.control()) ASSERT_TRUE(std::isfinite(c));
    EXPECT_LT(data_residual(g, s, data, 3), 1e-12);
  }
}

TEST(Interpolation, ExactDuplicateRowsAreAClearErrorNotNaN) {
  const auto data = make_grid(5, 4, 3, [](int i, int j, int c) {
    const int ii = i >= 3 ? i - 1 : i;  // rows 2 and 3 identical
    return c == 0 ? 0.01 * ii : c == 1 ? 0.01 * j : 0.0;
  });
  try {
    (void)GridInterpolator::from_grid(data, 5, 4, 3);
    FAIL() << "expected InterpolationError";
  } catch (const InterpolationError& e) {
    EXPECT_NE(std::string(e.what()).find("coincident"), std::string::npos) << e.what();
  }
}

TEST(Interpolation, DegreesAboveTheSupportedMaximumAreRejected) {
  const std::vector<double> params{0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1};
  EXPECT_THROW((void)averaging_knots(params, kMaxDegree + 1), InterpolationError);
  const auto data = wavy_grid(12, 12);
  const auto g = GridInterpolator::from_grid(data, 12, 12, 7, {Parameterization::ChordLength, 9});
  EXPECT_EQ(g.degree_u(), kMaxDegree);  // asked for 9, clamped to what the evaluators support
}

TEST(Interpolation, CollapsedGridIsAClearError) {
  const auto data = make_grid(3, 3, 3, [](int, int, int) { return 0.5; });
  EXPECT_THROW((void)GridInterpolator::from_grid(data, 3, 3, 3), InterpolationError);
}

TEST(Interpolation, MixedUnitsKeepEachChannelAccurate) {
  // Stiffness ~1e3 N/m beside positions ~1e-2 m (mixed units).
  const auto data = wavy_grid(9, 11);
  const auto g = GridInterpolator::from_grid(data, 9, 11, 7);
  const auto s = g.interpolate(data, 7);
  EXPECT_LT(data_residual(g, s, data, 7), 1e-12);
  EXPECT_LT(max_abs(s.control()), 1e4);
}

}  // namespace
}  // namespace palpa::spline
