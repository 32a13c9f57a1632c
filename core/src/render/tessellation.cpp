#include "palpa/render/tessellation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "palpa/mat/mat_body.hpp"
#include "palpa/spline/basis.hpp"
#include "../common/numeric.hpp"

namespace palpa::render {
namespace {

// Relative size below which a tangent or the cross product counts as vanished (as in
// mat::skeleton_normal, which then gives the limit direction).
constexpr double kDegenerate = 1e-10;
// A float holds a coordinate to within 2^-24 of its magnitude (round to nearest).
constexpr double kFloatRounding = 0x1p-24;


double norm3(const double* x) { return std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]); }

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

// The grid for `o.tolerance` with the float rounding of the stored positions set aside:
// each coordinate rounds by at most 2^-24 of its size, and |S| <= the largest control
// point (convex hull), so the drawn mesh stays within the tolerance, rounding included.
void choose_rounded_grid(const spline::BSplineSurface& s, const TessellationOptions& o, Mesh& out) {
  const auto dim = idx(s.dim());
  const auto& ctrl = s.control();
  double pmax = 0.0;
  for (std::size_t k = 0; k < ctrl.size(); k += dim) pmax = std::max(pmax, norm3(&ctrl[k]));
  TessellationOptions geometric = o;
  const double rounding = kFloatRounding * pmax * std::sqrt(3.0);
  geometric.tolerance = o.tolerance > rounding ? o.tolerance - rounding : std::numeric_limits<double>::min();
  out.error_bound = choose_grid(s, geometric, out.grid, out.us, out.vs) + rounding;
}

// Scratch: the v basis (values and first derivatives) of every grid column, then room for
// the row curve. Returns the row curve's offset in out.scratch.
std::size_t tabulate_v_basis(const spline::BSplineSurface& s, Mesh& out) {
  const int q = s.degree_v();
  const std::size_t cols = out.vs.size();
  const std::size_t vstride = 2 * idx(q + 1);
  const std::size_t vtable = cols * vstride;
  out.scratch.resize(vtable + idx(s.cols()) * 6);
  out.scratch_spans.resize(cols);
  for (std::size_t j = 0; j < cols; ++j) {
    const double v = out.vs[j];
    const int span = spline::find_span(s.cols(), q, v, s.knots_v());
    out.scratch_spans[j] = span;
    spline::basis_function_derivatives(span, v, q, 1, s.knots_v(), &out.scratch[j * vstride]);
  }
  return vtable;
}

// The row curve at u: C_b = sum_a N_a(u) P_ab and D_b = sum_a N'_a(u) P_ab for every
// control column b (xyz, then its u derivative), so each vertex costs a sum over q + 1.
void row_curve(const spline::BSplineSurface& s, double u, double* curve) {
  const int p = s.degree_u();
  const int ccols = s.cols();
  const auto dim = idx(s.dim());
  const auto& ctrl = s.control();
  std::array<double, 2 * (spline::kMaxDegree + 1)> nu_ders{};
  const int span_u = spline::find_span(s.rows(), p, u, s.knots_u());
  spline::basis_function_derivatives(span_u, u, p, 1, s.knots_u(), nu_ders.data());
  const double* nu = nu_ders.data();
  const double* du = nu_ders.data() + (p + 1);
  for (int b = 0; b < ccols; ++b) {
    double* cb = curve + idx(b) * 6;
    for (int k = 0; k < 6; ++k) cb[k] = 0.0;
    for (int a = 0; a <= p; ++a) {
      const double* P = &ctrl[idx((span_u - p + a) * ccols + b) * dim];
      for (int k = 0; k < 3; ++k) {
        cb[k] += nu[a] * P[k];
        cb[3 + k] += du[a] * P[k];
      }
    }
  }
}

// The vertices of grid row i from its row curve. Returns whether a normal was degenerate
// (left 0 for fill_degenerate_normals).
bool evaluate_row(const spline::BSplineSurface& s, const double* curve, int i, float sign, Mesh& out) {
  const int q = s.degree_v();
  const std::size_t cols = out.vs.size();
  const std::size_t vstride = 2 * idx(q + 1);
  bool any_degenerate = false;
  for (std::size_t j = 0; j < cols; ++j) {
    const double* nv = &out.scratch[j * vstride];
    const double* dv = nv + (q + 1);
    const int first = out.scratch_spans[j] - q;
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
    const std::size_t vtx = (idx(i) * cols + j) * 3;
    const double N[3] = {Su[1] * Sv[2] - Su[2] * Sv[1], Su[2] * Sv[0] - Su[0] * Sv[2], Su[0] * Sv[1] - Su[1] * Sv[0]};
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
  return any_degenerate;
}

// One vertex where Su x Sv vanished: the limit direction from the interior (a pole row or
// column, mat::skeleton_normal), else the mean of the neighbours' normals, else the mean
// over the whole grid, else +-z.
void fill_degenerate_normal(const spline::BSplineSurface& s, int i, int j, float sign, Mesh& out) {
  const int rows = static_cast<int>(out.us.size());
  const int cols = static_cast<int>(out.vs.size());
  float* nrm = &out.normals[(idx(i) * idx(cols) + idx(j)) * 3];
  double limit[3];
  if (mat::skeleton_normal(s, out.us[idx(i)], out.vs[idx(j)], limit)) {
    for (int k = 0; k < 3; ++k) nrm[k] = sign * static_cast<float>(limit[k]);
    return;
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

void fill_degenerate_normals(const spline::BSplineSurface& s, float sign, Mesh& out) {
  const int rows = static_cast<int>(out.us.size());
  const int cols = static_cast<int>(out.vs.size());
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      const float* nrm = &out.normals[(idx(i) * idx(cols) + idx(j)) * 3];
      if (nrm[0] == 0.0f && nrm[1] == 0.0f && nrm[2] == 0.0f) fill_degenerate_normal(s, i, j, sign, out);
    }
  }
}

}  // namespace

void tessellate(const spline::BSplineSurface& s, const TessellationOptions& o, bool outward_is_minus_normal,
                Mesh& out) {
  if (!(o.tolerance > 0.0) || !std::isfinite(o.tolerance)) {
    throw std::invalid_argument("tessellation: the tolerance must be positive and finite");
  }
  if (s.dim() < 3) throw std::invalid_argument("tessellate: the surface has fewer than 3 channels");
  choose_rounded_grid(s, o, out);
  const int rows = static_cast<int>(out.us.size());
  const int cols = static_cast<int>(out.vs.size());
  const std::size_t curve_at = tabulate_v_basis(s, out);
  const std::size_t n = idx(rows) * idx(cols);
  out.positions.resize(n * 3);
  out.normals.resize(n * 3);
  const float sign = outward_is_minus_normal ? -1.0f : 1.0f;
  bool any_degenerate = false;
  for (int i = 0; i < rows; ++i) {
    row_curve(s, out.us[idx(i)], &out.scratch[curve_at]);
    any_degenerate = evaluate_row(s, &out.scratch[curve_at], i, sign, out) || any_degenerate;
  }
  if (any_degenerate) fill_degenerate_normals(s, sign, out);

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
  const auto cols = static_cast<std::uint32_t>(mesh.cols);
  const auto nsamples = static_cast<double>(samples_per_edge);
  double worst = 0.0;
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    double uv[3][2];
    const float* pos[3];
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t vtx = mesh.triangles[t + k];
      uv[k][0] = mesh.us[vtx / cols];
      uv[k][1] = mesh.vs[vtx % cols];
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
