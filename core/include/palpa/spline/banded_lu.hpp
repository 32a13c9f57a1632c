#pragma once
// LU factorization of a banded matrix without pivoting. Interpolation's collocation
// matrices are totally positive, so Gaussian elimination without pivoting is stable
// for them (de Boor & Pinkus 1977); the factors keep the band, so the cost is O(n w^2).
#include <vector>

namespace palpa::spline {

class BandedLU {
 public:
  /// An n x n matrix with `lower` sub-diagonals and `upper` super-diagonals, all zero.
  BandedLU(int n, int lower, int upper);

  int size() const { return n_; }
  int lower() const { return lower_; }
  int upper() const { return upper_; }

  /// Entry (i, j); requires -lower <= j - i <= upper.
  double& at(int i, int j);
  double at(int i, int j) const;

  /// Doolittle factorization in place. Throws std::runtime_error naming the row when a
  /// pivot is zero or not finite (a singular system, e.g. from coincident parameters).
  void factorize();

  /// Solves A X = B in place for B with n rows of `width` contiguous values each (row
  /// stride `width`): every channel and every grid line shares one factorization.
  void solve(double* rhs, int width) const;

 private:
  int n_;
  int lower_;
  int upper_;
  bool factored_ = false;
  std::vector<double> band_;  // row i, column j at [i*(lower+upper+1) + (j - i + lower)]
};

}  // namespace palpa::spline
