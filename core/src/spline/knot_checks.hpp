#pragma once
// Shared validation of a clamped, non-decreasing knot vector.
#include <span>

namespace palpa::spline::detail {

/// Throws std::invalid_argument naming `what` unless knots has count + degree + 1
/// non-decreasing finite entries and 1 <= degree <= kMaxDegree, count > degree.
void check_knots(std::span<const double> knots, int degree, int count, const char* what);

/// Clamp a parameter into the knot range [knots.front(), knots.back()].
double clamp_to_knots(double u, std::span<const double> knots);

}  // namespace palpa::spline::detail
