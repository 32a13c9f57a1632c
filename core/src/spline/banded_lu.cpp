#include "palpa/spline/banded_lu.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace palpa::spline {

namespace {
int checked(int value, const char* what) {
  if (value < 0) throw std::invalid_argument(std::string("BandedLU: negative ") + what);
  return value;
}
}  // namespace

// Bandwidths beyond n - 1 hold nothing, so they are clamped before the band is allocated.
BandedLU::BandedLU(int n, int lower, int upper)
    : n_(checked(n - 1, "size") + 1),
      lower_(std::min(checked(lower, "bandwidth"), n_ - 1)),
      upper_(std::min(checked(upper, "bandwidth"), n_ - 1)),
      band_(static_cast<std::size_t>(n_) * static_cast<std::size_t>(lower_ + upper_ + 1), 0.0) {}

double& BandedLU::at(int i, int j) {
  assert(j - i >= -lower_ && j - i <= upper_ && "BandedLU::at outside the band");
  return band_[static_cast<std::size_t>(i * (lower_ + upper_ + 1) + (j - i + lower_))];
}

double BandedLU::at(int i, int j) const {
  assert(j - i >= -lower_ && j - i <= upper_ && "BandedLU::at outside the band");
  return band_[static_cast<std::size_t>(i * (lower_ + upper_ + 1) + (j - i + lower_))];
}

void BandedLU::factorize() {
  for (int k = 0; k < n_; ++k) {
    const double pivot = at(k, k);
    if (!std::isfinite(pivot) || pivot == 0.0) {
      throw std::runtime_error(fmt::format("singular collocation matrix at row {} (coincident parameters?)", k));
    }
    const int last_row = std::min(n_ - 1, k + lower_);
    const int last_col = std::min(n_ - 1, k + upper_);
    for (int i = k + 1; i <= last_row; ++i) {
      const double l = at(i, k) / pivot;
      at(i, k) = l;
      if (l == 0.0) continue;
      for (int j = k + 1; j <= last_col; ++j) at(i, j) -= l * at(k, j);
    }
  }
  factored_ = true;
}

void BandedLU::solve(double* rhs, int width) const {
  if (!factored_) throw std::logic_error("BandedLU::solve before factorize");
  const auto w = static_cast<std::size_t>(width);
  // Forward substitution with the unit lower factor.
  for (int i = 1; i < n_; ++i) {
    double* xi = rhs + static_cast<std::size_t>(i) * w;
    for (int k = std::max(0, i - lower_); k < i; ++k) {
      const double l = at(i, k);
      if (l == 0.0) continue;
      const double* xk = rhs + static_cast<std::size_t>(k) * w;
      for (std::size_t c = 0; c < w; ++c) xi[c] -= l * xk[c];
    }
  }
  // Back substitution with the upper factor.
  for (int i = n_ - 1; i >= 0; --i) {
    double* xi = rhs + static_cast<std::size_t>(i) * w;
    for (int j = i + 1; j <= std::min(n_ - 1, i + upper_); ++j) {
      const double u = at(i, j);
      if (u == 0.0) continue;
      const double* xj = rhs + static_cast<std::size_t>(j) * w;
      for (std::size_t c = 0; c < w; ++c) xi[c] -= u * xj[c];
    }
    const double inv = 1.0 / at(i, i);
    for (std::size_t c = 0; c < w; ++c) xi[c] *= inv;
  }
}

}  // namespace palpa::spline
