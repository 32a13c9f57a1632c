#include "palpa/spline/basis.hpp"

#include <algorithm>
#include <array>
#include <cstddef>

namespace palpa::spline {
namespace {
constexpr int kOrder = kMaxDegree + 1;

double knot(std::span<const double> knots, int i) { return knots[static_cast<std::size_t>(i)]; }
}  // namespace

int find_span(int control_points, int p, double u, std::span<const double> knots) {
  const int n = control_points - 1;
  if (u >= knot(knots, n + 1)) return n;  // the closed right end (u == 1) belongs to the last span
  if (u <= knot(knots, p)) return p;
  int low = p;
  int high = n + 1;
  int mid = (low + high) / 2;
  while (u < knot(knots, mid) || u >= knot(knots, mid + 1)) {
    if (u < knot(knots, mid)) {
      high = mid;
    } else {
      low = mid;
    }
    mid = (low + high) / 2;
  }
  return mid;
}

// The kernels are templates on the degree P (0: the runtime degree p) so that the common
// cubic case compiles to unrolled loops: the haptic loop calls them thousands of times a
// second.
template <int P>
void basis_kernel(int span, double u, int p_runtime, std::span<const double> knots, double* n) {
  const int p = P > 0 ? P : p_runtime;
  std::array<double, kOrder> left;  // entries 1..p are written before they are read
  std::array<double, kOrder> right;
  n[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    const auto uj = static_cast<std::size_t>(j);
    left[uj] = u - knot(knots, span + 1 - j);
    right[uj] = knot(knots, span + j) - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const auto ur = static_cast<std::size_t>(r);
      const double temp = n[r] / (right[ur + 1] + left[uj - ur]);
      n[r] = saved + right[ur + 1] * temp;
      saved = left[uj - ur] * temp;
    }
    n[j] = saved;
  }
}

template <int P>
void derivative_kernel(int span, double u, int p_runtime, int d, std::span<const double> knots, double* ders) {
  const int p = P > 0 ? P : p_runtime;
  // ndu holds the basis functions (upper triangle) and knot differences (lower triangle).
  std::array<std::array<double, kOrder>, kOrder> ndu;  // every entry read is written first
  std::array<std::array<double, kOrder>, 2> a{};
  std::array<double, kOrder> left;
  std::array<double, kOrder> right;
  const int stride = p + 1;

  ndu[0][0] = 1.0;
  for (std::size_t j = 1; j <= static_cast<std::size_t>(p); ++j) {
    const int ij = static_cast<int>(j);
    left[j] = u - knot(knots, span + 1 - ij);
    right[j] = knot(knots, span + ij) - u;
    double saved = 0.0;
    for (std::size_t r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  for (int j = 0; j <= p; ++j) ders[j] = ndu[static_cast<std::size_t>(j)][static_cast<std::size_t>(p)];

  const int dmax = std::min(d, p);
  for (int r = 0; r <= p; ++r) {
    std::size_t s1 = 0;
    std::size_t s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= dmax; ++k) {
      double value = 0.0;
      const int rk = r - k;
      const int pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[static_cast<std::size_t>(pk + 1)][static_cast<std::size_t>(rk)];
        value = a[s2][0] * ndu[static_cast<std::size_t>(rk)][static_cast<std::size_t>(pk)];
      }
      const int j1 = (rk >= -1) ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        const auto uj = static_cast<std::size_t>(j);
        a[s2][uj] = (a[s1][uj] - a[s1][uj - 1]) /
                    ndu[static_cast<std::size_t>(pk + 1)][static_cast<std::size_t>(rk + j)];
        value += a[s2][uj] * ndu[static_cast<std::size_t>(rk + j)][static_cast<std::size_t>(pk)];
      }
      if (r <= pk) {
        const auto uk = static_cast<std::size_t>(k);
        a[s2][uk] = -a[s1][uk - 1] / ndu[static_cast<std::size_t>(pk + 1)][static_cast<std::size_t>(r)];
        value += a[s2][uk] * ndu[static_cast<std::size_t>(r)][static_cast<std::size_t>(pk)];
      }
      ders[k * stride + r] = value;
      std::swap(s1, s2);
    }
  }
  // Multiply by p!/(p-k)!.
  double factor = p;
  for (int k = 1; k <= dmax; ++k) {
    for (int j = 0; j <= p; ++j) ders[k * stride + j] *= factor;
    factor *= (p - k);
  }
  for (int k = dmax + 1; k <= d; ++k) {
    for (int j = 0; j <= p; ++j) ders[k * stride + j] = 0.0;
  }
}

void basis_functions(int span, double u, int p, std::span<const double> knots, double* n) {
  switch (p) {
    case 2: basis_kernel<2>(span, u, p, knots, n); break;
    case 3: basis_kernel<3>(span, u, p, knots, n); break;
    default: basis_kernel<0>(span, u, p, knots, n); break;
  }
}

void basis_function_derivatives(int span, double u, int p, int d, std::span<const double> knots, double* ders) {
  switch (p) {
    case 2: derivative_kernel<2>(span, u, p, d, knots, ders); break;
    case 3: derivative_kernel<3>(span, u, p, d, knots, ders); break;
    default: derivative_kernel<0>(span, u, p, d, knots, ders); break;
  }
}

}  // namespace palpa::spline
