#include "palpa/contact/column.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "../common/numeric.hpp"

namespace palpa::contact {
namespace {

using spline::derivative_index;

struct Frame1 {
  Vec3 s, su, sv;
};

void first_order(const spline::BSplineSurface& sk, double u, double v, Frame1& out) {
  std::array<double, 4 * 3> d;
  sk.derivatives(u, v, 1, d, 3);
  out.s = Vec3(&d[derivative_index(0, 0, 1, 3, 0)]);
  out.su = Vec3(&d[derivative_index(1, 0, 1, 3, 0)]);
  out.sv = Vec3(&d[derivative_index(0, 1, 1, 3, 0)]);
}

Vec3 across(const Vec3& x, const Vec3& axis) { return x - x.dot(axis) * axis; }

}  // namespace

PressAxis press_axis_of(const spline::BSplineSurface& skeleton, int samples) {
  samples = std::max(samples, 2);
  Vec3 sum = Vec3::Zero();
  std::vector<Vec3> normals;
  normals.reserve(static_cast<std::size_t>(samples * samples));
  Frame1 f;
  for (int i = 0; i < samples; ++i) {
    for (int j = 0; j < samples; ++j) {
      const double u = static_cast<double>(i) / (samples - 1), v = static_cast<double>(j) / (samples - 1);
      first_order(skeleton, u, v, f);
      const Vec3 n = f.su.cross(f.sv);  // its length is the area element: the weight
      sum += n;
      double unit[3];
      if (mat::skeleton_normal(skeleton, u, v, unit)) normals.emplace_back(unit[0], unit[1], unit[2]);
    }
  }
  PressAxis axis;
  if (!(sum.norm() > 0.0) || normals.empty()) return axis;  // no area: no axis, not usable
  axis.up = sum.normalized();
  axis.min_cosine = 1.0;
  for (const auto& n : normals) axis.min_cosine = std::min(axis.min_cosine, n.dot(axis.up));
  axis.usable = axis.min_cosine > std::cos(kMaxColumnTilt);
  return axis;
}

FootPoint column_foot_point(const spline::BSplineSurface& skeleton, const Vec3& axis, const Vec3& q, double u0,
                            double v0) {
  double u = clamp01(u0), v = clamp01(v0);
  Frame1 f;
  first_order(skeleton, u, v, f);
  Vec3 r = across(f.s - q, axis);
  double g = r.squaredNorm();
  const double scale = std::max(q.norm(), f.s.norm());
  int it = 0;
  constexpr int kMaxIterations = 40;
  for (; it < kMaxIterations; ++it) {
    const Vec3 ju = across(f.su, axis), jv = across(f.sv, axis);
    Eigen::Matrix2d a;
    a << ju.dot(ju), ju.dot(jv), ju.dot(jv), jv.dot(jv);
    const double levenberg = 1e-12 * a.trace() + std::numeric_limits<double>::min();
    a(0, 0) += levenberg;
    a(1, 1) += levenberg;
    const Eigen::Vector2d b(-ju.dot(r), -jv.dot(r));
    const Eigen::Vector2d step = a.ldlt().solve(b);
    if (!step.allFinite()) break;
    // Backtracking on the projected step: the residual across the axis must shrink.
    double alpha = 1.0, un = u, vn = v;
    Frame1 trial;
    bool decreased = false;
    for (int k = 0; k < 30 && !decreased; ++k, alpha *= 0.5) {
      un = clamp01(u + alpha * step[0]);
      vn = clamp01(v + alpha * step[1]);
      first_order(skeleton, un, vn, trial);
      decreased = across(trial.s - q, axis).squaredNorm() < g;
    }
    if (!decreased) break;  // a minimum to round-off (on the line, or the nearest the box allows)
    const double moved = std::max(std::abs(un - u), std::abs(vn - v));
    u = un;
    v = vn;
    f = trial;
    r = across(f.s - q, axis);
    g = r.squaredNorm();
    if (moved < 1e-13 || std::sqrt(g) <= 1e-14 * scale) {
      ++it;
      break;
    }
  }
  FootPoint out;
  out.u = u;
  out.v = v;
  out.point = f.s;
  out.su = f.su;
  out.sv = f.sv;
  out.distance = (q - f.s).norm();
  out.iterations = it;
  // On the line to a nanometre (a thousandth of the haptic loop's resolution); a point of
  // the boundary that stays off the line means the line misses the sheet.
  out.converged = std::sqrt(g) <= 1e-9;
  return out;
}

Contact column_contact(const mat::MatBody& body, const FootPoint& foot, const Vec3& q, const Vec3& up) {
  Contact c = contact_at_foot(body, foot);
  double unit[3];
  mat::skeleton_normal(body.skeleton(), foot.u, foot.v, unit);
  const Vec3 n(unit[0], unit[1], unit[2]);
  c.side = 1;
  const double below = std::max(0.0, -(q - foot.point).dot(n));  // >= 0 under the skeleton
  const double depth = c.radius + below;
  const double thickness = 2.0 * c.radius;
  c.depth = std::min(depth, thickness);
  c.support_depth = std::max(0.0, depth - thickness);
  c.inside = true;
  // The way out turns from the skeleton's normal (at the skeleton, where the paper's reading
  // hands over) to the support's (at the bottom contour and in the support): tissue pressed
  // against the chest wall pushes back along the wall's normal, not along a normal of the
  // sheet that turns by a tenth of a radian per millimetre under a tight apex.
  const double t = c.radius > 0.0 ? std::clamp(below / c.radius, 0.0, 1.0) : 1.0;
  const Vec3 blend = (1.0 - t) * n + t * up;
  c.outward = blend.norm() > 0.0 ? Vec3(blend.normalized()) : n;
  return c;
}

}  // namespace palpa::contact
