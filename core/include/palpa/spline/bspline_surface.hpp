#pragma once
// Non-rational tensor-product B-spline surface with control points of any dimension:
// the skeleton SK carries xyz + radius + material channels, the contours carry xyz.
#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace palpa::spline {

/// The non-zero basis functions at one (u, v): computed once, they evaluate every
/// surface on the same knots (the skeleton and both contours of a MAT body share them).
struct SurfaceBasis {
  int span_u = 0;
  int span_v = 0;
  std::array<double, 8> nu{};  // N[span_u - p .. span_u](u)
  std::array<double, 8> nv{};
};

class BSplineSurface {
 public:
  /// control: rows * cols control points of `dim` values, row-major:
  /// point (i, j) at [(i*cols + j)*dim, +dim); i runs along u, j along v.
  /// Throws std::invalid_argument when knots, degrees and counts do not fit.
  BSplineSurface(int degree_u, int degree_v, std::vector<double> knots_u, std::vector<double> knots_v,
                 int rows, int cols, int dim, std::vector<double> control);

  int degree_u() const { return degree_u_; }
  int degree_v() const { return degree_v_; }
  int rows() const { return rows_; }
  int cols() const { return cols_; }
  int dim() const { return dim_; }
  const std::vector<double>& knots_u() const { return knots_u_; }
  const std::vector<double>& knots_v() const { return knots_v_; }
  const std::vector<double>& control() const { return control_; }
  std::span<const double> control_point(int i, int j) const;
  std::span<double> control_point(int i, int j);

  /// S(u, v) into out[0..dim) (only the first `channels` channels when 0 < channels < dim).
  /// u and v are clamped to [0, 1] (the knot range).
  void evaluate(double u, double v, std::span<double> out, int channels = 0) const;

  /// The basis functions at (u, v), clamped into the knot range.
  SurfaceBasis basis(double u, double v) const;

  /// S at the parameters of `basis` (made by this surface or one with the same degrees
  /// and knots), channels [first, first + count) into out[0..count).
  void evaluate(const SurfaceBasis& basis, std::span<double> out, int first, int count) const;

  /// A3.6 SurfaceDerivsAlg1: out[((k*(d+1)) + l)*channels + c] = d^(k+l) S_c / du^k dv^l
  /// for k + l <= d and the first `channels` channels (all when channels <= 0); entries
  /// with k + l > d are set to 0. out.size() >= (d+1)^2 * channels.
  void derivatives(double u, double v, int d, std::span<double> out, int channels = 0) const;

  /// Bytes held by this surface (knots and control points), for memory reports.
  std::size_t memory_bytes() const;

 private:
  // Degree-specialized kernels (P, Q = 0: the runtime degrees), see the .cpp.
  template <int P, int Q>
  void evaluate_kernel(double u, double v, double* out, int channels) const;
  template <int P, int Q>
  void derivatives_kernel(double u, double v, int d, double* out, int channels) const;

  int degree_u_;
  int degree_v_;
  int rows_;
  int cols_;
  int dim_;
  std::vector<double> knots_u_;
  std::vector<double> knots_v_;
  std::vector<double> control_;
};

/// Index of the derivative d^(k+l)/du^k dv^l in the output of derivatives(u, v, d, out).
constexpr std::size_t derivative_index(int k, int l, int d, int dim, int channel) {
  return static_cast<std::size_t>(((k * (d + 1)) + l) * dim + channel);
}

}  // namespace palpa::spline
