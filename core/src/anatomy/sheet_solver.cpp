// Newton's method on the whole skeleton sheet (docs/anatomy-import.md, "The fitting method").
// Each interior site contributes two equations (its top contour point on the free surface,
// its bottom one on the support) in its own height and radius and, through the skeleton's
// normal, in its neighbours' heights: a transport-like system that a site-by-site sweep
// amplifies where the radius exceeds the grid spacing, so it is solved as one.
#include <algorithm>
#include <cmath>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "sheet.hpp"

namespace palpa::anatomy {

namespace {

constexpr int kMaxIterations = 40;
constexpr double kConverged = 1e-7;  // m: the largest residual or step, 0.1 um
constexpr double kStalled = 1e-4;    // a step that lowers the cost by less than this share ends the solve
// The weight of the sheet's second differences against the contours' misses (both in m):
// small enough that a smooth sheet keeps its exact solution within a few um, large enough
// that a sheet zigzagging between sites (the system's unstable modes) costs more than it fits.
constexpr double kSmoothing = 0.05;

using Triplets = std::vector<Eigen::Triplet<double>>;

// Unknown numbers: 2k (height) and 2k + 1 (radius) for active site k. Active: interior
// sites with tissue under them; the others rest on the support with radius 0.
struct Unknowns {
  int rows = 0, cols = 0;
  std::vector<int> index;  // per site: its height's unknown, or -1
  int count = 0;

  Unknowns(const SurfacePair& pair, const Sheet& sheet) : rows(sheet.rows), cols(sheet.cols) {
    index.assign(sheet.sites.size(), -1);
    for (int i = 1; i < rows - 1; ++i) {
      for (int j = 1; j < cols - 1; ++j) {
        const double s = sheet.s[static_cast<std::size_t>(i)], t = sheet.t[static_cast<std::size_t>(j)];
        if (pair.top.sample(s, t) - pair.bottom.sample(s, t) > 0.0) {
          index[sheet.at(i, j)] = count;
          count += 2;
        }
      }
    }
  }
  int height(const Sheet& sheet, int i, int j) const { return index[sheet.at(i, j)]; }
};

double residuals(const SurfacePair& pair, const Sheet& sheet, const Unknowns& u, Eigen::VectorXd& f) {
  const auto normals = site_normals(pair, sheet);
  f.setZero(u.count);
  for (int i = 1; i < sheet.rows - 1; ++i) {
    for (int j = 1; j < sheet.cols - 1; ++j) {
      if (u.height(sheet, i, j) < 0) continue;
      const auto r = site_residual(pair, sheet.s[static_cast<std::size_t>(i)], sheet.t[static_cast<std::size_t>(j)],
                                   normals[sheet.at(i, j)], sheet.sites[sheet.at(i, j)]);
      f[u.height(sheet, i, j)] = r.ok ? r.f1 : 0.0;
      f[u.height(sheet, i, j) + 1] = r.ok ? r.f2 : 0.0;
    }
  }
  return f.cwiseAbs().maxCoeff();
}

// The Jacobian of the site equations. In a site's own radius it is exact (the radius
// does not move the normal); in the heights it is taken by finite differences, one pass per
// colour of a 3 x 3 colouring of the grid: sites of one colour are 3 apart, so the rows a
// height moves (its own site's and its 4 neighbours', through the normal) are told apart.
// The interpolating spline reaches farther, but faintly.
Eigen::SparseMatrix<double> jacobian(const SurfacePair& pair, const Sheet& sheet, const Unknowns& u,
                                     const Eigen::VectorXd& f) {
  constexpr double kStep = 1e-6;  // m
  Triplets triplets;
  triplets.reserve(static_cast<std::size_t>(u.count) * 10);
  const auto normals = site_normals(pair, sheet);
  for (int i = 1; i < sheet.rows - 1; ++i) {
    for (int j = 1; j < sheet.cols - 1; ++j) {
      const int k = u.height(sheet, i, j);
      if (k < 0) continue;
      const auto r = site_residual(pair, sheet.s[static_cast<std::size_t>(i)], sheet.t[static_cast<std::size_t>(j)],
                                   normals[sheet.at(i, j)], sheet.sites[sheet.at(i, j)]);
      triplets.emplace_back(k, k + 1, r.ok ? r.d1 : 1.0);
      triplets.emplace_back(k + 1, k + 1, r.ok ? r.d2 : -1.0);
    }
  }
  for (int colour = 0; colour < 9; ++colour) {
    Sheet probe = sheet;
    for (int i = 1 + colour / 3; i < sheet.rows - 1; i += 3) {
      for (int j = 1 + colour % 3; j < sheet.cols - 1; j += 3) probe.sites[probe.at(i, j)].m += kStep;
    }
    Eigen::VectorXd fp;
    residuals(pair, probe, u, fp);
    for (int i = 1 + colour / 3; i < sheet.rows - 1; i += 3) {
      for (int j = 1 + colour % 3; j < sheet.cols - 1; j += 3) {
        const int col = u.height(sheet, i, j);
        if (col < 0) continue;
        for (int di = -1; di <= 1; ++di) {
          for (int dj = -1; dj <= 1; ++dj) {
            if (di != 0 && dj != 0) continue;  // the diagonal neighbours' share is small and doubles the fill
            const int row = u.height(sheet, i + di, j + dj);
            if (row < 0) continue;
            for (int e = 0; e < 2; ++e) {
              const double d = (fp[row + e] - f[row + e]) / kStep;
              if (d != 0.0) triplets.emplace_back(row + e, col, d);
            }
          }
        }
      }
    }
  }
  Eigen::SparseMatrix<double> jac(u.count, u.count);
  jac.setFromTriplets(triplets.begin(), triplets.end());
  return jac;
}

// The sheet moved by `scale` times `step`, radii kept >= 0.
Sheet moved(const Sheet& sheet, const Unknowns& u, const Eigen::VectorXd& step, double scale) {
  Sheet out = sheet;
  for (int i = 1; i < sheet.rows - 1; ++i) {
    for (int j = 1; j < sheet.cols - 1; ++j) {
      const int k = u.height(sheet, i, j);
      if (k < 0) continue;
      Site& x = out.sites[out.at(i, j)];
      x.m += scale * step[k];
      x.r = std::max(0.0, x.r + scale * step[k + 1]);
    }
  }
  return out;
}

// The smoothing rows: kSmoothing times the second difference of the height and of the
// radius at each active site whose two neighbours along a direction are active too.
Eigen::SparseMatrix<double> smoothing(const Sheet& sheet, const Unknowns& u, double weight) {
  Triplets triplets;
  int row = 0;
  for (int i = 1; i < sheet.rows - 1; ++i) {
    for (int j = 1; j < sheet.cols - 1; ++j) {
      const int k = u.height(sheet, i, j);
      if (k < 0) continue;
      const int pairs[2][2] = {{u.height(sheet, i - 1, j), u.height(sheet, i + 1, j)},
                               {u.height(sheet, i, j - 1), u.height(sheet, i, j + 1)}};
      for (const auto& p : pairs) {
        if (p[0] < 0 || p[1] < 0) continue;
        for (int c = 0; c < 2; ++c) {  // height, then radius
          triplets.emplace_back(row, p[0] + c, weight);
          triplets.emplace_back(row, k + c, -2.0 * weight);
          triplets.emplace_back(row, p[1] + c, weight);
          ++row;
        }
      }
    }
  }
  Eigen::SparseMatrix<double> d(row, u.count);
  d.setFromTriplets(triplets.begin(), triplets.end());
  return d;
}

Eigen::VectorXd unknowns_of(const Sheet& sheet, const Unknowns& u) {
  Eigen::VectorXd x(u.count);
  for (int i = 1; i < sheet.rows - 1; ++i) {
    for (int j = 1; j < sheet.cols - 1; ++j) {
      const int k = u.height(sheet, i, j);
      if (k < 0) continue;
      x[k] = sheet.sites[sheet.at(i, j)].m;
      x[k + 1] = sheet.sites[sheet.at(i, j)].r;
    }
  }
  return x;
}

// The whole cost: the site equations squared plus the smoothing rows squared.
double cost_of(const SurfacePair& pair, const Sheet& sheet, const Unknowns& u, const Eigen::SparseMatrix<double>& d,
               Eigen::VectorXd& f, double& worst) {
  worst = residuals(pair, sheet, u, f);
  return f.squaredNorm() + (d * unknowns_of(sheet, u)).squaredNorm();
}

// One Levenberg-Marquardt step: true when the cost went down (mu then shrinks).
bool lm_step(const SurfacePair& pair, Sheet& sheet, const Unknowns& u, const Eigen::SparseMatrix<double>& d,
             Eigen::VectorXd& f, double& cost, double& worst, double& mu, double& largest) {
  const Eigen::SparseMatrix<double> jac = jacobian(pair, sheet, u, f);
  const Eigen::SparseMatrix<double> jtj = Eigen::SparseMatrix<double>(jac.transpose() * jac) + Eigen::SparseMatrix<double>(d.transpose() * d);
  const Eigen::VectorXd g = jac.transpose() * f + d.transpose() * (d * unknowns_of(sheet, u));
  for (int attempt = 0; attempt < 8; ++attempt, mu *= 10.0) {
    Eigen::SparseMatrix<double> a = jtj;
    for (int k = 0; k < a.rows(); ++k) a.coeffRef(k, k) += mu * (1.0 + jtj.coeff(k, k));
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(a);
    if (solver.info() != Eigen::Success) continue;
    const Eigen::VectorXd step = solver.solve(-g);
    if (!step.allFinite()) continue;
    Sheet trial = moved(sheet, u, step, 1.0);
    Eigen::VectorXd ft;
    double trial_worst = 0.0;
    const double trial_cost = cost_of(pair, trial, u, d, ft, trial_worst);
    if (trial_cost < cost) {
      sheet = std::move(trial);
      f = std::move(ft);
      cost = trial_cost;
      worst = trial_worst;
      largest = step.cwiseAbs().maxCoeff();
      mu = std::max(mu * 0.1, 1e-12);
      return true;
    }
  }
  return false;
}

// kSmoothing, grown with the sheet's radius over its grid spacing: the zigzag modes grow
// with that ratio (a height step of one site tilts the normal by step / spacing, which
// moves the contours by radius times that).
double smoothing_weight(const Sheet& sheet, const Unknowns& u) {
  std::vector<double> radii;
  for (int i = 1; i < sheet.rows - 1; ++i) {
    for (int j = 1; j < sheet.cols - 1; ++j) {
      if (u.height(sheet, i, j) >= 0) radii.push_back(sheet.sites[sheet.at(i, j)].r);
    }
  }
  if (radii.empty()) return kSmoothing;
  std::nth_element(radii.begin(), radii.begin() + static_cast<std::ptrdiff_t>(radii.size() / 2), radii.end());
  const double spacing = std::min(sheet.s[1] - sheet.s[0], sheet.t[1] - sheet.t[0]);
  return kSmoothing * std::max(1.0, radii[radii.size() / 2] / spacing);
}

}  // namespace

int solve_sheet(const SurfacePair& pair, Sheet& sheet) {
  if (sheet.rows < 3 || sheet.cols < 3) return 0;
  const Unknowns u(pair, sheet);
  if (u.count == 0) return 0;
  const Eigen::SparseMatrix<double> d = smoothing(sheet, u, smoothing_weight(sheet, u));
  Eigen::VectorXd f;
  double worst = 0.0;
  double cost = cost_of(pair, sheet, u, d, f, worst);
  double mu = 1e-6;
  int iteration = 0;
  while (iteration < kMaxIterations && worst > kConverged) {
    ++iteration;
    double largest = 0.0;
    const double before = cost;
    if (!lm_step(pair, sheet, u, d, f, cost, worst, mu, largest) || largest < kConverged) break;
    if (iteration >= 2 && before - cost < kStalled * before) break;
  }
  return iteration;
}

}  // namespace palpa::anatomy
