#include "palpa/render/tessellation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "palpa/mat/mat_body.hpp"
#include "palpa/spline/basis.hpp"

namespace palpa::render {
namespace {

// Largest segment count per direction: (4096 + 1)^2 vertices keep indices far inside 32 bits.
constexpr int kSegmentLimit = 4096;
// Relative size below which a tangent or the cross product counts as vanished (as in
// mat::skeleton_normal, which then gives the limit direction).
constexpr double kDegenerate = 1e-10;
// A float holds a coordinate to within 2^-24 of its magnitude (round to nearest).
constexpr double kFloatRounding = 0x1p-24;

std::size_t idx(int i) { return static_cast<std::size_t>(i); }

void check_options(const TessellationOptions& o) {
  if (!(o.tolerance > 0.0)) throw std::invalid_argument("tessellation: the tolerance must be positive");
  if (o.min_segments < 1 || o.max_segments < o.min_segments || o.max_segments > kSegmentLimit) {
    throw std::invalid_argument("tessellation: segments must satisfy 1 <= min_segments <= max_segments <= " +
                                std::to_string(kSegmentLimit));
  }
}

/// The parameter of grid line k of n + 1 over [a, b]; the last line is exactly b.
double grid_param(int k, int n, double a, double b) {
  return k == n ? b : a + (b - a) * static_cast<double>(k) / static_cast<double>(n);
}

double norm3(const double* x) { return std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]); }

/// |(c2 - c1) scale2 - (c1 - c0) scale1| * outer for control points c0, c1, c2 (xyz).
/// A zero knot interval means the basis function that coefficient multiplies is zero
/// everywhere: the coefficient contributes nothing and is taken as 0.
double second_difference(const double* c0, const double* c1, const double* c2, double d01, double d12, double d02,
                         double order1, double order2) {
  if (d02 <= 0.0) return 0.0;
  double r[3];
  for (int c = 0; c < 3; ++c) {
    const double a = d01 > 0.0 ? order1 * (c1[c] - c0[c]) / d01 : 0.0;
    const double b = d12 > 0.0 ? order1 * (c2[c] - c1[c]) / d12 : 0.0;
    r[c] = order2 * (b - a) / d02;
  }
  return norm3(r);
}

/// Rebuilds the index list of a rows x cols vertex grid: two triangles per cell, counter-
/// clockwise in (u, v) (seen from +N = Su x Sv), reversed when flipped.
void build_triangles(int rows, int cols, bool flip, std::vector<std::uint32_t>& tri) {
  tri.resize(idx(rows - 1) * idx(cols - 1) * 6);
  std::size_t t = 0;
  for (int i = 0; i + 1 < rows; ++i) {
    for (int j = 0; j + 1 < cols; ++j) {
      const auto a = static_cast<std::uint32_t>(i * cols + j);
      const auto b = static_cast<std::uint32_t>((i + 1) * cols + j);
      const auto c = b + 1;
      const auto d = a + 1;
      if (!flip) {
        tri[t] = a, tri[t + 1] = b, tri[t + 2] = c;
        tri[t + 3] = a, tri[t + 4] = c, tri[t + 5] = d;
      } else {
        tri[t] = a, tri[t + 1] = c, tri[t + 2] = b;
        tri[t + 3] = a, tri[t + 4] = d, tri[t + 5] = c;
      }
      t += 6;
    }
  }
}

}  // namespace

DerivativeBounds second_derivative_bounds(const spline::BSplineSurface& s) {
  if (s.dim() < 3) throw std::invalid_argument("second_derivative_bounds: the surface has fewer than 3 channels");
  const int p = s.degree_u();
  const int q = s.degree_v();
  const int rows = s.rows();
  const int cols = s.cols();
  const auto& ku = s.knots_u();
  const auto& kv = s.knots_v();
  const auto pd = static_cast<double>(p);
  const auto qd = static_cast<double>(q);
  auto cp = [&s](int i, int j) { return s.control_point(i, j).data(); };
  DerivativeBounds b;
  // Suu: A3.7 twice along u. First differences P1_i = p (P_{i+1} - P_i) / (U_{i+p+1} - U_{i+1}),
  // second P2_i = (p - 1)(P1_{i+1} - P1_i) / (U_{i+p+1} - U_{i+2}).
  if (p >= 2) {
    for (int j = 0; j < cols; ++j) {
      for (int i = 0; i + 2 < rows; ++i) {
        const double d01 = ku[idx(i + p + 1)] - ku[idx(i + 1)];
        const double d12 = ku[idx(i + p + 2)] - ku[idx(i + 2)];
        const double d02 = ku[idx(i + p + 1)] - ku[idx(i + 2)];
        b.suu = std::max(b.suu, second_difference(cp(i, j), cp(i + 1, j), cp(i + 2, j), d01, d12, d02, pd, pd - 1.0));
      }
    }
  }
  if (q >= 2) {
    for (int i = 0; i < rows; ++i) {
      for (int j = 0; j + 2 < cols; ++j) {
        const double d01 = kv[idx(j + q + 1)] - kv[idx(j + 1)];
        const double d12 = kv[idx(j + q + 2)] - kv[idx(j + 2)];
        const double d02 = kv[idx(j + q + 1)] - kv[idx(j + 2)];
        b.svv = std::max(b.svv, second_difference(cp(i, j), cp(i, j + 1), cp(i, j + 2), d01, d12, d02, qd, qd - 1.0));
      }
    }
  }
  // Suv: one difference along u, then one along v:
  // P11_ij = q (P10_{i,j+1} - P10_ij) / (V_{j+q+1} - V_{j+1}).
  for (int i = 0; i + 1 < rows; ++i) {
    const double du = ku[idx(i + p + 1)] - ku[idx(i + 1)];
    if (du <= 0.0) continue;
    for (int j = 0; j + 1 < cols; ++j) {
      const double dv = kv[idx(j + q + 1)] - kv[idx(j + 1)];
      if (dv <= 0.0) continue;
      const double* a = cp(i, j);
      const double* b1 = cp(i + 1, j);
      const double* c = cp(i, j + 1);
      const double* d = cp(i + 1, j + 1);
      double r[3];
      for (int k = 0; k < 3; ++k) r[k] = pd * qd * ((d[k] - c[k]) - (b1[k] - a[k])) / (du * dv);
      b.suv = std::max(b.suv, norm3(r));
    }
  }
  return b;
}

double object_tolerance_from_screen(double pixels, double pixels_per_metre) {
  if (!(pixels > 0.0) || !std::isfinite(pixels) || !(pixels_per_metre > 0.0) || !std::isfinite(pixels_per_metre)) {
    throw std::invalid_argument(
        "object_tolerance_from_screen: pixels and pixels per metre must be positive and finite");
  }
  return pixels / pixels_per_metre;
}

double grid_error_bound(const DerivativeBounds& b, double range_u, double range_v, int nu, int nv) {
  const double hu = range_u / static_cast<double>(nu);
  const double hv = range_v / static_cast<double>(nv);
  return 0.125 * (hu * hu * b.suu + 2.0 * hu * hv * b.suv + hv * hv * b.svv);
}

Segments choose_segments(const DerivativeBounds& b, const TessellationOptions& o, double range_u, double range_v) {
  check_options(o);
  if (!(range_u > 0.0) || !(range_v > 0.0) || !std::isfinite(range_u) || !std::isfinite(range_v)) {
    throw std::invalid_argument("choose_segments: parameter ranges must be positive and finite");
  }
  const int lo = o.min_segments;
  const int hi = o.max_segments;
  const double tol = o.tolerance;
  auto bound = [&](int nu, int nv) { return grid_error_bound(b, range_u, range_v, nu, nv); };
  if (bound(lo, lo) <= tol) return {lo, lo, bound(lo, lo)};
  Segments best{hi, hi, bound(hi, hi)};
  bool found = false;
  std::int64_t best_product = 0;
  for (int nu = lo; nu <= hi; ++nu) {
    if (found && std::int64_t{nu} * lo > best_product) break;  // nv >= lo: no better grid follows
    const double hu = range_u / static_cast<double>(nu);
    // The smallest nv with (hu^2 suu + 2 hu hv suv + hv^2 svv) / 8 <= tol: the positive
    // root of svv hv^2 + 2 suv hu hv - c = 0, c = 8 tol - suu hu^2, written without
    // cancellation as c / (suv hu + sqrt(suv^2 hu^2 + svv c)).
    const double c = 8.0 * tol - b.suu * hu * hu;
    if (!(c >= 0.0)) continue;
    const double denom = b.suv * hu + std::sqrt(b.suv * b.suv * hu * hu + b.svv * c);
    // range_v / hv_max; no limit on hv when v does not enter the bound (denom = 0).
    const double need = denom > 0.0 ? (c > 0.0 ? range_v * denom / c : std::numeric_limits<double>::infinity()) : 0.0;
    if (!(need <= static_cast<double>(hi))) continue;
    int nv = std::max(lo, static_cast<int>(std::ceil(need)));
    while (nv > lo && bound(nu, nv - 1) <= tol) --nv;  // round-off in the root
    while (nv <= hi && bound(nu, nv) > tol) ++nv;
    if (nv > hi) continue;
    const std::int64_t product = std::int64_t{nu} * nv;
    const double e = bound(nu, nv);
    if (!found || product < best_product || (product == best_product && e < best.bound)) {
      best = {nu, nv, e};
      best_product = product;
      found = true;
    }
  }
  return best;
}

void tessellate(const spline::BSplineSurface& s, const TessellationOptions& o, bool outward_is_minus_normal,
                Mesh& out) {
  check_options(o);
  if (s.dim() < 3) throw std::invalid_argument("tessellate: the surface has fewer than 3 channels");
  const auto& ku = s.knots_u();
  const auto& kv = s.knots_v();
  const double u0 = ku.front();
  const double u1 = ku.back();
  const double v0 = kv.front();
  const double v1 = kv.back();
  const int p = s.degree_u();
  const int q = s.degree_v();
  const int crows = s.rows();
  const int ccols = s.cols();
  const auto dim = idx(s.dim());
  const auto& ctrl = s.control();

  // Positions are stored as floats: each coordinate rounds by at most 2^-24 of its size,
  // and |S| <= the largest control point (convex hull). That share of the tolerance is
  // set aside, so the drawn mesh stays within the tolerance, rounding included.
  double pmax = 0.0;
  for (std::size_t k = 0; k < ctrl.size(); k += dim) pmax = std::max(pmax, norm3(&ctrl[k]));
  TessellationOptions geometric = o;
  const double rounding = kFloatRounding * pmax * std::sqrt(3.0);
  geometric.tolerance = o.tolerance > rounding ? o.tolerance - rounding : std::numeric_limits<double>::min();
  const auto seg = choose_segments(second_derivative_bounds(s), geometric, u1 - u0, v1 - v0);
  const int rows = seg.u + 1;
  const int cols = seg.v + 1;
  out.error_bound = seg.bound + rounding;

  // Scratch: the v basis (values and first derivatives) of every grid column, then the
  // row curve: for the current u, C_b = sum_a N_a(u) P_ab and D_b = sum_a N'_a(u) P_ab
  // for every control column b (xyz), so each vertex costs only a sum over q + 1 terms.
  const std::size_t vstride = 2 * idx(q + 1);
  const std::size_t vtable = idx(cols) * vstride;
  out.scratch.resize(vtable + idx(ccols) * 6);
  out.scratch_spans.resize(idx(cols));
  for (int j = 0; j < cols; ++j) {
    const double v = grid_param(j, cols - 1, v0, v1);
    const int span = spline::find_span(ccols, q, v, kv);
    out.scratch_spans[idx(j)] = span;
    spline::basis_function_derivatives(span, v, q, 1, kv, &out.scratch[idx(j) * vstride]);
  }
  double* curve = &out.scratch[vtable];

  const std::size_t n = idx(rows) * idx(cols);
  out.positions.resize(n * 3);
  out.normals.resize(n * 3);
  const float sign = outward_is_minus_normal ? -1.0f : 1.0f;
  bool any_degenerate = false;
  std::array<double, 2 * (spline::kMaxDegree + 1)> nu_ders{};
  for (int i = 0; i < rows; ++i) {
    const double u = grid_param(i, rows - 1, u0, u1);
    const int span_u = spline::find_span(crows, p, u, ku);
    spline::basis_function_derivatives(span_u, u, p, 1, ku, nu_ders.data());
    const double* nu = nu_ders.data();
    const double* du = nu_ders.data() + (p + 1);
    for (int b = 0; b < ccols; ++b) {
      double c[3] = {0.0, 0.0, 0.0};
      double d[3] = {0.0, 0.0, 0.0};
      for (int a = 0; a <= p; ++a) {
        const double* P = &ctrl[idx((span_u - p + a) * ccols + b) * dim];
        for (int k = 0; k < 3; ++k) {
          c[k] += nu[a] * P[k];
          d[k] += du[a] * P[k];
        }
      }
      double* cb = curve + idx(b) * 6;
      for (int k = 0; k < 3; ++k) {
        cb[k] = c[k];
        cb[3 + k] = d[k];
      }
    }
    for (int j = 0; j < cols; ++j) {
      const double* nv = &out.scratch[idx(j) * vstride];
      const double* dv = nv + (q + 1);
      const int first = out.scratch_spans[idx(j)] - q;
      double S[3] = {0.0, 0.0, 0.0};
      double Su[3] = {0.0, 0.0, 0.0};
      double Sv[3] = {0.0, 0.0, 0.0};
      for (int c = 0; c <= q; ++c) {
        const double* cb = curve + idx(first + c) * 6;
        for (int k = 0; k < 3; ++k) {
          S[k] += nv[c] * cb[k];
          Su[k] += nv[c] * cb[3 + k];
          Sv[k] += dv[c] * cb[k];
        }
      }
      const std::size_t vtx = (idx(i) * idx(cols) + idx(j)) * 3;
      const double N[3] = {Su[1] * Sv[2] - Su[2] * Sv[1], Su[2] * Sv[0] - Su[0] * Sv[2],
                           Su[0] * Sv[1] - Su[1] * Sv[0]};
      const double lu = norm3(Su);
      const double lv = norm3(Sv);
      const double ln = norm3(N);
      const bool degenerate = !(lu > kDegenerate * lv) || !(lv > kDegenerate * lu) || !(ln > kDegenerate * lu * lv);
      any_degenerate = any_degenerate || degenerate;
      for (std::size_t k = 0; k < 3; ++k) {
        out.positions[vtx + k] = static_cast<float>(S[k]);
        // 0 marks a vertex whose normal the second pass fills in.
        out.normals[vtx + k] = degenerate ? 0.0f : sign * static_cast<float>(N[k] / ln);
      }
    }
  }

  // Where Su x Sv vanished: the limit direction from the interior (a pole row or
  // column, mat::skeleton_normal), else the mean of the neighbours' normals, else the
  // mean over the whole grid, else +-z.
  if (any_degenerate) {
    for (int i = 0; i < rows; ++i) {
      for (int j = 0; j < cols; ++j) {
        float* nrm = &out.normals[(idx(i) * idx(cols) + idx(j)) * 3];
        if (nrm[0] != 0.0f || nrm[1] != 0.0f || nrm[2] != 0.0f) continue;
        double limit[3];
        if (mat::skeleton_normal(s, grid_param(i, rows - 1, u0, u1), grid_param(j, cols - 1, v0, v1), limit)) {
          for (int k = 0; k < 3; ++k) nrm[k] = sign * static_cast<float>(limit[k]);
          continue;
        }
        double sum[3] = {0.0, 0.0, 0.0};
        for (int a = std::max(0, i - 1); a <= std::min(rows - 1, i + 1); ++a) {
          for (int b = std::max(0, j - 1); b <= std::min(cols - 1, j + 1); ++b) {
            const float* m = &out.normals[(idx(a) * idx(cols) + idx(b)) * 3];
            for (int k = 0; k < 3; ++k) sum[k] += static_cast<double>(m[k]);
          }
        }
        double len = norm3(sum);
        if (!(len > 1e-6)) {
          for (double& x : sum) x = 0.0;
          for (std::size_t k = 0; k < out.normals.size(); ++k) sum[k % 3] += static_cast<double>(out.normals[k]);
          len = norm3(sum);
        }
        if (len > 1e-6) {
          for (int k = 0; k < 3; ++k) nrm[k] = static_cast<float>(sum[k] / len);
        } else {
          nrm[0] = 0.0f, nrm[1] = 0.0f, nrm[2] = sign;
        }
      }
    }
  }

  const bool same_grid = out.rows == rows && out.cols == cols &&
                         out.outward_is_minus_normal == outward_is_minus_normal &&
                         out.triangles.size() == idx(rows - 1) * idx(cols - 1) * 6;
  if (!same_grid) build_triangles(rows, cols, outward_is_minus_normal, out.triangles);
  out.rows = rows;
  out.cols = cols;
  out.outward_is_minus_normal = outward_is_minus_normal;
}

double max_parametric_deviation(const Mesh& mesh, const spline::BSplineSurface& s, int samples_per_edge) {
  if (samples_per_edge < 1) throw std::invalid_argument("max_parametric_deviation: samples_per_edge must be >= 1");
  if (mesh.rows < 2 || mesh.cols < 2) return 0.0;
  const auto& ku = s.knots_u();
  const auto& kv = s.knots_v();
  const auto cols = static_cast<std::uint32_t>(mesh.cols);
  const auto nsamples = static_cast<double>(samples_per_edge);
  double worst = 0.0;
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    double uv[3][2];
    const float* pos[3];
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t vtx = mesh.triangles[t + k];
      uv[k][0] = grid_param(static_cast<int>(vtx / cols), mesh.rows - 1, ku.front(), ku.back());
      uv[k][1] = grid_param(static_cast<int>(vtx % cols), mesh.cols - 1, kv.front(), kv.back());
      pos[k] = &mesh.positions[std::size_t{vtx} * 3];
    }
    for (int a = 0; a <= samples_per_edge; ++a) {
      for (int b = 0; a + b <= samples_per_edge; ++b) {
        const double w[3] = {a / nsamples, b / nsamples, (samples_per_edge - a - b) / nsamples};
        double u = 0.0;
        double v = 0.0;
        double lin[3] = {0.0, 0.0, 0.0};
        for (std::size_t k = 0; k < 3; ++k) {
          u += w[k] * uv[k][0];
          v += w[k] * uv[k][1];
          for (std::size_t c = 0; c < 3; ++c) lin[c] += w[k] * static_cast<double>(pos[k][c]);
        }
        std::array<double, 3> S{};
        s.evaluate(u, v, S, 3);
        const double d[3] = {lin[0] - S[0], lin[1] - S[1], lin[2] - S[2]};
        worst = std::max(worst, norm3(d));
      }
    }
  }
  return worst;
}

bool BodyMeshes::update(const deform::DeformedBody& body, const TessellationOptions& o) {
  if (valid_ && body_ == &body && version_ == body.version() && options_ == o) return false;
  valid_ = false;
  tessellate(body.top(), o, false, top_);
  tessellate(body.bottom(), o, true, bottom_);
  body_ = &body;
  version_ = body.version();
  options_ = o;
  valid_ = true;
  return true;
}

}  // namespace palpa::render
