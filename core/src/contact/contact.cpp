#include "palpa/contact/contact.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <limits>

namespace palpa::contact {

Contact contact_at_foot(const mat::MatBody& body, const FootPoint& foot) {
  Contact c;
  c.foot = foot;
  std::array<double, mat::kSkeletonChannels> sk;
  body.skeleton().evaluate(foot.u, foot.v, sk);
  // A fit may dip a little below 0 beside a kink or at the closed boundary: read it as 0.
  c.radius = std::max(0.0, sk[mat::kRadius]);
  c.stiffness = std::max(0.0, sk[mat::kStiffness]);
  return c;
}

Contact make_contact(const mat::MatBody& body, const FootPoint& foot, const Vec3& q) {
  Contact c = contact_at_foot(body, foot);
  const Vec3 n = foot.su.cross(foot.sv);
  const Vec3 d = q - foot.point;
  const double len = d.norm();
  // At a foot point Q - P is orthogonal to every free direction of the skeleton (a
  // parameter strictly inside (0, 1)), so any part of it along one is round-off of the
  // foot-point search (Newton stops within 1e-13 in u, v: about 1e-15 m). It does not
  // matter far from the skeleton, but a probe pressed onto the skeleton itself is only
  // femtometres from P and there (Q - P) / |Q - P| would point wherever the round-off
  // does: sideways, flinging the normal spring, the shear springs' rest point and the
  // tumours' columns about by tens of newtons between ticks at a probe held still. So
  // the direction is taken from Q - P with those parts removed: +-N inside the grid, and
  // in the plane of N and the outward edge direction where a parameter sits on the
  // boundary (the rim), where that part is the real geometry.
  Vec3 w = d;
  const auto drop = [&w](const Vec3& tangent) {
    const double tt = tangent.squaredNorm();
    if (tt > 0.0) w -= (w.dot(tangent) / tt) * tangent;
  };
  const bool free_u = foot.u > 0.0 && foot.u < 1.0;
  const bool free_v = foot.v > 0.0 && foot.v < 1.0;
  const double nn = n.norm();
  if (free_u && free_v && nn > 0.0) {
    w = (d.dot(n) / (nn * nn)) * n;  // both tangents at once: exact even where Su, Sv are skewed
  } else {
    if (free_u) drop(foot.su);
    if (free_v) drop(foot.sv);
  }
  const double wlen = w.norm();
  // Within round-off of the skeleton the direction of Q - P is noise: use the normal.
  const double on_skeleton = 64.0 * std::numeric_limits<double>::epsilon() * std::max(q.norm(), foot.point.norm());
  if (wlen > on_skeleton) {
    c.outward = w / wlen;
    c.side = w.dot(n) >= 0.0 ? 1 : -1;
  } else {
    c.outward = nn > 0.0 ? Vec3(n / nn) : Vec3::UnitZ();
    c.side = 1;
  }
  c.depth = c.radius - len;
  c.inside = c.depth >= 0.0;
  return c;
}

Contact top_side_contact(const Contact& c, const Vec3& q) {
  const Vec3 n = c.foot.su.cross(c.foot.sv);
  const double nn = n.norm();
  if (!(nn > 0.0)) return c;  // no normal (a pole): the radial reading is all there is
  const Vec3 unit_n = n / nn;
  const double len = (q - c.foot.point).norm();
  const double s = len * c.outward.dot(unit_n);  // signed height over the skeleton
  Contact top = c;
  top.side = 1;
  if (s >= 0.0) return top;
  const double depth = c.depth - 2.0 * s;  // R - |PQ| + 2|s|
  const double thickness = 2.0 * c.radius;
  top.depth = std::min(depth, thickness);
  top.support_depth = std::max(0.0, depth - thickness);
  top.inside = depth >= 0.0;
  const Vec3 mirrored = c.outward - 2.0 * c.outward.dot(unit_n) * unit_n;
  top.outward = mirrored.norm() > 0.0 ? Vec3(mirrored.normalized()) : unit_n;
  return top;
}

}  // namespace palpa::contact
