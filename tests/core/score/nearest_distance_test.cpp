// Nearest-point distances (the search pattern's strip spacing): the k-d tree's answer
// against every pair compared, on random sets with duplicates and coincident points, and
// two parallel lines whose gap is known.
#include "palpa/score/nearest_distance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

using palpa::Vec3;

std::vector<double> brute_force(const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
  std::vector<double> out;
  for (const Vec3& p : from) {
    double best = std::numeric_limits<double>::infinity();
    for (const Vec3& q : to) best = std::min(best, (p - q).squaredNorm());
    out.push_back(std::sqrt(best));
  }
  return out;
}

TEST(NearestDistances, EqualEveryPairComparedOnRandomSets) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coord(-0.05, 0.05);
  std::uniform_int_distribution<int> size(1, 400);
  for (int trial = 0; trial < 60; ++trial) {
    std::vector<Vec3> a(static_cast<std::size_t>(size(rng))), b(static_cast<std::size_t>(size(rng)));
    for (auto& p : a) p = Vec3(coord(rng), coord(rng), 0.2 * coord(rng));
    for (auto& p : b) p = Vec3(coord(rng), coord(rng), 0.2 * coord(rng));
    // Duplicates in the searched set, and points of one set on the other.
    for (std::size_t k = 0; k < b.size() / 3; ++k) b.push_back(b[k]);
    for (std::size_t k = 0; k < a.size() / 5 && k < b.size(); ++k) a[k] = b[k];
    const auto fast = palpa::score::nearest_distances(a, b);
    const auto slow = brute_force(a, b);
    ASSERT_EQ(fast.size(), slow.size());
    for (std::size_t k = 0; k < fast.size(); ++k) ASSERT_NEAR(fast[k], slow[k], 1e-15) << "trial " << trial << " point " << k;
  }
}

TEST(NearestDistances, TwoParallelLinesAreTheirGapApart) {
  // 50 000 points on each of two lines 10 mm apart, many of them at the same place (a
  // session that jumps across a body on one line, then on the other).
  std::vector<Vec3> a, b;
  for (int k = 0; k < 50000; ++k) {
    const double x = 0.001 * (k % 40);
    a.emplace_back(x, 0.0, 0.01);
    b.emplace_back(x + 0.0005 * (k % 2), 0.01, 0.01);  // every x of `a` too, and between
    b.emplace_back(x, 0.01, 0.01);
  }
  const auto d = palpa::score::nearest_distances(a, b);
  ASSERT_EQ(d.size(), a.size());
  for (const double x : d) ASSERT_NEAR(x, 0.01, 1e-12);
}

TEST(NearestDistances, ANearCopyCloudOnEachLine) {
  // The same, each point moved by up to a nanometre: no two alike, every distance within
  // 2 nm of the gap.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-1e-9, 1e-9);
  std::vector<Vec3> a, b;
  for (int k = 0; k < 50000; ++k) {
    a.emplace_back(0.02 + jitter(rng), jitter(rng), jitter(rng));
    b.emplace_back(0.02 + jitter(rng), 0.01 + jitter(rng), jitter(rng));
  }
  const auto d = palpa::score::nearest_distances(a, b);
  for (const double x : d) ASSERT_NEAR(x, 0.01, 4e-9);
}

TEST(NearestDistances, PointsNotFinite) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto d = palpa::score::nearest_distances({Vec3(nan, 0, 0), Vec3(0, 0, 1)}, {Vec3(0, 0, 0), Vec3(nan, nan, nan)});
  ASSERT_EQ(d.size(), 2u);
  EXPECT_TRUE(std::isnan(d[0]));
  EXPECT_DOUBLE_EQ(d[1], 1.0);
  EXPECT_TRUE(palpa::score::nearest_distances({Vec3::Zero()}, {Vec3(nan, 0, 0)}).empty());
}

TEST(NearestDistances, EmptySets) {
  EXPECT_TRUE(palpa::score::nearest_distances({Vec3::Zero()}, {}).empty());
  EXPECT_TRUE(palpa::score::nearest_distances({}, {Vec3::Zero()}).empty());
}

}  // namespace
