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

void BSplineSurface::evaluate(double u, double v, std::span<double> out, int channels) const {
  const int nc = (channels <= 0 || channels > dim_) ? dim_ : channels;
  if (out.size() < static_cast<std::size_t>(nc)) throw std::invalid_argument("BSplineSurface::evaluate: output too small");
  // The bicubic case (every body with 4+ points per direction) gets unrolled loops.
  if (degree_u_ == 3 && degree_v_ == 3) {
    evaluate_kernel<3, 3>(u, v, out.data(), nc);
  } else {
    evaluate_kernel<0, 0>(u, v, out.data(), nc);
  }
}

template <int P, int Q>
void BSplineSurface::evaluate_kernel(double u, double v, double* out, int nc) const {
  const int p = P > 0 ? P : degree_u_;
  const int q = Q > 0 ? Q : degree_v_;
  u = detail::clamp_to_knots(u, knots_u_);
  v = detail::clamp_to_knots(v, knots_v_);
  const int span_u = find_span(rows_, p, u, knots_u_);
  const int span_v = find_span(cols_, q, v, knots_v_);
  std::array<double, kOrder> nu;  // written by basis_functions before use
  std::array<double, kOrder> nv;
  basis_functions(span_u, u, p, knots_u_, nu.data());
  basis_functions(span_v, v, q, knots_v_, nv.data());

  std::array<double, kMaxDim> temp;
  std::fill_n(out, nc, 0.0);
  for (int k = 0; k <= p; ++k) {
    std::fill_n(temp.begin(), nc, 0.0);
    const double* row = &control_[static_cast<std::size_t>(((span_u - p + k) * cols_ + span_v - q) * dim_)];
    for (int l = 0; l <= q; ++l) {
      const double* cp = row + l * dim_;
      const double b = nv[static_cast<std::size_t>(l)];
      for (int c = 0; c < nc; ++c) temp[static_cast<std::size_t>(c)] += b * cp[c];
    }
    const double a = nu[static_cast<std::size_t>(k)];
    for (int c = 0; c < nc; ++c) out[c] += a * temp[static_cast<std::size_t>(c)];
  }
}

SurfaceBasis BSplineSurface::basis(double u, double v) const {
  SurfaceBasis b;
  u = detail::clamp_to_knots(u, knots_u_);
  v = detail::clamp_to_knots(v, knots_v_);
  b.span_u = find_span(rows_, degree_u_, u, knots_u_);
  b.span_v = find_span(cols_, degree_v_, v, knots_v_);
  basis_functions(b.span_u, u, degree_u_, knots_u_, b.nu.data());
  basis_functions(b.span_v, v, degree_v_, knots_v_, b.nv.data());
  return b;
}

void BSplineSurface::evaluate(const SurfaceBasis& b, std::span<double> out, int first, int count) const {
  if (first < 0 || count < 1 || first + count > dim_ || out.size() < static_cast<std::size_t>(count)) {
    throw std::invalid_argument("BSplineSurface::evaluate: channel range or output size");
  }
  std::fill_n(out.begin(), count, 0.0);
  for (int k = 0; k <= degree_u_; ++k) {
    const double a = b.nu[static_cast<std::size_t>(k)];
    const double* row =
        &control_[static_cast<std::size_t>(((b.span_u - degree_u_ + k) * cols_ + b.span_v - degree_v_) * dim_ + first)];
    for (int l = 0; l <= degree_v_; ++l) {
      const double w = a * b.nv[static_cast<std::size_t>(l)];
      const double* cp = row + l * dim_;
      for (int c = 0; c < count; ++c) out[static_cast<std::size_t>(c)] += w * cp[c];
    }
  }
}

void BSplineSurface::derivatives(double u, double v, int d, std::span<double> out, int channels) const {
  if (d < 0 || d > kMaxDegree) throw std::invalid_argument("BSplineSurface::derivatives: order outside 0..7");
  const int nc = (channels <= 0 || channels > dim_) ? dim_ : channels;
  if (out.size() < static_cast<std::size_t>((d + 1) * (d + 1) * nc)) {
    throw std::invalid_argument("BSplineSurface::derivatives: output too small");
  }
  if (degree_u_ == 3 && degree_v_ == 3) {
    derivatives_kernel<3, 3>(u, v, d, out.data(), nc);
  } else {
    derivatives_kernel<0, 0>(u, v, d, out.data(), nc);
  }
}

template <int P, int Q>
void BSplineSurface::derivatives_kernel(double u, double v, int d, double* out, int nc) const {
  const int p = P > 0 ? P : degree_u_;
  const int q = Q > 0 ? Q : degree_v_;
  u = detail::clamp_to_knots(u, knots_u_);
  v = detail::clamp_to_knots(v, knots_v_);
  const int du = std::min(d, p);
  const int dv = std::min(d, q);
  const int span_u = find_span(rows_, p, u, knots_u_);
  const int span_v = find_span(cols_, q, v, knots_v_);
  // Scratch on the stack, left uninitialized: every entry read below is written first.
  std::array<double, kOrder * kOrder> nu;
  std::array<double, kOrder * kOrder> nv;
  basis_function_derivatives(span_u, u, p, du, knots_u_, nu.data());
  basis_function_derivatives(span_v, v, q, dv, knots_v_, nv.data());

  std::fill_n(out, (d + 1) * (d + 1) * nc, 0.0);
  // temp[s] holds sum_r N_v^(l)[r] * P[row s][r] for the current l (A3.6).
  std::array<double, kOrder * kMaxDim> temp;
  for (int l = 0; l <= dv; ++l) {
    for (int s = 0; s <= p; ++s) {
      double* ts = &temp[static_cast<std::size_t>(s * nc)];
      std::fill_n(ts, nc, 0.0);
      const double* row = &control_[static_cast<std::size_t>(((span_u - p + s) * cols_ + span_v - q) * dim_)];
      for (int r = 0; r <= q; ++r) {
        const double b = nv[static_cast<std::size_t>(l * (q + 1) + r)];
        const double* cp = row + r * dim_;
        for (int c = 0; c < nc; ++c) ts[c] += b * cp[c];
      }
    }
    for (int k = 0; k <= std::min(du, d - l); ++k) {
      double* o = out + derivative_index(k, l, d, nc, 0);
      for (int s = 0; s <= p; ++s) {
        const double a = nu[static_cast<std::size_t>(k * (p + 1) + s)];
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
