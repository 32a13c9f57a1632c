// Banded LU against a dense solve of the same system.
#include "palpa/spline/banded_lu.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

namespace palpa::spline {
namespace {

TEST(BandedLU, SolvesLikeADenseSolverForManyRightHandSides) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  for (int n : {1, 2, 5, 17, 64}) {
    for (auto [lo, up] : {std::pair{0, 0}, std::pair{1, 2}, std::pair{3, 3}, std::pair{2, 0}}) {
      BandedLU lu(n, lo, up);
      Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
      for (int i = 0; i < n; ++i) {
        for (int j = std::max(0, i - lo); j <= std::min(n - 1, i + up); ++j) {
          const double x = (i == j) ? 4.0 + dist(rng) : dist(rng);  // diagonally dominant: no pivoting needed
          lu.at(i, j) = x;
          dense(i, j) = x;
        }
      }
      const int width = 5;
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rhs(n, width);
      for (int i = 0; i < n; ++i)
        for (int c = 0; c < width; ++c) rhs(i, c) = dist(rng);
      const Eigen::MatrixXd expected = dense.partialPivLu().solve(Eigen::MatrixXd(rhs));
      lu.factorize();
      lu.solve(rhs.data(), width);
      EXPECT_LT((Eigen::MatrixXd(rhs) - expected).cwiseAbs().maxCoeff(), 1e-13) << "n=" << n;
    }
  }
}

TEST(BandedLU, ZeroPivotIsAClearErrorNotNaN) {
  BandedLU lu(3, 1, 1);
  lu.at(0, 0) = 1.0;
  lu.at(0, 1) = 1.0;
  lu.at(1, 0) = 1.0;
  lu.at(1, 1) = 1.0;  // second pivot becomes exactly 0
  lu.at(2, 2) = 1.0;
  EXPECT_THROW(lu.factorize(), std::runtime_error);
}

TEST(BandedLU, SolveBeforeFactorizeIsRejected) {
  BandedLU lu(2, 0, 0);
  double x[2] = {1, 2};
  EXPECT_THROW(lu.solve(x, 1), std::logic_error);
}

}  // namespace
}  // namespace palpa::spline
