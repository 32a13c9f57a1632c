// Surface evaluation and A3.6 derivatives against finite differences and hand values.
#include "palpa/spline/bspline_surface.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace palpa::spline {
namespace {

BSplineSurface random_surface(int dim) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  const int rows = 6;
  const int cols = 5;
  std::vector<double> control(static_cast<std::size_t>(rows * cols * dim));
  for (auto& x : control) x = dist(rng);
  return {3, 2, {0, 0, 0, 0, 0.3, 0.55, 1, 1, 1, 1}, {0, 0, 0, 0.4, 0.45, 1, 1, 1}, rows, cols, dim, control};
}

TEST(Surface, ValueOfDerivativesEqualsEvaluate) {
  const auto s = random_surface(7);
  std::vector<double> ders(9 * 7);
  std::vector<double> val(7);
  for (double u : {0.0, 0.2, 0.3, 0.77, 1.0}) {
    for (double v : {0.0, 0.41, 0.45, 0.9, 1.0}) {
      s.derivatives(u, v, 2, ders);
      s.evaluate(u, v, val);
      for (int c = 0; c < 7; ++c) EXPECT_NEAR(ders[derivative_index(0, 0, 2, 7, c)], val[static_cast<std::size_t>(c)], 1e-14);
    }
  }
}

TEST(Surface, DerivativesUpToSecondOrderAgreeWithFiniteDifferences) {
  const auto s = random_surface(4);
  const double h = 1e-5;
  std::vector<double> d(9 * 4);
  auto at = [&](double u, double v, int c) {
    std::vector<double> out(4);
    s.evaluate(u, v, out);
    return out[static_cast<std::size_t>(c)];
  };
  for (double u : {0.1, 0.42, 0.8}) {
    for (double v : {0.2, 0.6, 0.95}) {
      s.derivatives(u, v, 2, d);
      for (int c = 0; c < 4; ++c) {
        const double su = (at(u + h, v, c) - at(u - h, v, c)) / (2 * h);
        const double sv = (at(u, v + h, c) - at(u, v - h, c)) / (2 * h);
        const double suu = (at(u + h, v, c) - 2 * at(u, v, c) + at(u - h, v, c)) / (h * h);
        const double svv = (at(u, v + h, c) - 2 * at(u, v, c) + at(u, v - h, c)) / (h * h);
        const double suv =
            (at(u + h, v + h, c) - at(u + h, v - h, c) - at(u - h, v + h, c) + at(u - h, v - h, c)) / (4 * h * h);
        EXPECT_NEAR(d[derivative_index(1, 0, 2, 4, c)], su, 1e-6);
        EXPECT_NEAR(d[derivative_index(0, 1, 2, 4, c)], sv, 1e-6);
        EXPECT_NEAR(d[derivative_index(2, 0, 2, 4, c)], suu, 1e-3 * (1 + std::abs(suu)));
        EXPECT_NEAR(d[derivative_index(0, 2, 2, 4, c)], svv, 1e-3 * (1 + std::abs(svv)));
        EXPECT_NEAR(d[derivative_index(1, 1, 2, 4, c)], suv, 1e-3 * (1 + std::abs(suv)));
        EXPECT_EQ(d[derivative_index(2, 1, 2, 4, c)], 0.0);  // k + l > d is not computed
      }
    }
  }
}

TEST(Surface, CornersAreTheCornerControlPointsAndParametersAreClamped) {
  const auto s = random_surface(3);
  std::vector<double> out(3);
  const std::pair<double, double> corners[] = {{0, 0}, {0, 1}, {1, 0}, {1, 1}};
  for (auto [u, v] : corners) {
    s.evaluate(u, v, out);
    const auto cp = s.control_point(u == 0 ? 0 : s.rows() - 1, v == 0 ? 0 : s.cols() - 1);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(out[static_cast<std::size_t>(c)], cp[static_cast<std::size_t>(c)], 1e-15);
  }
  std::vector<double> clamped(3);
  s.evaluate(-0.5, 1.5, clamped);
  s.evaluate(0.0, 1.0, out);
  EXPECT_EQ(clamped, out);
  s.evaluate(std::nan(""), 0.5, clamped);  // NaN parameters never propagate
  for (double x : clamped) EXPECT_TRUE(std::isfinite(x));
}

TEST(Surface, DerivativesOnTheDomainBoundaryAgreeWithOneSidedDifferences) {
  const auto s = random_surface(3);
  const double h = 1e-6;
  std::vector<double> d(4 * 3);
  std::vector<double> a(3);
  std::vector<double> b(3);
  for (double u : {0.0, 1.0}) {
    for (double v : {0.0, 0.37, 1.0}) {
      s.derivatives(u, v, 1, d);
      const double du = u == 0.0 ? h : -h;
      const double dv = v == 1.0 ? -h : h;
      s.evaluate(u, v, a);
      s.evaluate(u + du, v, b);
      for (int c = 0; c < 3; ++c) {
        const auto uc = static_cast<std::size_t>(c);
        EXPECT_NEAR(d[derivative_index(1, 0, 1, 3, c)], (b[uc] - a[uc]) / du, 2e-4) << u << "," << v;
      }
      s.evaluate(u, v + dv, b);
      for (int c = 0; c < 3; ++c) {
        const auto uc = static_cast<std::size_t>(c);
        EXPECT_NEAR(d[derivative_index(0, 1, 1, 3, c)], (b[uc] - a[uc]) / dv, 2e-4) << u << "," << v;
      }
    }
  }
}

TEST(Surface, RejectsInconsistentConstruction) {
  EXPECT_THROW(BSplineSurface(3, 3, {0, 0, 0, 0, 1, 1, 1, 1}, {0, 0, 0, 0, 1, 1, 1, 1}, 4, 4, 3,
                              std::vector<double>(10)),
               std::invalid_argument);
  EXPECT_THROW(BSplineSurface(3, 3, {0, 0, 0, 0, 1, 1, 1}, {0, 0, 0, 0, 1, 1, 1, 1}, 4, 4, 3,
                              std::vector<double>(48)),
               std::invalid_argument);
  // Unclamped ends would divide by a zero-length end interval.
  EXPECT_THROW(BSplineSurface(1, 1, {0, 0.5, 0.5, 1}, {0, 0, 1, 1}, 2, 2, 3, std::vector<double>(12)),
               std::invalid_argument);
}

}  // namespace
}  // namespace palpa::spline
