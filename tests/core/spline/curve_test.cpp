// Curves: evaluation, derivatives, and A9.1 interpolation.
#include "palpa/spline/bspline_curve.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "palpa/spline/interpolation.hpp"

namespace palpa::spline {
namespace {

TEST(Curve, RejectsKnotsThatDoNotFit) {
  EXPECT_THROW(BSplineCurve(2, {0, 0, 0, 1, 1}, 1, {0, 1, 2}), std::invalid_argument);  // too few knots
  EXPECT_THROW(BSplineCurve(2, {0, 0, 1, 0, 1, 1}, 1, {0, 1, 2}), std::invalid_argument);  // decreasing
  EXPECT_THROW(BSplineCurve(3, {0, 0, 0, 0, 1, 1, 1}, 1, {0, 1, 2}), std::invalid_argument);  // degree too high
}

TEST(Curve, ClampedEndsAreTheEndControlPoints) {
  const BSplineCurve c(3, {0, 0, 0, 0, 0.4, 1, 1, 1, 1}, 2, {0, 0, 1, 2, 3, 1, 4, 4, 5, 0});
  double out[2];
  c.evaluate(0.0, out);
  EXPECT_EQ(out[0], 0.0);
  EXPECT_EQ(out[1], 0.0);
  c.evaluate(1.0, out);
  EXPECT_DOUBLE_EQ(out[0], 5.0);
  EXPECT_DOUBLE_EQ(out[1], 0.0);
}

TEST(Curve, InterpolationPassesThroughThePointsAndDerivativesMatchFiniteDifferences) {
  std::vector<double> pts;
  const int count = 9;
  for (int k = 0; k < count; ++k) {
    const double t = k * 0.3 + 0.01 * k * k;
    pts.insert(pts.end(), {std::cos(t), std::sin(t), 0.2 * t, 1000.0 * t});  // xyz + a channel in other units
  }
  const auto curve = interpolate_curve(pts, count, 4);
  const auto params = curve_parameters(pts, count, 4, Parameterization::ChordLength);
  double out[4];
  for (int k = 0; k < count; ++k) {
    curve.evaluate(params[static_cast<std::size_t>(k)], out);
    for (int c = 0; c < 4; ++c) {
      const double scale = c == 3 ? 3000.0 : 1.0;
      EXPECT_NEAR(out[c], pts[static_cast<std::size_t>(k * 4 + c)], 1e-13 * scale);
    }
  }
  const double h = 1e-6;
  for (double u : {0.1, 0.33, 0.77}) {
    double d[12];
    double plus[4];
    double minus[4];
    curve.derivatives(u, 2, d);
    curve.evaluate(u + h, plus);
    curve.evaluate(u - h, minus);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(d[4 + c], (plus[c] - minus[c]) / (2 * h), 1e-6);
  }
}

TEST(Curve, ParametersByHand) {
  // Points on the x axis at 0, 1, 5: chord steps 1 and 4, centripetal steps 1 and 2.
  const std::vector<double> pts{0, 0, 0, 1, 0, 0, 5, 0, 0};
  const auto chord = curve_parameters(pts, 3, 3, Parameterization::ChordLength);
  const auto centripetal = curve_parameters(pts, 3, 3, Parameterization::Centripetal);
  EXPECT_DOUBLE_EQ(chord[1], 0.2);
  EXPECT_DOUBLE_EQ(centripetal[1], 1.0 / 3.0);
  EXPECT_EQ(chord[2], 1.0);
}

TEST(Curve, ExactDuplicatePointsAreAClearError) {
  const std::vector<double> pts{0, 0, 0, 1, 0, 0, 1, 0, 0, 2, 0, 0};
  EXPECT_THROW(interpolate_curve(pts, 4, 3), InterpolationError);
}

}  // namespace
}  // namespace palpa::spline
