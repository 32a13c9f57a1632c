#include "palpa/spline/bspline_surface.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "knot_checks.hpp"
#include "palpa/spline/basis.hpp"

namespace palpa::spline {
namespace {
constexpr int kOrder = kMaxDegree + 1;
// Enough for the channels of the skeleton and then some; evaluation stays on the stack.
constexpr int kMaxDim = 16;
}  // namespace

BSplineSurface::BSplineSurface(int degree_u, int degree_v, std::vector<double> knots_u,
                               std::vector<double> knots_v, int rows, int cols, int dim,
                               std::vector<double> control)
    : degree_u_(degree_u),
      degree_v_(degree_v),
      rows_(rows),
      cols_(cols),
      dim_(dim),
      knots_u_(std::move(knots_u)),
      knots_v_(std::move(knots_v)),
      control_(std::move(control)) {
  if (dim_ < 1 || dim_ > kMaxDim) throw std::invalid_argument("BSplineSurface: dimension outside 1..16");
  if (rows_ < 2 || cols_ < 2 ||
      control_.size() != static_cast<std::size_t>(rows_) * static_cast<std::size_t>(cols_) *
                             static_cast<std::size_t>(dim_)) {
    throw std::invalid_argument("BSplineSurface: control values do not match rows * cols * dim");
  }
  detail::check_knots(knots_u_, degree_u_, rows_, "BSplineSurface (u)");
  detail::check_knots(knots_v_, degree_v_, cols_, "BSplineSurface (v)");
}

std::span<const double> BSplineSurface::control_point(int i, int j) const {
  return {&control_[static_cast<std::size_t>((i * cols_ + j) * dim_)], static_cast<std::size_t>(dim_)};
}

std::span<double> BSplineSurface::control_point(int i, int j) {
  return {&control_[static_cast<std::size_t>((i * cols_ + j) * dim_)], static_cast<std::size_t>(dim_)};
}

void BSplineSurface::evaluate(double u, double v, std::span<double> out) const {
  if (out.size() < static_cast<std::size_t>(dim_)) throw std::invalid_argument("BSplineSurface::evaluate: output too small");
  u = detail::clamp_to_knots(u, knots_u_);
  v = detail::clamp_to_knots(v, knots_v_);
  const int span_u = find_span(rows_, degree_u_, u, knots_u_);
  const int span_v = find_span(cols_, degree_v_, v, knots_v_);
  std::array<double, kOrder> nu{};
  std::array<double, kOrder> nv{};
  basis_functions(span_u, u, degree_u_, knots_u_, nu.data());
  basis_functions(span_v, v, degree_v_, knots_v_, nv.data());

  std::array<double, kMaxDim> temp{};
  std::fill_n(out.begin(), dim_, 0.0);
  for (int k = 0; k <= degree_u_; ++k) {
    std::fill_n(temp.begin(), dim_, 0.0);
    const int row = span_u - degree_u_ + k;
    for (int l = 0; l <= degree_v_; ++l) {
      const double* cp = &control_[static_cast<std::size_t>((row * cols_ + span_v - degree_v_ + l) * dim_)];
      const double b = nv[static_cast<std::size_t>(l)];
      for (int c = 0; c < dim_; ++c) temp[static_cast<std::size_t>(c)] += b * cp[c];
    }
    const double a = nu[static_cast<std::size_t>(k)];
    for (int c = 0; c < dim_; ++c) out[static_cast<std::size_t>(c)] += a * temp[static_cast<std::size_t>(c)];
  }
}

void BSplineSurface::derivatives(double u, double v, int d, std::span<double> out, int channels) const {
  if (d < 0 || d > kMaxDegree) throw std::invalid_argument("BSplineSurface::derivatives: order outside 0..7");
  const int nc = (channels <= 0 || channels > dim_) ? dim_ : channels;
  if (out.size() < static_cast<std::size_t>((d + 1) * (d + 1) * nc)) {
    throw std::invalid_argument("BSplineSurface::derivatives: output too small");
  }
  u = detail::clamp_to_knots(u, knots_u_);
  v = detail::clamp_to_knots(v, knots_v_);
  const int du = std::min(d, degree_u_);
  const int dv = std::min(d, degree_v_);
  const int span_u = find_span(rows_, degree_u_, u, knots_u_);
  const int span_v = find_span(cols_, degree_v_, v, knots_v_);
  // Scratch on the stack, left uninitialized: every entry read below is written first.
  std::array<double, kOrder * kOrder> nu;  // NOLINT(cppcoreguidelines-pro-type-member-init)
  std::array<double, kOrder * kOrder> nv;  // NOLINT(cppcoreguidelines-pro-type-member-init)
  basis_function_derivatives(span_u, u, degree_u_, du, knots_u_, nu.data());
  basis_function_derivatives(span_v, v, degree_v_, dv, knots_v_, nv.data());

  std::fill_n(out.begin(), (d + 1) * (d + 1) * nc, 0.0);
  // temp[s] holds sum_r N_v^(l)[r] * P[row s][r] for the current l (A3.6).
  std::array<double, kOrder * kMaxDim> temp;  // NOLINT(cppcoreguidelines-pro-type-member-init)
  for (int l = 0; l <= dv; ++l) {
    for (int s = 0; s <= degree_u_; ++s) {
      double* ts = &temp[static_cast<std::size_t>(s * nc)];
      std::fill_n(ts, nc, 0.0);
      const int row = span_u - degree_u_ + s;
      for (int r = 0; r <= degree_v_; ++r) {
        const double b = nv[static_cast<std::size_t>(l * (degree_v_ + 1) + r)];
        const double* cp = &control_[static_cast<std::size_t>((row * cols_ + span_v - degree_v_ + r) * dim_)];
        for (int c = 0; c < nc; ++c) ts[c] += b * cp[c];
      }
    }
    for (int k = 0; k <= std::min(du, d - l); ++k) {
      double* o = &out[derivative_index(k, l, d, nc, 0)];
      for (int s = 0; s <= degree_u_; ++s) {
        const double a = nu[static_cast<std::size_t>(k * (degree_u_ + 1) + s)];
        const double* ts = &temp[static_cast<std::size_t>(s * nc)];
        for (int c = 0; c < nc; ++c) o[c] += a * ts[c];
      }
    }
  }
}

std::size_t BSplineSurface::memory_bytes() const {
  return sizeof(*this) + (knots_u_.capacity() + knots_v_.capacity() + control_.capacity()) * sizeof(double);
}

}  // namespace palpa::spline
