#pragma once
// Inside test and penetration (paper section 3.1): a probe Q with foot point P = SK(u, v)
// is inside the body when |PQ| <= R(u, v); its penetration depth is R(u, v) - |PQ|.
#include <limits>

#include "palpa/contact/foot_point.hpp"
#include "palpa/mat/mat_body.hpp"

namespace palpa::contact {

struct Contact {
  FootPoint foot;
  double depth = -std::numeric_limits<double>::infinity();  ///< m: R - |PQ|, negative outside
  bool inside = false;                                       ///< depth >= 0
  double radius = 0.0;     ///< R(u, v), m (a dip below 0 next to the boundary reads as 0)
  double stiffness = 0.0;  ///< k(u, v), N/m (clamped at 0)
  /// Unit direction from the foot point towards the probe, (Q - P)/|Q - P|: the way out of
  /// the body. The foot point's round-off along free tangents is removed first, so at an
  /// interior foot point it is exactly +-N (docs/model.md, section 2). On the skeleton
  /// itself (|PQ| at round-off) it is the skeleton normal N (top side).
  Vec3 outward = Vec3::UnitZ();
  /// +1 when the probe is on the top (+N) side of the skeleton, -1 on the bottom side.
  int side = 1;
  /// m: for a body on a support (top_side_contact), how far the press reaches past the
  /// bottom contour into the support; depth is then the whole thickness 2R. 0 otherwise.
  double support_depth = 0.0;
};

/// The foot point with R and k read at it (a dip below 0 read as 0); the rest at its defaults.
Contact contact_at_foot(const mat::MatBody& body, const FootPoint& foot);

/// Evaluates radius, stiffness and the outward direction at a foot point.
Contact make_contact(const mat::MatBody& body, const FootPoint& foot, const Vec3& q);

/// The same contact read as a press on the top contour, for a body whose bottom rests on a
/// rigid support (docs/model.md, "Bodies on a support"). With s the probe's height over the
/// skeleton along its unit normal N, a probe on the top side (s >= 0) is unchanged; one
/// below the skeleton is measured from the top: depth = R - |PQ| + 2|s| (R - s at an
/// interior foot point, so the depth runs continuously from 0 at the top contour to the
/// thickness 2R at the bottom contour and on into the support), the outward direction is
/// mirrored onto the top side (+N at an interior foot point) and side is +1. A press past
/// the thickness 2R is in the support: depth stays 2R and the rest is support_depth.
/// Whatever path brought the probe there, the same position gives the same contact.
Contact top_side_contact(const Contact& c, const Vec3& q);

}  // namespace palpa::contact
