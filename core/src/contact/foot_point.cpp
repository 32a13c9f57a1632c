#include "palpa/contact/foot_point.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include "../common/numeric.hpp"

namespace palpa::contact {
namespace {

using spline::derivative_index;

// SK's xyz and its derivatives up to second order at (u, v).
struct Local {
  Vec3 s, su, sv, suu, suv, svv;
};

void local_frame(const spline::BSplineSurface& sk, double u, double v, Local& out) {
  std::array<double, 9 * 3> d;  // filled by derivatives()
  sk.derivatives(u, v, 2, d, 3);
  const auto at = [&](int k, int l) { return Vec3(&d[derivative_index(k, l, 2, 3, 0)]); };
  out.s = at(0, 0);
  out.su = at(1, 0);
  out.sv = at(0, 1);
  out.suu = at(2, 0);
  out.suv = at(1, 1);
  out.svv = at(0, 2);
}

Vec3 position(const spline::BSplineSurface& sk, double u, double v) {
  std::array<double, 3> p;
  sk.evaluate(u, v, p, 3);
  return {p[0], p[1], p[2]};
}


FootPoint finish(const Local& l, double u, double v, const Vec3& q, int iterations, bool converged) {
  FootPoint f;
  f.u = u;
  f.v = v;
  f.point = l.s;
  f.su = l.su;
  f.sv = l.sv;
  f.distance = (q - l.s).norm();
  f.iterations = iterations;
  f.converged = converged;
  return f;
}

// A step (du, dv) on the free parameters, and whether it is Newton's (else Gauss-Newton).
struct Step {
  double du = 0.0, dv = 0.0;
  bool newton = true;
};

// Newton matrix; Gauss-Newton (J^T J, positive semi-definite) where the Hessian is not
// positive definite, e.g. beyond the skeleton's radius of curvature.
Step newton_step(const Local& l, const Vec3& r, double gu, double gv, bool free_u, bool free_v) {
  const double guu = l.su.dot(l.su);
  const double guv = l.su.dot(l.sv);
  const double gvv = l.sv.dot(l.sv);
  double huu = guu + l.suu.dot(r);
  double huv = guv + l.suv.dot(r);
  double hvv = gvv + l.svv.dot(r);
  const double levenberg = 1e-12 * (guu + gvv) + std::numeric_limits<double>::min();
  Step step;
  if (free_u && free_v) {
    if (!(huu > 0.0 && huu * hvv - huv * huv > 0.0)) {
      huu = guu + levenberg;
      huv = guv;
      hvv = gvv + levenberg;
      step.newton = false;
    }
    const double det = huu * hvv - huv * huv;
    step.du = -(hvv * gu - huv * gv) / det;
    step.dv = -(huu * gv - huv * gu) / det;
  } else if (free_u) {
    step.newton = huu > 0.0;
    step.du = -gu / (step.newton ? huu : guu + levenberg);
  } else {
    step.newton = hvv > 0.0;
    step.dv = -gv / (step.newton ? hvv : gvv + levenberg);
  }
  return step;
}

// Backtracking on the projected step: f must decrease. The full step is taken almost
// always, so the trial point gets the whole local frame at once; later trials need only
// the position. Returns false when no decrease is possible (a minimum to round-off);
// else (un, vn) and their frame in `trial`.
bool line_search(const spline::BSplineSurface& skeleton, const Vec3& q, double u, double v, double f,
                 const Step& step, double& un, double& vn, Local& trial) {
  double alpha = 1.0;
  un = clamp01(u + step.du);
  vn = clamp01(v + step.dv);
  local_frame(skeleton, un, vn, trial);
  double fn = 0.5 * (trial.s - q).squaredNorm();
  if (fn < f) {
    if (step.newton) return true;
    // A Gauss-Newton step ignores the curvature of the skeleton, so where the distance
    // is flat (a probe near the skeleton's centre of curvature) it undershoots by far:
    // keep doubling it while f keeps falling.
    for (int k = 0; k < 30; ++k) {
      const double ue = clamp01(u + 2.0 * alpha * step.du);
      const double ve = clamp01(v + 2.0 * alpha * step.dv);
      if (ue == un && ve == vn) break;  // pinned by the box
      const double fe = 0.5 * (position(skeleton, ue, ve) - q).squaredNorm();
      if (!(fe < fn)) break;
      alpha *= 2.0;
      un = ue;
      vn = ve;
      fn = fe;
    }
    if (alpha > 1.0) local_frame(skeleton, un, vn, trial);
    return true;
  }
  for (int k = 1; k < 30; ++k) {
    alpha *= 0.5;
    un = clamp01(u + alpha * step.du);
    vn = clamp01(v + alpha * step.dv);
    fn = 0.5 * (position(skeleton, un, vn) - q).squaredNorm();
    if (fn < f) {
      local_frame(skeleton, un, vn, trial);
      return true;
    }
  }
  return false;
}

}  // namespace

FootPoint newton_foot_point(const spline::BSplineSurface& skeleton, const Vec3& q, double u0, double v0,
                            const NewtonOptions& options) {
  double u = clamp01(u0);
  double v = clamp01(v0);
  Local l;
  local_frame(skeleton, u, v, l);
  Vec3 r = l.s - q;
  double f = 0.5 * r.squaredNorm();
  int it = 0;
  bool converged = false;
  for (; it < options.max_iterations; ++it) {
    const double gu = l.su.dot(r);
    const double gv = l.sv.dot(r);
    // Active set: a parameter on its bound whose gradient points out of the box stays
    // there, and the search continues along the edge (or stops at a corner).
    const bool free_u = !((u <= 0.0 && gu > 0.0) || (u >= 1.0 && gu < 0.0));
    const bool free_v = !((v <= 0.0 && gv > 0.0) || (v >= 1.0 && gv < 0.0));
    if (!free_u && !free_v) {
      converged = true;
      break;
    }
    const Step step = newton_step(l, r, gu, gv, free_u, free_v);
    if (!std::isfinite(step.du) || !std::isfinite(step.dv)) break;
    // Converged when the full step is below the tolerance. When what the step could gain
    // (-g.d/2) is below the round-off of f (f = |r|^2/2 with r = S - Q carries an error of
    // about eps |S| |r|), f can no longer judge it, but the gradient (Su.r, Sv.r) is still
    // accurate: take the step as it is and stop. This last step matters: the depth
    // R(u,v) - |PQ| is first-order in (u, v) through R.
    if (std::max(std::abs(step.du), std::abs(step.dv)) < options.parameter_tolerance) {
      converged = true;
      break;
    }
    const double gain = -0.5 * (gu * step.du + gv * step.dv);
    const double noise = 8.0 * std::numeric_limits<double>::epsilon() * l.s.norm() * r.norm();
    if (step.newton && gain <= noise + std::numeric_limits<double>::min()) {
      u = clamp01(u + step.du);
      v = clamp01(v + step.dv);
      local_frame(skeleton, u, v, l);
      converged = true;
      ++it;
      break;
    }
    double un = u, vn = v;
    Local trial;
    if (!line_search(skeleton, q, u, v, f, step, un, vn, trial)) {
      converged = true;
      break;
    }
    const double moved = std::max(std::abs(un - u), std::abs(vn - v));
    u = un;
    v = vn;
    l = trial;
    r = l.s - q;
    f = 0.5 * r.squaredNorm();
    if (moved < options.parameter_tolerance) {
      converged = true;
      ++it;
      break;
    }
  }
  return finish(l, u, v, q, it, converged);
}

FootPoint bisect_foot_point(const spline::BSplineSurface& skeleton, const Vec3& q, int levels) {
  double ub = 0.0;
  double ue = 1.0;
  double vb = 0.0;
  double ve = 1.0;
  std::array<double, 4 * 3> d;
  int level = 0;
  for (; level < levels; ++level) {
    const double um = 0.5 * (ub + ue);
    const double vm = 0.5 * (vb + ve);
    skeleton.derivatives(um, vm, 1, d, 3);
    const Vec3 w = q - Vec3(&d[derivative_index(0, 0, 1, 3, 0)]);
    const double cu = w.dot(Vec3(&d[derivative_index(1, 0, 1, 3, 0)]));
    const double cv = w.dot(Vec3(&d[derivative_index(0, 1, 1, 3, 0)]));
    if (cu == 0.0 && cv == 0.0) {  // the normal passes through Q
      ub = ue = um;
      vb = ve = vm;
      break;
    }
    (cu > 0.0 ? ub : ue) = um;
    (cv > 0.0 ? vb : ve) = vm;
  }
  Local l;
  local_frame(skeleton, 0.5 * (ub + ue), 0.5 * (vb + ve), l);
  return finish(l, 0.5 * (ub + ue), 0.5 * (vb + ve), q, level, true);
}

FootPointSearch::FootPointSearch(const spline::BSplineSurface& skeleton, int samples_per_span)
    : per_span_(std::max(1, samples_per_span)) {
  resample(skeleton);
}

void FootPointSearch::resample(const spline::BSplineSurface& skeleton) {
  // Parameters: every distinct knot plus per_span_ - 1 points inside each span, so a
  // seed is never farther than a fraction of a span from the foot point.
  auto params = [this](const std::vector<double>& knots) {
    std::vector<double> out;
    for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
      if (!(knots[k + 1] > knots[k])) continue;
      for (int s = 0; s < per_span_; ++s) out.push_back(knots[k] + (knots[k + 1] - knots[k]) * s / per_span_);
    }
    out.push_back(knots.back());
    return out;
  };
  const auto us = params(skeleton.knots_u());
  const auto vs = params(skeleton.knots_v());
  const auto widest = [](const std::vector<double>& p) {
    double w = 0.0;
    for (std::size_t k = 1; k < p.size(); ++k) w = std::max(w, p[k] - p[k - 1]);
    return w;
  };
  spacing_u_ = widest(us);
  spacing_v_ = widest(vs);
  uv_.clear();
  points_.clear();
  uv_.reserve(us.size() * vs.size());
  points_.reserve(us.size() * vs.size());
  for (double u : us) {
    for (double v : vs) {
      uv_.push_back({u, v});
      points_.push_back(position(skeleton, u, v));
    }
  }
  // Every skeleton point lies within reach_ of some sample: half the largest gap between
  // neighbouring samples, with a margin for the bulge of the arc over its chord.
  double gap = 0.0;
  for (std::size_t i = 0; i < us.size(); ++i) {
    for (std::size_t j = 0; j < vs.size(); ++j) {
      const auto& p = points_[i * vs.size() + j];
      if (i + 1 < us.size()) gap = std::max(gap, (points_[(i + 1) * vs.size() + j] - p).norm());
      if (j + 1 < vs.size()) gap = std::max(gap, (points_[i * vs.size() + j + 1] - p).norm());
    }
  }
  reach_ = 0.75 * gap * std::sqrt(2.0);

  sample_cols_ = vs.size();
  blocks_.clear();
  constexpr std::size_t kBlock = 4;
  for (std::size_t i0 = 0; i0 < us.size(); i0 += kBlock) {
    for (std::size_t j0 = 0; j0 < vs.size(); j0 += kBlock) {
      Block b{Vec3::Zero(), 0.0, i0, std::min(i0 + kBlock, us.size()), j0, std::min(j0 + kBlock, vs.size())};
      double count = 0.0;
      for (std::size_t i = b.i0; i < b.i1; ++i)
        for (std::size_t j = b.j0; j < b.j1; ++j, count += 1.0) b.center += points_[i * sample_cols_ + j];
      b.center /= count;
      for (std::size_t i = b.i0; i < b.i1; ++i)
        for (std::size_t j = b.j0; j < b.j1; ++j)
          b.radius = std::max(b.radius, (points_[i * sample_cols_ + j] - b.center).norm());
      blocks_.push_back(b);
    }
  }
}

std::array<std::size_t, 3> FootPointSearch::nearest_samples(const Vec3& q, std::array<double, 3>& d2) const {
  std::array<std::size_t, 3> best{0, 0, 0};
  d2.fill(std::numeric_limits<double>::infinity());
  // Start with the block whose sphere is nearest, so the bound below prunes from the start.
  std::size_t first = 0;
  double first_bound = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    const double bound = (blocks_[b].center - q).norm() - blocks_[b].radius;
    if (bound < first_bound) {
      first_bound = bound;
      first = b;
    }
  }
  for (std::size_t n = 0; n <= blocks_.size(); ++n) {
    const std::size_t b = n == 0 ? first : n - 1;
    if (n > 0 && b == first) continue;
    const Block& block = blocks_[b];
    const double bound = (block.center - q).norm() - block.radius;
    if (bound > 0.0 && bound * bound >= d2[2]) continue;  // no sample of this block can enter the three
    for (std::size_t i = block.i0; i < block.i1; ++i) {
      for (std::size_t j = block.j0; j < block.j1; ++j) {
        const std::size_t k = i * sample_cols_ + j;
        insert_seed(k, (points_[k] - q).squaredNorm(), best, d2);
      }
    }
  }
  return best;
}

void FootPointSearch::insert_seed(std::size_t k, double dk, std::array<std::size_t, 3>& best,
                                  std::array<double, 3>& d2) const {
  {
    if (dk >= d2[2]) return;
    // Samples of a collapsed row (a pole) are copies of one point where Su = Sv = 0, so
    // Newton cannot leave it: let one copy stand for all, keeping the other seeds for
    // the rows around it.
    bool duplicate = false;
    for (std::size_t s = 0; s < 3 && std::isfinite(d2[s]); ++s) duplicate = duplicate || points_[best[s]] == points_[k];
    if (duplicate) return;
    std::size_t slot = 2;
    while (slot > 0 && dk < d2[slot - 1]) {
      d2[slot] = d2[slot - 1];
      best[slot] = best[slot - 1];
      --slot;
    }
    d2[slot] = dk;
    best[slot] = k;
  }
}

FootPoint FootPointSearch::closest(const spline::BSplineSurface& skeleton, const Vec3& q,
                                   const NewtonOptions& options) const {
  // Newton from the three nearest samples: on a concave skeleton near its centre of
  // curvature, or beyond a curved one's radius of curvature, several basins are nearly
  // as close, and the nearest sample alone can sit in the wrong one.
  std::array<double, 3> d2{};
  const auto seeds = nearest_samples(q, d2);
  FootPoint result;
  result.distance = std::numeric_limits<double>::infinity();
  for (std::size_t s = 0; s < seeds.size(); ++s) {
    if (!std::isfinite(d2[s])) break;
    const auto f = newton_foot_point(skeleton, q, uv_[seeds[s]].u, uv_[seeds[s]].v, options);
    if (f.distance < result.distance) result = f;
  }
  return result;
}

FootPoint FootPointSearch::closest_from(const spline::BSplineSurface& skeleton, const Vec3& q, double u0, double v0,
                                        const NewtonOptions& options) const {
  auto f = newton_foot_point(skeleton, q, u0, v0, options);
  // The three nearest samples tell whether another basin may hold the global minimum.
  // Newton runs again from each one that is nearer than the result or lies more than a
  // sample spacing away from it in parameter space (where the distance is flat, a
  // sample's offset in one direction can hide a better basin in the other); the nearest
  // answer wins. While tracking, the nearest samples sit next to the foot point and this
  // costs only the scan.
  std::array<double, 3> d2{};
  const auto seeds = nearest_samples(q, d2);
  const FootPoint tracked = f;
  for (std::size_t s = 0; s < seeds.size(); ++s) {
    if (!std::isfinite(d2[s])) break;
    const auto& seed = uv_[seeds[s]];
    const bool elsewhere = std::abs(seed.u - tracked.u) > spacing_u_ || std::abs(seed.v - tracked.v) > spacing_v_;
    // Nothing within reach_ of a sample can be nearer than (its distance - reach_).
    const bool could_be_nearer = std::sqrt(d2[s]) - reach_ < tracked.distance;
    if (!(d2[s] < tracked.distance * tracked.distance) && !(elsewhere && could_be_nearer)) continue;
    const auto g = newton_foot_point(skeleton, q, seed.u, seed.v, options);
    if (g.distance < f.distance) f = g;
  }
  return f;
}

}  // namespace palpa::contact
