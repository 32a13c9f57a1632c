#include "knot_checks.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "palpa/spline/basis.hpp"

namespace palpa::spline::detail {

void check_knots(std::span<const double> knots, int degree, int count, const char* what) {
  if (degree < 1 || degree > kMaxDegree) {
    throw std::invalid_argument(fmt::format("{}: degree {} outside 1..{}", what, degree, kMaxDegree));
  }
  if (count <= degree) {
    throw std::invalid_argument(
        fmt::format("{}: {} control points are too few for degree {}", what, count, degree));
  }
  if (knots.size() != static_cast<std::size_t>(count + degree + 1)) {
    throw std::invalid_argument(fmt::format("{}: expected {} knots, got {}", what, count + degree + 1, knots.size()));
  }
  for (std::size_t i = 0; i < knots.size(); ++i) {
    if (!std::isfinite(knots[i]) || (i > 0 && knots[i] < knots[i - 1])) {
      throw std::invalid_argument(fmt::format("{}: knots must be finite and non-decreasing (index {})", what, i));
    }
  }
  if (!(knots.back() > knots.front())) {
    throw std::invalid_argument(std::string(what) + ": empty knot range");
  }
  // Clamped ends: the curve starts and ends at its end control points, and the basis
  // recurrences never divide by a zero-length end interval.
  const auto p = static_cast<std::size_t>(degree);
  for (std::size_t i = 1; i <= p; ++i) {
    if (knots[i] != knots[0] || knots[knots.size() - 1 - i] != knots.back()) {
      throw std::invalid_argument(std::string(what) + ": knots must be clamped (degree + 1 equal knots at each end)");
    }
  }
}

double clamp_to_knots(double u, std::span<const double> knots) {
  if (!(u >= knots.front())) return knots.front();  // also maps NaN to the left end
  if (u > knots.back()) return knots.back();
  return u;
}

}  // namespace palpa::spline::detail
