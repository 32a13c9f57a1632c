// The least-squares MAT fit of a body on a support (docs/anatomy-import.md, "The fitting
// method"): the grid over the tissue's footprint, the midpoint start, the sheet solved by
// Newton's method (sheet_solver.cpp), and the grid chosen by its fit error.
#include "palpa/anatomy/mat_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "palpa/anatomy/import_error.hpp"
#include "palpa/mat/mat_body.hpp"
#include "rim_distance.hpp"  // measure_fit
#include "sheet.hpp"

namespace palpa::anatomy {

namespace {

double thickness_at(const SurfacePair& pair, double s, double t) {
  return std::max(0.0, pair.top.sample(s, t) - pair.bottom.sample(s, t));
}

struct Footprint {
  double s_lo = 0.0, s_hi = 0.0, t_lo = 0.0, t_hi = 0.0;
};

Footprint footprint(const SurfacePair& pair) {
  Footprint box{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  const HeightField& top = pair.top;
  for (int b = 0; b < top.nt; ++b) {
    for (int a = 0; a < top.ns; ++a) {
      if (!(top.at(a, b) - pair.bottom.at(a, b) > 0.5 * pair.resolution)) continue;
      box.s_lo = std::min(box.s_lo, top.s_at(a));
      box.s_hi = std::max(box.s_hi, top.s_at(a));
      box.t_lo = std::min(box.t_lo, top.t_at(b));
      box.t_hi = std::max(box.t_hi, top.t_at(b));
    }
  }
  if (!(box.s_hi > box.s_lo && box.t_hi > box.t_lo)) throw ImportError("no tissue between the support and the free surface");
  return box;
}

// rows sites from one spacing before lo to one after hi.
std::vector<double> site_positions(double lo, double hi, int count) {
  const double step = (hi - lo) / (count - 3);
  std::vector<double> out(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) out[static_cast<std::size_t>(i)] = lo + (i - 1) * step;
  return out;
}

// The coarser fit's height and radius at (s, t), bilinear between its sites.
Site from_coarser(const FittedBody& coarse, const Frame& frame, double s, double t) {
  const auto& ss = coarse.s_sites;
  const auto& ts = coarse.t_sites;
  const auto locate = [](const std::vector<double>& x, double v, std::size_t& i, double& w) {
    const auto it = std::upper_bound(x.begin() + 1, x.end() - 1, v);
    i = static_cast<std::size_t>(it - x.begin()) - 1;
    w = std::clamp((v - x[i]) / (x[i + 1] - x[i]), 0.0, 1.0);
  };
  std::size_t i = 0, j = 0;
  double wi = 0.0, wj = 0.0;
  locate(ss, s, i, wi);
  locate(ts, t, j, wj);
  const auto cols = static_cast<std::size_t>(coarse.grid.cols);
  Site out;
  for (int c = 0; c < 4; ++c) {
    const std::size_t a = i + static_cast<std::size_t>(c & 1), b = j + static_cast<std::size_t>(c >> 1);
    const double w = ((c & 1) ? wi : 1.0 - wi) * ((c >> 1) ? wj : 1.0 - wj);
    out.m += w * frame.to_local(to_vec3(coarse.grid.medial[a * cols + b])).z();
    out.r += w * coarse.grid.radius[a * cols + b];
  }
  return out;
}

Sheet initial_sheet(const SurfacePair& pair, int rows, int cols, const FittedBody* start) {
  const Footprint box = footprint(pair);
  Sheet sheet;
  sheet.s = site_positions(box.s_lo, box.s_hi, rows);
  sheet.t = site_positions(box.t_lo, box.t_hi, cols);
  sheet.rows = rows;
  sheet.cols = cols;
  sheet.sites.resize(static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols));
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      const double s = sheet.s[static_cast<std::size_t>(i)], t = sheet.t[static_cast<std::size_t>(j)];
      const double hb = pair.bottom.sample(s, t);
      const bool rim = i == 0 || j == 0 || i == rows - 1 || j == cols - 1;
      const double half = rim ? 0.0 : 0.5 * thickness_at(pair, s, t);
      Site site{hb + half, half};
      if (start != nullptr && !rim && half > 0.0) site = from_coarser(*start, pair.frame, s, t);
      sheet.sites[static_cast<std::size_t>(i * cols + j)] = site;
    }
  }
  return sheet;
}

// The rim rounded over `band` (m): where the free surface meets the support the thickness
// has a kink that an interpolating spline overshoots into a negative radius, so there the
// thickness is blended into its Gaussian blur of `sigma`; farther in the surfaces stay.
SurfacePair rounded_rim(const SurfacePair& pair, double sigma, double band) {
  SurfacePair out = pair;
  HeightField thickness = pair.top;
  for (std::size_t k = 0; k < thickness.h.size(); ++k) thickness.h[k] = pair.top.h[k] - pair.bottom.h[k];
  const HeightField smooth = blurred(thickness, sigma);
  const auto rim = rim_distance(pair);
  for (std::size_t k = 0; k < thickness.h.size(); ++k) {
    const double w = std::clamp(rim[k] / band, 0.0, 1.0);
    out.top.h[k] = pair.bottom.h[k] + w * thickness.h[k] + (1.0 - w) * smooth.h[k];
  }
  return out;
}

mat::BodyGrid to_grid(const SurfacePair& pair, const Sheet& sheet, const std::string& id) {
  mat::BodyGrid grid;
  grid.id = id;
  grid.support = mat::Support::Bottom;
  grid.rows = sheet.rows;
  grid.cols = sheet.cols;
  const auto xyz = skeleton_xyz(pair, sheet);
  for (std::size_t k = 0; k < sheet.sites.size(); ++k) {
    grid.medial.push_back({xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]});
    grid.radius.push_back(sheet.sites[k].r);
  }
  return grid;
}

}  // namespace

FittedBody fit_body(const SurfacePair& pair, int rows, int cols, const std::string& id, const FittedBody* start) {
  if (rows < 5 || cols < 5) throw ImportError(fmt::format("grid {}x{}: at least 5x5 is needed", rows, cols));
  Sheet sheet = initial_sheet(pair, rows, cols, start);
  const double spacing = std::max(sheet.s[1] - sheet.s[0], sheet.t[1] - sheet.t[0]);
  FittedBody out;
  out.report.rim_band = std::max(spacing, 2.0 * pair.resolution);
  const SurfacePair rounded = rounded_rim(pair, 0.5 * spacing, out.report.rim_band);
  out.report.iterations = solve_sheet(rounded, sheet);
  out.grid = to_grid(pair, sheet, id);
  out.s_sites = sheet.s;
  out.t_sites = sheet.t;
  measure_fit(pair, out);
  return out;
}

// m: the default grid is at least this fine, whatever the fit error: about a finger pad's
// width, so that the tissue and the tumours are placed where the finger meets them.
constexpr double kCoarsestSpacing = 10e-3;

FittedBody fit_body_auto(const SurfacePair& pair, const std::string& id) {
  const Footprint box = footprint(pair);
  const double ls = box.s_hi - box.s_lo, lt = box.t_hi - box.t_lo;
  FittedBody best, last;
  double best_error = std::numeric_limits<double>::infinity();
  double spacing = std::max(ls, lt) / 8.0;
  int stalled = 0;
  for (bool finest = false; !finest;) {
    const int rows = std::clamp(static_cast<int>(std::ceil(ls / spacing)) + 3, 9, 65);
    const int cols = std::clamp(static_cast<int>(std::ceil(lt / spacing)) + 3, 9, 65);
    finest = rows == 65 && cols == 65;
    double error = std::numeric_limits<double>::infinity();
    try {
      last = fit_body(pair, rows, cols, id, last.grid.rows > 0 ? &last : nullptr);
      error = std::max(last.report.top.interior_max, last.report.bottom.interior_max);
      const bool improved = error < 0.9 * best_error;
      if (error < best_error) {
        best_error = error;
        best = last;
      }
      // Met, or two finer grids in a row did not help: what is left is in the data (a
      // feature smaller than the grid can follow, or noise), and finer grids cost more.
      stalled = improved ? 0 : stalled + 1;
      const double reached = std::max(last.s_sites[1] - last.s_sites[0], last.t_sites[1] - last.t_sites[0]);
      if (error <= kFitTarget || (stalled >= 2 && reached <= kCoarsestSpacing)) break;
    } catch (const ImportError&) {
      if (finest && best.grid.rows == 0) throw;
    }
    spacing /= error > 4.0 * kFitTarget ? 2.0 : std::sqrt(2.0);
  }
  return best;
}

}  // namespace palpa::anatomy
