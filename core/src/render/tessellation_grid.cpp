#include "palpa/render/tessellation_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "../common/numeric.hpp"

namespace palpa::render {
namespace {

// Largest segment count per direction: (4096 + 1)^2 vertices keep indices far inside 32 bits.
constexpr int kSegmentLimit = 4096;
// Shares of the tolerance tried by choose_grid for the direction planned first.
constexpr int kShareSteps = 20;


void check_options(const TessellationOptions& o) {
  if (!(o.tolerance > 0.0) || !std::isfinite(o.tolerance)) {
    throw std::invalid_argument("tessellation: the tolerance must be positive and finite");
  }
  if (o.min_segments < 1 || o.max_segments < o.min_segments || o.max_segments > kSegmentLimit) {
    throw std::invalid_argument(
        fmt::format("tessellation: segments must satisfy 1 <= min_segments <= max_segments <= {}", kSegmentLimit));
  }
}

double norm3(const double* x) { return std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]); }

/// The factors of a second difference over the knot intervals d01, d12 and d02 for
/// derivative orders order1 and order2. A zero interval means the basis function that
/// coefficient multiplies is zero everywhere: it contributes nothing (factor 0).
struct DifferenceFactors {
  double f01 = 0.0, f12 = 0.0, f02 = 0.0;
};

DifferenceFactors difference_factors(double d01, double d12, double d02, double order1, double order2) {
  return {d01 > 0.0 ? order1 / d01 : 0.0, d12 > 0.0 ? order1 / d12 : 0.0, d02 > 0.0 ? order2 / d02 : 0.0};
}

/// |f02 (f12 (c2 - c1) - f01 (c1 - c0))| for control points c0, c1, c2 (xyz).
double second_difference(const double* c0, const double* c1, const double* c2, const DifferenceFactors& f) {
  double r[3];
  for (int c = 0; c < 3; ++c) r[c] = f.f02 * (f.f12 * (c2[c] - c1[c]) - f.f01 * (c1[c] - c0[c]));
  return norm3(r);
}

/// The non-empty spans of a clamped knot vector of n control points and degree p: their
/// indices and the distinct knots bounding them.
void collect_spans(const std::vector<double>& knots, int n, int p, std::vector<int>& spans,
                   std::vector<double>& bounds) {
  spans.clear();
  bounds.clear();
  bounds.push_back(knots[idx(p)]);
  for (int k = p; k < n; ++k) {
    if (knots[idx(k + 1)] > knots[idx(k)]) {
      spans.push_back(k);
      bounds.push_back(knots[idx(k + 1)]);
    }
  }
}

/// Norms of the control points of Suu (rows - 2 x cols), Svv (rows x cols - 2) and Suv
/// (rows - 1 x cols - 1), row-major with the surface's column count as stride.
void derivative_norms(const spline::BSplineSurface& s, GridScratch& g) {
  const int p = s.degree_u(), q = s.degree_v();
  const int rows = s.rows(), cols = s.cols();
  const auto& ku = s.knots_u();
  const auto& kv = s.knots_v();
  const auto pd = static_cast<double>(p), qd = static_cast<double>(q);
  auto cp = [&s](int i, int j) { return s.control_point(i, j).data(); };
  const std::size_t n = idx(rows) * idx(cols);
  g.d2u.assign(n, 0.0);
  g.d2v.assign(n, 0.0);
  g.d11.assign(n, 0.0);
  // Suu: A3.7 twice along u. First differences P1_i = p (P_{i+1} - P_i) / (U_{i+p+1} - U_{i+1}),
  // second P2_i = (p - 1)(P1_{i+1} - P1_i) / (U_{i+p+1} - U_{i+2}).
  for (int i = 0; p >= 2 && i + 2 < rows; ++i) {
    const auto f = difference_factors(ku[idx(i + p + 1)] - ku[idx(i + 1)], ku[idx(i + p + 2)] - ku[idx(i + 2)],
                                      ku[idx(i + p + 1)] - ku[idx(i + 2)], pd, pd - 1.0);
    for (int j = 0; j < cols; ++j) g.d2u[idx(i * cols + j)] = second_difference(cp(i, j), cp(i + 1, j), cp(i + 2, j), f);
  }
  for (int j = 0; q >= 2 && j + 2 < cols; ++j) {
    const auto f = difference_factors(kv[idx(j + q + 1)] - kv[idx(j + 1)], kv[idx(j + q + 2)] - kv[idx(j + 2)],
                                      kv[idx(j + q + 1)] - kv[idx(j + 2)], qd, qd - 1.0);
    for (int i = 0; i < rows; ++i) g.d2v[idx(i * cols + j)] = second_difference(cp(i, j), cp(i, j + 1), cp(i, j + 2), f);
  }
  // Suv: one difference along u, then one along v:
  // P11_ij = p q ((P_{i+1,j+1} - P_{i,j+1}) - (P_{i+1,j} - P_ij)) / (du dv).
  for (int i = 0; i + 1 < rows; ++i) {
    const double du = ku[idx(i + p + 1)] - ku[idx(i + 1)];
    for (int j = 0; du > 0.0 && j + 1 < cols; ++j) {
      const double dv = kv[idx(j + q + 1)] - kv[idx(j + 1)];
      if (dv <= 0.0) continue;
      const double *a = cp(i, j), *b = cp(i + 1, j), *c = cp(i, j + 1), *d = cp(i + 1, j + 1);
      const double f = pd * qd / (du * dv);
      double r[3];
      for (int k = 0; k < 3; ++k) r[k] = f * ((d[k] - c[k]) - (b[k] - a[k]));
      g.d11[idx(i * cols + j)] = norm3(r);
    }
  }
}

/// Largest entry of a row-major table (stride cols) over rows [i0, i1] x columns [j0, j1].
double window_max(const std::vector<double>& t, int cols, int i0, int i1, int j0, int j1) {
  double m = 0.0;
  for (int i = std::max(0, i0); i <= i1; ++i)
    for (int j = std::max(0, j0); j <= j1; ++j) m = std::max(m, t[idx(i * cols + j)]);
  return m;
}

/// Segments for a span of length len where h^2 * need <= budget must hold; 0 when no
/// count up to limit does.
int span_segments(double len, double need, double budget, int limit) {
  if (!(need > 0.0)) return 1;
  if (!(budget > 0.0)) return 0;
  const double n = std::ceil(len * std::sqrt(need / budget));
  return n <= static_cast<double>(limit) ? std::max(1, static_cast<int>(n)) : 0;
}

/// Segments per span for every span (need[a] per span) so that h^2 need <= budget: the
/// total (0 when over limit) and the largest h^2 need they give (<= budget).
struct DirectionPlan {
  int total = 0;
  double used = 0.0;
};

DirectionPlan direction_segments(const std::vector<double>& knots, const std::vector<double>& need, double budget,
                                 int limit, std::vector<int>* out) {
  DirectionPlan plan;
  for (std::size_t a = 0; a + 1 < knots.size(); ++a) {
    const double len = knots[a + 1] - knots[a];
    const int n = span_segments(len, need[a], budget, limit);
    if (n == 0 || plan.total + n > limit) return {};
    plan.total += n;
    plan.used = std::max(plan.used, len * len / (static_cast<double>(n) * n) * need[a]);
    if (out != nullptr) (*out)[a] = n;
  }
  return plan;
}

/// The cells of a grid whose first direction gets `share` of the budget and the second
/// what the first leaves unused (rounding up its counts leaves some); 0 when infeasible.
long long plan_cells(const GridScratch& g, const TessellationOptions& o, double budget, double share, bool u_first) {
  const auto& knots1 = u_first ? g.knots_u : g.knots_v;
  const auto& knots2 = u_first ? g.knots_v : g.knots_u;
  const auto first = direction_segments(knots1, u_first ? g.need_u : g.need_v, budget * share, o.max_segments, nullptr);
  if (first.total == 0) return 0;
  const auto second =
      direction_segments(knots2, u_first ? g.need_v : g.need_u, budget - first.used, o.max_segments, nullptr);
  if (second.total == 0) return 0;
  return static_cast<long long>(std::max(first.total, o.min_segments)) * std::max(second.total, o.min_segments);
}

/// Adds segments to the widest until there are at least min_segments.
void top_up(const std::vector<double>& knots, int min_segments, std::vector<int>& seg) {
  int total = 0;
  for (int n : seg) total += n;
  for (; total < min_segments; ++total) {
    std::size_t widest = 0;
    for (std::size_t a = 1; a < seg.size(); ++a) {
      if ((knots[a + 1] - knots[a]) / seg[a] > (knots[widest + 1] - knots[widest]) / seg[widest]) widest = a;
    }
    ++seg[widest];
  }
}

/// The grid lines of a direction: each span cut evenly into seg[a] segments; the knots
/// themselves exactly.
void grid_lines(const std::vector<double>& knots, const std::vector<int>& seg, std::vector<double>& lines) {
  lines.clear();
  for (std::size_t a = 0; a < seg.size(); ++a) {
    const double h = (knots[a + 1] - knots[a]) / seg[a];
    for (int k = 0; k < seg[a]; ++k) lines.push_back(k == 0 ? knots[a] : knots[a] + h * k);
  }
  lines.push_back(knots.back());
}

/// True when no interior knot has multiplicity >= degree: the surface is C1 across every
/// knot in this direction, so a cell may straddle knots under one second-derivative bound.
bool c1_across_knots(const std::vector<double>& knots, int degree) {
  const std::size_t last = knots.size() - static_cast<std::size_t>(degree) - 1;
  std::size_t run = 1;
  for (std::size_t k = static_cast<std::size_t>(degree) + 1; k < last; ++k) {
    run = knots[k] == knots[k - 1] ? run + 1 : 1;
    if (run >= static_cast<std::size_t>(degree)) return false;
  }
  return true;
}

/// The fewest segments n per direction for which the uniform n x n grid meets the
/// tolerance by the bounds b holding everywhere (the bound falls as 1/n^2); 0 when more
/// than `limit` would be needed.
int uniform_segments(const DerivativeBounds& b, double range_u, double range_v, double tolerance, int limit) {
  const double k = range_u * range_u * b.suu + 2.0 * range_u * range_v * b.suv + range_v * range_v * b.svv;
  const double n = std::ceil(std::sqrt(k / (8.0 * tolerance)));
  if (!(n <= static_cast<double>(limit))) return 0;
  int segments = std::max(1, static_cast<int>(n));
  // Rounding: step up while the bound as grid_error_bound computes it is over.
  while (segments < limit && grid_error_bound(b, range_u, range_v, segments, segments) > tolerance) ++segments;
  return segments;
}

/// With o.uniform_if_cheaper: the segments per direction of the uniform grid within the
/// tolerance when it has fewer cells than knot_cells (-1: no grid through the knots fits), else 0.
int cheaper_uniform(const spline::BSplineSurface& s, const TessellationOptions& o, const GridScratch& g,
                    const DerivativeBounds& global, long long knot_cells) {
  if (!o.uniform_if_cheaper || !c1_across_knots(s.knots_u(), s.degree_u()) || !c1_across_knots(s.knots_v(), s.degree_v())) {
    return 0;
  }
  const int fewest = uniform_segments(global, g.knots_u.back() - g.knots_u.front(), g.knots_v.back() - g.knots_v.front(),
                                      o.tolerance, o.max_segments);
  if (fewest == 0) return 0;
  const int n = std::max(o.min_segments, fewest);
  return knot_cells < 0 || static_cast<long long>(n) * n < knot_cells ? n : 0;
}

void uniform_lines(double a, double b, int n, std::vector<double>& lines) {
  lines.resize(idx(n + 1));
  for (int k = 0; k <= n; ++k) lines[idx(k)] = k == n ? b : a + (b - a) * k / n;
}

}  // namespace

void patch_bounds(const spline::BSplineSurface& s, GridScratch& g) {
  if (s.dim() < 3) throw std::invalid_argument("patch_bounds: the surface has fewer than 3 channels");
  const int p = s.degree_u(), q = s.degree_v();
  const int cols = s.cols();
  collect_spans(s.knots_u(), s.rows(), p, g.span_u, g.knots_u);
  collect_spans(s.knots_v(), cols, q, g.span_v, g.knots_v);
  derivative_norms(s, g);
  g.patches.resize(g.span_u.size() * g.span_v.size());
  // On span k the nonzero basis functions of degree p - r (the r-th derivative's) are
  // those of control points k - p .. k - r (A2.1 on the derivative's knot vector).
  for (std::size_t a = 0; a < g.span_u.size(); ++a) {
    const int k = g.span_u[a];
    for (std::size_t b = 0; b < g.span_v.size(); ++b) {
      const int l = g.span_v[b];
      auto& patch = g.patches[a * g.span_v.size() + b];
      patch.suu = p >= 2 ? window_max(g.d2u, cols, k - p, k - 2, l - q, l) : 0.0;
      patch.svv = q >= 2 ? window_max(g.d2v, cols, k - p, k, l - q, l - 2) : 0.0;
      patch.suv = window_max(g.d11, cols, k - p, k - 1, l - q, l - 1);
    }
  }
}

DerivativeBounds second_derivative_bounds(const spline::BSplineSurface& s) {
  GridScratch g;
  patch_bounds(s, g);
  DerivativeBounds m;
  for (const auto& b : g.patches) {
    m.suu = std::max(m.suu, b.suu);
    m.suv = std::max(m.suv, b.suv);
    m.svv = std::max(m.svv, b.svv);
  }
  return m;
}

double object_tolerance_from_screen(double pixels, double pixels_per_metre) {
  if (!(pixels > 0.0) || !std::isfinite(pixels) || !(pixels_per_metre > 0.0) || !std::isfinite(pixels_per_metre)) {
    throw std::invalid_argument(
        "object_tolerance_from_screen: pixels and pixels per metre must be positive and finite");
  }
  return pixels / pixels_per_metre;
}

double cell_error_bound(const DerivativeBounds& b, double hu, double hv) {
  return 0.125 * (hu * hu * b.suu + 2.0 * hu * hv * b.suv + hv * hv * b.svv);
}

double grid_error_bound(const DerivativeBounds& b, double range_u, double range_v, int nu, int nv) {
  return cell_error_bound(b, range_u / static_cast<double>(nu), range_v / static_cast<double>(nv));
}

double choose_grid(const spline::BSplineSurface& s, const TessellationOptions& o, GridScratch& g,
                   std::vector<double>& us, std::vector<double>& vs) {
  check_options(o);
  patch_bounds(s, g);
  const std::size_t nu = g.span_u.size(), nv = g.span_v.size();
  // The need of each span: hu^2 (suu + suv) <= 8 share tol on every patch along it.
  auto& need_u = g.need_u;
  auto& need_v = g.need_v;
  need_u.assign(nu, 0.0);
  need_v.assign(nv, 0.0);
  DerivativeBounds global;
  for (std::size_t a = 0; a < nu; ++a) {
    for (std::size_t b = 0; b < nv; ++b) {
      const auto& p = g.patches[a * nv + b];
      need_u[a] = std::max(need_u[a], p.suu + p.suv);
      need_v[b] = std::max(need_v[b], p.svv + p.suv);
      global = {std::max(global.suu, p.suu), std::max(global.suv, p.suv), std::max(global.svv, p.svv)};
    }
  }
  const double budget = 8.0 * o.tolerance;
  double best_share = -1.0;
  bool best_u_first = true;
  long long best_cells = 0;
  for (int step = 1; step <= kShareSteps; ++step) {
    const double share = static_cast<double>(step) / kShareSteps;
    for (bool u_first : {true, false}) {
      const long long cells = plan_cells(g, o, budget, share, u_first);
      if (cells > 0 && (best_share < 0.0 || cells < best_cells)) best_share = share, best_u_first = u_first, best_cells = cells;
    }
  }
  if (const int n = cheaper_uniform(s, o, g, global, best_share < 0.0 ? -1 : best_cells); n > 0) {
    uniform_lines(g.knots_u.front(), g.knots_u.back(), n, us);
    uniform_lines(g.knots_v.front(), g.knots_v.back(), n, vs);
    return grid_error_bound(global, g.knots_u.back() - g.knots_u.front(), g.knots_v.back() - g.knots_v.front(), n, n);
  }
  if (best_share < 0.0) {  // too fine for max_segments: the uniform grid at the limit
    uniform_lines(g.knots_u.front(), g.knots_u.back(), o.max_segments, us);
    uniform_lines(g.knots_v.front(), g.knots_v.back(), o.max_segments, vs);
    return grid_error_bound(global, g.knots_u.back() - g.knots_u.front(), g.knots_v.back() - g.knots_v.front(),
                            o.max_segments, o.max_segments);
  }
  g.seg_u.resize(nu);
  g.seg_v.resize(nv);
  if (best_u_first) {
    const double used = direction_segments(g.knots_u, need_u, budget * best_share, o.max_segments, &g.seg_u).used;
    direction_segments(g.knots_v, need_v, budget - used, o.max_segments, &g.seg_v);
  } else {
    const double used = direction_segments(g.knots_v, need_v, budget * best_share, o.max_segments, &g.seg_v).used;
    direction_segments(g.knots_u, need_u, budget - used, o.max_segments, &g.seg_u);
  }
  top_up(g.knots_u, o.min_segments, g.seg_u);
  top_up(g.knots_v, o.min_segments, g.seg_v);
  grid_lines(g.knots_u, g.seg_u, us);
  grid_lines(g.knots_v, g.seg_v, vs);
  double bound = 0.0;
  for (std::size_t a = 0; a < nu; ++a) {
    const double hu = (g.knots_u[a + 1] - g.knots_u[a]) / g.seg_u[a];
    for (std::size_t b = 0; b < nv; ++b) {
      const double hv = (g.knots_v[b + 1] - g.knots_v[b]) / g.seg_v[b];
      bound = std::max(bound, cell_error_bound(g.patches[a * nv + b], hu, hv));
    }
  }
  return bound;
}

}  // namespace palpa::render
