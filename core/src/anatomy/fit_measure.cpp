// The fit error of an imported body: its contours sampled densely against the input
// surfaces (docs/anatomy-import.md, "Accuracy").
#include <algorithm>
#include <cmath>
#include <limits>

#include "palpa/anatomy/import_error.hpp"
#include "palpa/mat/mat_body.hpp"
#include "rim_distance.hpp"

namespace palpa::anatomy {

namespace {

constexpr int kSamplesPerInterval = 8;

// One chamfer pass (weights 1 and sqrt 2 in steps) in the given scan order.
void chamfer_pass(std::vector<double>& d, int ns, int nt, double step, bool forward) {
  const double diag = step * std::sqrt(2.0);
  const int da = forward ? -1 : 1;
  for (int bi = 0; bi < nt; ++bi) {
    const int b = forward ? bi : nt - 1 - bi;
    for (int ai = 0; ai < ns; ++ai) {
      const int a = forward ? ai : ns - 1 - ai;
      double& here = d[static_cast<std::size_t>(a + ns * b)];
      auto relax = [&](int x, int y, double w) {
        if (x >= 0 && y >= 0 && x < ns && y < nt) here = std::min(here, d[static_cast<std::size_t>(x + ns * y)] + w);
      };
      relax(a + da, b, step);
      relax(a, b + da, step);
      relax(a + da, b + da, diag);
      relax(a - da, b + da, diag);
    }
  }
}

struct Accumulator {
  SurfaceError error;
  double sum = 0.0, interior_sum = 0.0;
  long count = 0, interior_count = 0;

  void add(double d, bool interior, const Vec3& p) {
    if (std::isnan(d)) return;
    if (d > error.max) {
      error.max = d;
      error.worst = p;
    }
    sum += d * d;
    ++count;
    if (interior) {
      error.interior_max = std::max(error.interior_max, d);
      interior_sum += d * d;
      ++interior_count;
    }
  }
  SurfaceError finish() {
    error.rms = count > 0 ? std::sqrt(sum / static_cast<double>(count)) : 0.0;
    error.interior_rms = interior_count > 0 ? std::sqrt(interior_sum / static_cast<double>(interior_count)) : 0.0;
    return error;
  }
};

double rim_at(const SurfacePair& pair, const std::vector<double>& rim, const Vec3& p) {
  const Vec3 q = pair.frame.to_local(p);
  const HeightField& f = pair.top;
  const int a = std::clamp(static_cast<int>(std::lround((q.x() - f.s0) / f.step)), 0, f.ns - 1);
  const int b = std::clamp(static_cast<int>(std::lround((q.y() - f.t0) / f.step)), 0, f.nt - 1);
  return rim[static_cast<std::size_t>(a + f.ns * b)];
}

std::vector<double> dense_params(const std::vector<double>& sites) {
  std::vector<double> out;
  for (std::size_t i = 0; i + 1 < sites.size(); ++i) {
    for (int k = 0; k < kSamplesPerInterval; ++k) {
      out.push_back(sites[i] + (sites[i + 1] - sites[i]) * k / kSamplesPerInterval);
    }
  }
  out.push_back(sites.back());
  return out;
}

mat::MatBody fit_geometry(const mat::BodyGrid& grid) {
  mat::BodyGrid geometry = grid;
  geometry.stiffness.assign(grid.point_count(), 1.0);  // any uniform tissue: only the shape is measured
  geometry.modulus.clear();
  try {
    return mat::MatBody::fit(geometry);
  } catch (const mat::FitError& e) {
    throw ImportError(e.what());
  }
}

}  // namespace

std::vector<double> rim_distance(const SurfacePair& pair) {
  const HeightField& top = pair.top;
  const auto n = static_cast<std::size_t>(top.ns) * static_cast<std::size_t>(top.nt);
  std::vector<char> inside(n);
  for (std::size_t k = 0; k < n; ++k) inside[k] = top.h[k] - pair.bottom.h[k] > 0.5 * pair.resolution;
  // Distance to the nearest inside sample, and to the nearest outside one; each sample keeps
  // the one across the rim from it.
  std::vector<double> to_in(n), to_out(n);
  for (std::size_t k = 0; k < n; ++k) {
    to_in[k] = inside[k] ? 0.0 : std::numeric_limits<double>::infinity();
    to_out[k] = inside[k] ? std::numeric_limits<double>::infinity() : 0.0;
  }
  for (auto* d : {&to_in, &to_out}) {
    chamfer_pass(*d, top.ns, top.nt, top.step, true);
    chamfer_pass(*d, top.ns, top.nt, top.step, false);
  }
  std::vector<double> rim(n);
  for (std::size_t k = 0; k < n; ++k) rim[k] = inside[k] ? to_out[k] : to_in[k];
  return rim;
}

void measure_fit(const SurfacePair& pair, FittedBody& fitted) {
  const mat::MatBody body = fit_geometry(fitted.grid);
  const auto rim = rim_distance(pair);
  Accumulator top, bottom;
  double p[3];
  for (double u : dense_params(body.u_params())) {
    for (double v : dense_params(body.v_params())) {
      body.top().evaluate(u, v, p);
      const Vec3 pt(p[0], p[1], p[2]);
      top.add(surface_distance(pair, pair.top, pt), rim_at(pair, rim, pt) >= fitted.report.rim_band, pt);
      body.bottom().evaluate(u, v, p);
      const Vec3 pb(p[0], p[1], p[2]);
      bottom.add(surface_distance(pair, pair.bottom, pb), rim_at(pair, rim, pb) >= fitted.report.rim_band, pb);
    }
  }
  fitted.report.top = top.finish();
  fitted.report.bottom = bottom.finish();
}

}  // namespace palpa::anatomy
