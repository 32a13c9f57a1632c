#include "marks.hpp"

#include <algorithm>
#include <limits>

namespace palpa::score::detail {

Landing land_on_body(const scene::SceneBody& body, int index, const Vec3& q) {
  const contact::FootPoint foot = body.search.closest(body.body.skeleton(), q);
  Landing out;
  out.body = index;
  out.u = foot.u;
  out.v = foot.v;
  out.top = top_point(body.body, foot.u, foot.v).point;
  return out;
}

Landing land_on_scene(const scene::Scene& scene, const Vec3& q, scene::ProbeState& state) {
  const scene::ProbeResult r = scene.probe(q, state);
  if (r.nearest >= 0) {
    Landing out;
    out.body = r.nearest;
    out.u = r.contact.foot.u;
    out.v = r.contact.foot.v;
    out.top = top_point(scene.body(static_cast<std::size_t>(r.nearest)).body, out.u, out.v).point;
    return out;
  }
  // Every body was culled (a mark far off the tissue): the body whose surface is nearest.
  Landing best;
  double best_depth = -std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < scene.size(); ++b) {
    const auto& sb = scene.body(b);
    const contact::FootPoint foot = sb.search.closest(sb.body.skeleton(), q);
    const contact::Contact c = contact::make_contact(sb.body, foot, q);
    if (c.depth > best_depth) {
      best_depth = c.depth;
      best.body = static_cast<int>(b);
      best.u = foot.u;
      best.v = foot.v;
    }
  }
  if (best.body >= 0) best.top = top_point(scene.body(static_cast<std::size_t>(best.body)).body, best.u, best.v).point;
  return best;
}

std::vector<session::Mark> standing(const std::vector<session::Event>& events) {
  std::vector<session::Mark> out;
  for (const auto& e : events) {
    if (e.kind == session::EventKind::Mark) {
      out.push_back({e.mark, e.t, e.position});
    } else if (e.kind == session::EventKind::Unmark) {
      std::erase_if(out, [&](const session::Mark& m) { return m.id == e.mark; });
    }
  }
  return out;
}

int match_marks(const std::vector<Landing>& mark_tops, const std::vector<Landing>& tumour_tops,
                std::vector<MarkResult>& marks, std::vector<TumourResult>& tumours, double hit_margin) {
  struct Pair {
    double distance;
    std::size_t mark, tumour;
  };
  std::vector<Pair> pairs;
  for (std::size_t m = 0; m < marks.size(); ++m) {
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < tumours.size(); ++k) {
      const double d = (mark_tops[m].top - tumour_tops[k].top).norm();
      nearest = std::min(nearest, d);
      if (d <= tumours[k].radius + hit_margin) pairs.push_back({d, m, k});
    }
    marks[m].nearest_mm = tumours.empty() ? 0.0 : 1000.0 * nearest;
  }
  std::stable_sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.distance < b.distance; });
  for (const auto& p : pairs) {
    if (tumours[p.tumour].found || marks[p.mark].tumour >= 0) continue;
    tumours[p.tumour].found = true;
    tumours[p.tumour].mark = marks[p.mark].id;
    tumours[p.tumour].localization_error_mm = 1000.0 * p.distance;
    marks[p.mark].tumour = static_cast<int>(p.tumour);
  }
  // A mark left over that still reaches a tumour marks one already found: a duplicate.
  int false_positives = 0;
  for (std::size_t m = 0; m < marks.size(); ++m) {
    if (marks[m].tumour >= 0) continue;
    marks[m].duplicate = std::any_of(pairs.begin(), pairs.end(), [&](const Pair& p) { return p.mark == m; });
    if (!marks[m].duplicate) ++false_positives;
  }
  return false_positives;
}

}  // namespace palpa::score::detail
