#include "palpa/spline/bspline_curve.hpp"

#include <array>
#include <stdexcept>

#include "knot_checks.hpp"
#include "palpa/spline/basis.hpp"

namespace palpa::spline {
namespace {
constexpr int kOrder = kMaxDegree + 1;
}

BSplineCurve::BSplineCurve(int degree, std::vector<double> knots, int dim, std::vector<double> control)
    : degree_(degree), dim_(dim), knots_(std::move(knots)), control_(std::move(control)) {
  if (dim_ < 1 || control_.size() % static_cast<std::size_t>(dim_) != 0) {
    throw std::invalid_argument("BSplineCurve: control values do not divide into points of dimension dim");
  }
  detail::check_knots(knots_, degree_, control_points(), "BSplineCurve");
}

void BSplineCurve::evaluate(double u, std::span<double> out) const {
  if (out.size() < static_cast<std::size_t>(dim_)) throw std::invalid_argument("BSplineCurve::evaluate: output too small");
  u = detail::clamp_to_knots(u, knots_);
  const int span = find_span(control_points(), degree_, u, knots_);
  std::array<double, kOrder> n{};
  basis_functions(span, u, degree_, knots_, n.data());
  for (int c = 0; c < dim_; ++c) out[static_cast<std::size_t>(c)] = 0.0;
  for (int j = 0; j <= degree_; ++j) {
    const double* cp = &control_[static_cast<std::size_t>((span - degree_ + j) * dim_)];
    for (int c = 0; c < dim_; ++c) out[static_cast<std::size_t>(c)] += n[static_cast<std::size_t>(j)] * cp[c];
  }
}

void BSplineCurve::derivatives(double u, int d, std::span<double> out) const {
  if (d < 0 || d > kMaxDegree || out.size() < static_cast<std::size_t>((d + 1) * dim_)) {
    throw std::invalid_argument("BSplineCurve::derivatives: order outside 0..7 or output too small");
  }
  u = detail::clamp_to_knots(u, knots_);
  const int span = find_span(control_points(), degree_, u, knots_);
  std::array<double, kOrder * kOrder> ders{};
  const int dk = d < degree_ ? d : degree_;
  basis_function_derivatives(span, u, degree_, dk, knots_, ders.data());
  for (std::size_t i = 0; i < static_cast<std::size_t>((d + 1) * dim_); ++i) out[i] = 0.0;
  for (int k = 0; k <= dk; ++k) {
    for (int j = 0; j <= degree_; ++j) {
      const double b = ders[static_cast<std::size_t>(k * (degree_ + 1) + j)];
      const double* cp = &control_[static_cast<std::size_t>((span - degree_ + j) * dim_)];
      for (int c = 0; c < dim_; ++c) out[static_cast<std::size_t>(k * dim_ + c)] += b * cp[c];
    }
  }
}

}  // namespace palpa::spline
