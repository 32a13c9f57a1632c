#include "palpa/contact/contact.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <limits>

namespace palpa::contact {

Contact make_contact(const mat::MatBody& body, const FootPoint& foot, const Vec3& q) {
  Contact c;
  c.foot = foot;
  std::array<double, mat::kSkeletonChannels> sk;
  body.skeleton().evaluate(foot.u, foot.v, sk);
  // A fit may dip a little below 0 beside a kink or at the closed boundary: read it as 0.
  c.radius = std::max(0.0, sk[mat::kRadius]);
  c.stiffness = std::max(0.0, sk[mat::kStiffness]);
  const Vec3 n = foot.su.cross(foot.sv);
  const Vec3 d = q - foot.point;
  const double len = d.norm();
  // Within round-off of the skeleton the direction of Q - P is noise: use the normal.
  const double on_skeleton = 64.0 * std::numeric_limits<double>::epsilon() * std::max(q.norm(), foot.point.norm());
  if (len > on_skeleton) {
    c.outward = d / len;
    c.side = d.dot(n) >= 0.0 ? 1 : -1;
  } else {
    const double nn = n.norm();
    c.outward = nn > 0.0 ? Vec3(n / nn) : Vec3::UnitZ();
    c.side = 1;
  }
  c.depth = c.radius - len;
  c.inside = c.depth >= 0.0;
  return c;
}

}  // namespace palpa::contact
