#include "palpa/spline/knot_refinement.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "palpa/spline/basis.hpp"
#include "../common/numeric.hpp"

namespace palpa::spline {
namespace {


// A5.4 for one curve: n + 1 control points of `dim` values (P), degree p, knots U, sorted
// knots X to insert. Returns Q (n + 2 + r control points) and writes Ubar.
std::vector<double> refine_curve(const std::vector<double>& P, int dim, int p, const std::vector<double>& U,
                                 std::span<const double> X, std::vector<double>& Ubar) {
  const int n = static_cast<int>(P.size()) / dim - 1;
  const int m = n + p + 1;
  const int r = static_cast<int>(X.size()) - 1;
  std::vector<double> Q(idx(n + r + 2) * idx(dim), 0.0);
  Ubar.assign(idx(m + r + 2), 0.0);
  const auto copy = [&](int to, const std::vector<double>& from_vec, int from) {
    std::copy_n(from_vec.begin() + static_cast<std::ptrdiff_t>(from * dim), dim,
                Q.begin() + static_cast<std::ptrdiff_t>(to * dim));
  };
  const int a = find_span(n + 1, p, X.front(), U);
  const int b = find_span(n + 1, p, X.back(), U) + 1;
  for (int j = 0; j <= a - p; ++j) copy(j, P, j);
  for (int j = b - 1; j <= n; ++j) copy(j + r + 1, P, j);
  for (int j = 0; j <= a; ++j) Ubar[idx(j)] = U[idx(j)];
  for (int j = b + p; j <= m; ++j) Ubar[idx(j + r + 1)] = U[idx(j)];
  int i = b + p - 1;
  int k = b + p + r;
  for (int j = r; j >= 0; --j) {
    while (X[idx(j)] <= U[idx(i)] && i > a) {
      copy(k - p - 1, P, i - p - 1);
      Ubar[idx(k)] = U[idx(i)];
      --k;
      --i;
    }
    copy(k - p - 1, Q, k - p);
    for (int l = 1; l <= p; ++l) {
      const int ind = k - p + l;
      double alfa = Ubar[idx(k + l)] - X[idx(j)];
      if (std::abs(alfa) == 0.0) {
        copy(ind - 1, Q, ind);
      } else {
        alfa /= Ubar[idx(k + l)] - U[idx(i - p + l)];
        for (int c = 0; c < dim; ++c) {
          auto& q0 = Q[idx((ind - 1) * dim + c)];
          q0 = alfa * q0 + (1.0 - alfa) * Q[idx(ind * dim + c)];
        }
      }
    }
    Ubar[idx(k)] = X[idx(j)];
    --k;
  }
  return Q;
}

}  // namespace

BSplineSurface refine_knots(const BSplineSurface& s, Direction direction, std::span<const double> insert) {
  if (insert.empty()) return s;
  if (!std::is_sorted(insert.begin(), insert.end()) || insert.front() < 0.0 || insert.back() > 1.0) {
    throw std::invalid_argument("refine_knots: the knots to insert must be sorted and within [0, 1]");
  }
  const int dim = s.dim();
  const bool along_u = direction == Direction::U;
  const int p = along_u ? s.degree_u() : s.degree_v();
  const auto& knots = along_u ? s.knots_u() : s.knots_v();
  const int lines = along_u ? s.cols() : s.rows();        // curves to refine
  const int points = along_u ? s.rows() : s.cols();       // control points per curve
  const int refined = points + static_cast<int>(insert.size());
  std::vector<double> control(idx(refined) * idx(lines) * idx(dim));
  std::vector<double> new_knots;
  std::vector<double> curve(idx(points) * idx(dim));
  for (int line = 0; line < lines; ++line) {
    for (int k = 0; k < points; ++k) {
      const auto cp = along_u ? s.control_point(k, line) : s.control_point(line, k);
      std::copy(cp.begin(), cp.end(), curve.begin() + static_cast<std::ptrdiff_t>(k * dim));
    }
    const auto q = refine_curve(curve, dim, p, knots, insert, new_knots);
    for (int k = 0; k < refined; ++k) {
      const int i = along_u ? k : line, j = along_u ? line : k;
      const int cols = along_u ? s.cols() : refined;
      std::copy_n(q.begin() + static_cast<std::ptrdiff_t>(k * dim), dim,
                  control.begin() + static_cast<std::ptrdiff_t>((i * cols + j) * dim));
    }
  }
  return along_u ? BSplineSurface(s.degree_u(), s.degree_v(), new_knots, s.knots_v(), refined, s.cols(), dim,
                                  std::move(control))
                 : BSplineSurface(s.degree_u(), s.degree_v(), s.knots_u(), new_knots, s.rows(), refined, dim,
                                  std::move(control));
}

std::vector<double> split_spans(const std::vector<double>& knots, std::span<const int> pieces) {
  std::vector<double> out;
  std::size_t span = 0;
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    const double a = knots[k], b = knots[k + 1];
    if (!(b > a)) continue;
    const int n = span < pieces.size() ? std::max(1, pieces[span]) : 1;
    for (int i = 1; i < n; ++i) out.push_back(a + (b - a) * i / n);
    ++span;
  }
  return out;
}

}  // namespace palpa::spline
