// Basis functions against hand-computed values (The NURBS Book, Ex2.3/Ex2.4) and properties.
#include "palpa/spline/basis.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace palpa::spline {
namespace {

// U = {0,0,0,1,2,3,4,4,5,5,5}, p = 2: 8 basis functions (The NURBS Book, Ex2.3).
const std::vector<double> kBookKnots{0, 0, 0, 1, 2, 3, 4, 4, 5, 5, 5};
constexpr int kBookCount = 8;

TEST(Basis, FindSpanMatchesTheBookExample) {
  EXPECT_EQ(find_span(kBookCount, 2, 2.5, kBookKnots), 4);
  EXPECT_EQ(find_span(kBookCount, 2, 0.0, kBookKnots), 2);
  EXPECT_EQ(find_span(kBookCount, 2, 1.0, kBookKnots), 3);   // a knot starts its own span
  EXPECT_EQ(find_span(kBookCount, 2, 4.0, kBookKnots), 7);   // double knot at 4: [U7, U8) = [4, 5)
}

TEST(Basis, FindSpanAtTheClosedRightEndIsTheLastNonEmptySpan) {
  EXPECT_EQ(find_span(kBookCount, 2, 5.0, kBookKnots), 7);
  EXPECT_EQ(find_span(kBookCount, 2, 4.999999, kBookKnots), 7);
  EXPECT_EQ(find_span(kBookCount, 2, 7.0, kBookKnots), 7);   // beyond the end
  EXPECT_EQ(find_span(kBookCount, 2, -1.0, kBookKnots), 2);  // before the start
}

TEST(Basis, BasisFunctionsMatchTheBookExample) {
  std::array<double, 3> n{};
  basis_functions(4, 2.5, 2, kBookKnots, n.data());
  EXPECT_DOUBLE_EQ(n[0], 1.0 / 8.0);  // N_{2,2}(5/2)
  EXPECT_DOUBLE_EQ(n[1], 6.0 / 8.0);  // N_{3,2}(5/2)
  EXPECT_DOUBLE_EQ(n[2], 1.0 / 8.0);  // N_{4,2}(5/2)
}

TEST(Basis, DerivativesMatchTheBookExample) {
  std::array<double, 9> d{};
  basis_function_derivatives(4, 2.5, 2, 2, kBookKnots, d.data());
  EXPECT_DOUBLE_EQ(d[0], 1.0 / 8.0);
  EXPECT_DOUBLE_EQ(d[3], -0.5);  // N'_{2,2}
  EXPECT_DOUBLE_EQ(d[4], 0.0);   // N'_{3,2}
  EXPECT_DOUBLE_EQ(d[5], 0.5);   // N'_{4,2}
  EXPECT_DOUBLE_EQ(d[6], 1.0);   // N''_{2,2}
  EXPECT_DOUBLE_EQ(d[7], -2.0);
  EXPECT_DOUBLE_EQ(d[8], 1.0);
}

TEST(Basis, DerivativesAboveTheDegreeAreZero) {
  std::array<double, 12> d{};
  d.fill(42.0);
  basis_function_derivatives(4, 2.5, 2, 3, kBookKnots, d.data());
  for (int j = 9; j < 12; ++j) EXPECT_EQ(d[static_cast<std::size_t>(j)], 0.0);
}

TEST(Basis, PartitionOfUnityEverywhereIncludingTheEnds) {
  const std::vector<double> knots{0, 0, 0, 0, 0.1, 0.35, 0.7, 1, 1, 1, 1};
  const int count = 7;
  for (int s = 0; s <= 1000; ++s) {
    const double u = s / 1000.0;
    const int span = find_span(count, 3, u, knots);
    std::array<double, 4> n{};
    basis_functions(span, u, 3, knots, n.data());
    double sum = 0.0;
    for (double x : n) {
      EXPECT_GE(x, -1e-15);
      sum += x;
    }
    EXPECT_NEAR(sum, 1.0, 1e-14) << "u = " << u;
  }
  std::array<double, 4> n{};
  basis_functions(find_span(count, 3, 1.0, knots), 1.0, 3, knots, n.data());
  EXPECT_DOUBLE_EQ(n[3], 1.0);  // only the last function is non-zero at u = 1
}

TEST(Basis, DerivativesAgreeWithFiniteDifferences) {
  const std::vector<double> knots{0, 0, 0, 0, 0.2, 0.45, 0.5, 0.8, 1, 1, 1, 1};
  const int count = 8;
  const int p = 3;
  const double h = 1e-6;
  for (double u : {0.05, 0.3, 0.47, 0.62, 0.93}) {
    const int span = find_span(count, p, u, knots);
    ASSERT_EQ(span, find_span(count, p, u + h, knots));
    ASSERT_EQ(span, find_span(count, p, u - h, knots));
    std::array<double, 12> d{};
    basis_function_derivatives(span, u, p, 2, knots, d.data());
    std::array<double, 4> plus{};
    std::array<double, 4> minus{};
    std::array<double, 4> mid{};
    basis_functions(span, u + h, p, knots, plus.data());
    basis_functions(span, u - h, p, knots, minus.data());
    basis_functions(span, u, p, knots, mid.data());
    for (std::size_t j = 0; j < 4; ++j) {
      EXPECT_NEAR(d[j], mid[j], 1e-15);
      EXPECT_NEAR(d[4 + j], (plus[j] - minus[j]) / (2 * h), 1e-6);
      EXPECT_NEAR(d[8 + j], (plus[j] - 2 * mid[j] + minus[j]) / (h * h), 2e-2);
    }
  }
}

}  // namespace
}  // namespace palpa::spline
