#include "palpa/scene/scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace palpa::scene {

Bounds probe_box_of(const mat::MatBody& body, const Bounds& bounds) {
  if (!body.anchored()) return bounds;
  // A support's wall goes on below the bottom contour: the box takes it in, whichever way
  // the body faces.
  Bounds b = bounds;
  b.lo.array() -= kSupportReach;
  b.hi.array() += kSupportReach;
  return b;
}

bool Bounds::contains(const Vec3& q) const {
  return (q.array() >= lo.array()).all() && (q.array() <= hi.array()).all();
}

Bounds bounds_of(const mat::MatBody& body) {
  const auto& sk = body.skeleton();
  Bounds b;
  b.lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  b.hi = -b.lo;
  double r = 0.0;
  for (int i = 0; i < sk.rows(); ++i) {
    for (int j = 0; j < sk.cols(); ++j) {
      const auto cp = sk.control_point(i, j);
      const Vec3 p(cp[mat::kX], cp[mat::kY], cp[mat::kZ]);
      b.lo = b.lo.cwiseMin(p);
      b.hi = b.hi.cwiseMax(p);
      r = std::max(r, cp[mat::kRadius]);
    }
  }
  // Every point within R(u,v) of SK lies in the hull of the control points grown by the
  // largest radius control value (both by the convex hull property of B-splines).
  b.lo.array() -= r;
  b.hi.array() += r;
  return b;
}

double tumour_clearance(const mat::MatBody& body, const contact::FootPointSearch& search, const mat::Tumour& tumour) {
  const Vec3 c(tumour.center[0], tumour.center[1], tumour.center[2]);
  double worst = contact::make_contact(body, search.closest(body.skeleton(), c), c).depth;
  if (worst < 0.0) return worst;
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dz = -1; dz <= 1; ++dz) {
        if (dx == 0 && dy == 0 && dz == 0) continue;
        const Vec3 x = c + tumour.radius * Vec3(dx, dy, dz).normalized();
        worst = std::min(worst, contact::make_contact(body, search.closest(body.skeleton(), x), x).depth);
      }
    }
  }
  return worst;
}

namespace {

// Pa: the tissue's modulus at the skeleton point nearest to `centre` (0 for a body in N/m).
double modulus_around(const mat::BodyGrid& grid, const std::array<double, 3>& centre) {
  if (grid.modulus.empty()) return 0.0;
  std::size_t nearest = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < grid.medial.size(); ++k) {
    const auto& m = grid.medial[k];
    const double d = std::hypot(m[0] - centre[0], m[1] - centre[1], m[2] - centre[2]);
    if (d < best) {
      best = d;
      nearest = k;
    }
  }
  return grid.modulus[nearest];
}

}  // namespace

Scene Scene::build(const io::CaseFile& file, const std::string& source, const mat::FitOptions& options) {
  Scene scene;
  scene.indenter_ = file.indenter;
  scene.bodies_.reserve(file.bodies.size());
  std::vector<io::Problem> problems;
  for (std::size_t k = 0; k < file.bodies.size(); ++k) {
    try {
      auto body = mat::MatBody::fit(file.bodies[k], options);
      contact::FootPointSearch search(body.skeleton());
      const auto bounds = bounds_of(body);
      const auto probe_box = probe_box_of(body, bounds);
      const auto& grid = file.bodies[k];
      std::optional<mat::LayerStiffnessTable> layer;
      if (!grid.modulus.empty()) layer.emplace(grid.poisson, mat::kFingertipPadRadius);
      // A body on a support reads presses under its skeleton along its column.
      const auto axis = body.anchored() ? contact::press_axis_of(body.skeleton()) : contact::PressAxis{};
      scene.bodies_.push_back(
          {std::move(body), std::move(search), bounds, probe_box, {}, grid.force_model, layer, grid.poisson,
           grid.stiffening, axis});
    } catch (const mat::FitError& e) {
      problems.push_back({fmt::format("/bodies/{}", k), std::string("cannot fit: ") + e.what()});
    }
  }
  if (!problems.empty()) throw io::CaseError(source, std::move(problems));

  for (std::size_t k = 0; k < file.tumours.size(); ++k) {
    const auto& t = file.tumours[k];
    const auto it = std::find_if(scene.bodies_.begin(), scene.bodies_.end(),
                                 [&](const SceneBody& b) { return b.body.id() == t.body; });
    if (it == scene.bodies_.end()) {
      problems.push_back({fmt::format("/tumors/{}/body", k), "unknown body \"" + t.body + "\""});
      continue;
    }
    // The centre's depth alone is not enough where the surface slopes: see tumour_clearance.
    const double worst = tumour_clearance(it->body, it->search, t);
    if (worst < 0.0) {
      const Vec3 c(t.center[0], t.center[1], t.center[2]);
      const bool centre_inside =
          contact::make_contact(it->body, it->search.closest(it->body.skeleton(), c), c).depth >= 0.0;
      problems.push_back({fmt::format("/tumors/{}", k),
                          fmt::format("tumour (radius {:.4g} m) is not inside body \"{}\": {} {:.4g} m {} the surface",
                                      t.radius, t.body, centre_inside ? "it reaches" : "its centre is", -worst,
                                      centre_inside ? "beyond" : "outside")});
      continue;
    }
    mat::Tumour placed = t;
    if (t.modulus > 0.0) {
      const auto& grid = file.bodies[static_cast<std::size_t>(it - scene.bodies_.begin())];
      const double around = modulus_around(grid, t.center);
      if (!(around > 0.0)) {
        problems.push_back({fmt::format("/tumors/{}/modulus", k),
                            "a tumour given by its modulus (Pa) needs its body \"" + t.body +
                                "\" given by \"modulus\" too, with tissue stiffer than 0 Pa around it"});
        continue;
      }
      placed.modulus_ratio = t.modulus / around;
    }
    it->tumours.push_back(placed);
  }
  if (!problems.empty()) throw io::CaseError(source, std::move(problems));
  return scene;
}

namespace {

// A press into a body on a support: the paper's reading over the skeleton, the column's
// under it (docs/model.md, "Under the skeleton: the column"); the mirrored reading where
// the column misses the sheet (beyond the rim) or the body is too steep for one.
contact::Contact supported_contact(const SceneBody& sb, const contact::Contact& nearest, const Vec3& q) {
  const bool interior = nearest.foot.u > 0.0 && nearest.foot.u < 1.0 && nearest.foot.v > 0.0 && nearest.foot.v < 1.0;
  // Over an interior foot point of a graph the probe is above the sheet: nothing to do.
  if (!sb.press_axis.usable || (interior && nearest.side > 0)) return contact::top_side_contact(nearest, q);
  const auto column = contact::column_foot_point(sb.body.skeleton(), sb.press_axis.up, q, nearest.foot.u,
                                                 nearest.foot.v);
  if (!column.converged || (q - column.point).dot(sb.press_axis.up) >= 0.0) return contact::top_side_contact(nearest, q);
  return contact::column_contact(sb.body, column, q, sb.press_axis.up);
}

}  // namespace

ProbeState Scene::make_state() const {
  ProbeState s;
  s.u.assign(bodies_.size(), 0.0);
  s.v.assign(bodies_.size(), 0.0);
  s.warm.assign(bodies_.size(), 0);
  s.entry_side.assign(bodies_.size(), 0);
  s.held = -1;
  return s;
}

ProbeResult Scene::probe(const Vec3& q, ProbeState& state, const ProbeOptions& options) const {
  ProbeResult result;
  double best_depth = -std::numeric_limits<double>::infinity();
  bool held_chosen = false;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const SceneBody& sb = bodies_[b];
    if (!sb.probe_box.contains(q)) {
      state.warm[b] = 0;  // the next entry into this body starts cold
      state.entry_side[b] = 0;
      continue;
    }
    ++result.bodies_tested;
    const auto& sk = sb.body.skeleton();
    contact::FootPoint foot;
    if (options.method == FootPointMethod::Bisect) {
      foot = contact::bisect_foot_point(sk, q, options.bisect_levels);
    } else if (state.warm[b] != 0) {
      foot = sb.search.closest_from(sk, q, state.u[b], state.v[b]);
    } else {
      foot = sb.search.closest(sk, q);
    }
    state.u[b] = foot.u;
    state.v[b] = foot.v;
    state.warm[b] = 1;
    auto c = contact::make_contact(sb.body, foot, q);
    if (sb.body.anchored()) {
      c = supported_contact(sb, c, q);  // only the top is touchable: no side to remember
    } else if (options.remember_side) {
      if (!c.inside) {
        state.entry_side[b] = 0;
      } else if (state.entry_side[b] == 0) {
        state.entry_side[b] = static_cast<signed char>(c.side);
      } else if (state.entry_side[b] != c.side) {
        // Past the skeleton: measure the press from the surface it entered through.
        c.depth = c.radius + c.foot.distance;
        c.outward = -c.outward;
        c.side = state.entry_side[b];
      }
    }
    // The proxy keeps the body it touched while the probe is still inside it.
    const bool held = options.remember_side && state.held == static_cast<int>(b) && c.inside;
    if (held || (c.depth > best_depth && !held_chosen)) {
      best_depth = c.depth;
      result.nearest = static_cast<int>(b);
      result.contact = c;
      held_chosen = held_chosen || held;
    }
  }
  if (result.nearest >= 0 && result.contact.inside) result.body = result.nearest;
  state.held = result.body;
  if (result.body >= 0) {
    const SceneBody& sb = bodies_[static_cast<std::size_t>(result.body)];
    if (sb.force_model == mat::ForceModel::Calibrated) {
      contact::ForceOptions calibrated = options.force;  // a few dozen bytes on the stack
      calibrated.shear = false;
      calibrated.stiffening = sb.stiffening;
      if (indenter_ == mat::Indenter::Finger && sb.layer) {
        // The tissue's modulus back from the stiffness the pad would feel here.
        const double per_pascal = (*sb.layer)(1.0, 2.0 * result.contact.radius);
        calibrated.finger.on = per_pascal > 0.0;
        calibrated.finger.modulus = calibrated.finger.on ? result.contact.stiffness / per_pascal : 0.0;
        calibrated.finger.poisson = sb.poisson;
      }
      result.force = contact::contact_force(sb.body, result.contact, q, sb.tumours, calibrated);
    } else {
      result.force = contact::contact_force(sb.body, result.contact, q, sb.tumours, options.force);
    }
  }
  return result;
}

}  // namespace palpa::scene
