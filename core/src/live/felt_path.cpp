// The finger's path between two frames, felt every millimetre (felt_path.hpp).
#include "palpa/live/felt_path.hpp"

#include <algorithm>
#include <cmath>

#include "palpa/live/press_control.hpp"

namespace palpa::live {

namespace {

FeltPoint feel_at(const scene::Scene& scene, scene::ProbeState& state, const scene::ProbeOptions& options,
                  const ContactEnd& at) {
  FeltPoint p{at.t, at.finger, 0.0, 0.0, at.finger, Vec3::UnitZ()};
  if (at.body < 0 || static_cast<std::size_t>(at.body) >= scene.size() || !(at.depth > 0.0)) return p;
  const auto body = static_cast<std::size_t>(at.body);
  const auto column = surface_frame(scene.body(body).body, at.u, at.v);
  p.thickness = column.thickness;
  p.skin = column.top;
  p.normal = column.normal;
  p.firmness = apparent_firmness(scene, state, options, body, at.u, at.v, at.depth);
  return p;
}

bool one_stretch(const ContactEnd& a, const ContactEnd& b) {
  return a.body >= 0 && a.body == b.body && a.depth > 0.0 && b.depth > 0.0 && b.t > a.t &&
         std::abs(b.u - a.u) <= 0.5 && std::abs(b.v - a.v) <= 0.5 && a.finger.allFinite() && b.finger.allFinite();
}

}  // namespace

void felt_between(const scene::Scene& scene, scene::ProbeState& state, const scene::ProbeOptions& options,
                  const ContactEnd& from, const ContactEnd& to, std::vector<FeltPoint>& out) {
  out.clear();
  if (!one_stretch(from, to)) {
    out.push_back(feel_at(scene, state, options, to));
    return;
  }
  const double travel = (to.finger - from.finger).norm();
  const int n = static_cast<int>(std::clamp(std::ceil(travel / kFeltStep), 1.0, static_cast<double>(kFeltMost)));
  for (int k = 1; k <= n; ++k) {
    if (k == n) {  // the snapshot itself, exactly as taken
      out.push_back(feel_at(scene, state, options, to));
      break;
    }
    const double s = static_cast<double>(k) / n;
    ContactEnd at = to;
    at.t = from.t + s * (to.t - from.t);
    at.finger = from.finger + s * (to.finger - from.finger);
    at.u = from.u + s * (to.u - from.u);
    at.v = from.v + s * (to.v - from.v);
    at.depth = from.depth + s * (to.depth - from.depth);
    out.push_back(feel_at(scene, state, options, at));
  }
}

}  // namespace palpa::live
