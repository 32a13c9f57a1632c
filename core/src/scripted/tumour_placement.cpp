#include "palpa/scripted/tumour_placement.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "palpa/scene/scene.hpp"
#include "surface_frame.hpp"

namespace palpa::scripted {

std::optional<Placement> placement_of(const io::CaseFile& file, std::size_t index) {
  const auto& doc = file.document;
  if (!doc.is_object() || !doc.contains("tumors") || !doc["tumors"].is_array()) return std::nullopt;
  const auto& tumours = doc["tumors"];
  if (index >= tumours.size() || !tumours[index].is_object() || !tumours[index].contains("placement")) {
    return std::nullopt;
  }
  const auto& p = tumours[index]["placement"];
  Placement out;
  out.u = {p["u"][0].get<double>(), p["u"][1].get<double>()};
  out.v = {p["v"][0].get<double>(), p["v"][1].get<double>()};
  out.depth = {p["depth"][0].get<double>(), p["depth"][1].get<double>()};
  return out;
}

namespace {

bool overlaps(const mat::Tumour& a, const mat::Tumour& b) {
  double d2 = 0.0;
  for (std::size_t c = 0; c < 3; ++c) d2 += (a.center[c] - b.center[c]) * (a.center[c] - b.center[c]);
  const double r = a.radius + b.radius;
  return d2 < r * r;
}

}  // namespace

io::CaseFile place_tumours(const io::CaseFile& file, std::uint64_t seed, const std::string& source,
                           const mat::FitOptions& options) {
  io::CaseFile bodies_only = file;
  bodies_only.tumours.clear();
  const auto scene = scene::Scene::build(bodies_only, source, options);  // throws for a body that cannot be fitted

  io::CaseFile out = file;
  SplitMix64 rng(seed);
  std::vector<io::Problem> problems;
  for (std::size_t k = 0; k < out.tumours.size(); ++k) {
    const auto rule = placement_of(file, k);
    if (!rule) continue;
    mat::Tumour& t = out.tumours[k];
    const std::string where = fmt::format("/tumors/{}/placement", k);
    const scene::SceneBody* body = nullptr;
    for (std::size_t b = 0; b < scene.size(); ++b) {
      if (scene.body(b).body.id() == t.body) body = &scene.body(b);
    }
    if (body == nullptr) {
      problems.push_back({fmt::format("/tumors/{}/body", k), fmt::format("unknown body \"{}\"", t.body)});
      continue;
    }
    bool placed = false;
    for (int draw = 0; draw < kMaxPlacementDraws && !placed; ++draw) {
      // Always three draws per attempt, so one tumour's rejections do not depend on the
      // order of checks below.
      const double u = rng.uniform(rule->u[0], rule->u[1]);
      const double v = rng.uniform(rule->v[0], rule->v[1]);
      const double d = rng.uniform(rule->depth[0], rule->depth[1]);
      const auto f = detail::frame_at(body->body, u, v);
      if (!f.ok) continue;
      const palpa::Vec3 c = f.top - d * 2.0 * f.radius * f.normal;
      t.center = {c.x(), c.y(), c.z()};
      if (scene::tumour_clearance(body->body, body->search, t) < 0.0) continue;
      bool clear = true;
      for (std::size_t j = 0; j < out.tumours.size() && clear; ++j) {
        // Later tumours with a rule are checked against this one when they are drawn.
        if (j != k && (j < k || !placement_of(file, j)) && overlaps(t, out.tumours[j])) clear = false;
      }
      placed = clear;
    }
    if (!placed) {
      problems.push_back({where, fmt::format("no centre inside body \"{}\" and clear of the other tumours in {} draws "
                                             "(seed {}): widen the ranges or shrink the tumour",
                                             t.body, kMaxPlacementDraws, seed)});
    }
  }
  if (!problems.empty()) throw io::CaseError(source, std::move(problems));
  out.document = io::to_json(out);
  return out;
}

}  // namespace palpa::scripted
