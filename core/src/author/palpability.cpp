#include "palpa/author/palpability.hpp"

#include <algorithm>
#include <cmath>

#include "palpa/mat/mat_body.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/scripted/scripted_trainee.hpp"

namespace palpa::author {
namespace {

constexpr int kPressSteps = 64;       // the press goes in along a path (the probe keeps its side)
constexpr double kStartAbove = 0.002;  // m above the skin where the press starts

struct Press {
  Vec3 top = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  double thickness = 0.0;
  bool ok = false;
};

// The skin straight over `centre`: its foot point on the skeleton, the top contour P + R N.
Press press_over(const scene::SceneBody& body, const Vec3& centre) {
  Press p;
  const auto& skeleton = body.body.skeleton();
  const auto foot = body.search.closest(skeleton, centre);
  double s[mat::kRadius + 1];
  skeleton.evaluate(foot.u, foot.v, s, mat::kRadius + 1);
  double n[3];
  if (!mat::skeleton_normal(skeleton, foot.u, foot.v, n)) return p;
  const double radius = std::max(0.0, s[mat::kRadius]);
  p.normal = Vec3(n[0], n[1], n[2]);
  p.top = Vec3(s[mat::kX], s[mat::kY], s[mat::kZ]) + radius * p.normal;
  p.thickness = 2.0 * radius;
  p.ok = radius > 0.0;
  return p;
}

// |F| at the end of a press from above the skin to `depth` below it along -normal.
double press_force(const scene::Scene& scene, const Press& p, double depth) {
  scene::ProbeOptions options;
  options.remember_side = true;
  options.force.max_force = 1e6;  // the contrast, not what a device could render
  auto state = scene.make_state();
  double force = 0.0;
  for (int k = 0; k <= kPressSteps; ++k) {
    const double d = -kStartAbove + (depth + kStartAbove) * k / kPressSteps;
    const auto r = scene.probe(p.top - d * p.normal, state, options);
    force = r.body >= 0 ? r.force.total.norm() : 0.0;
  }
  return force;
}

}  // namespace

double deep_press_share() {
  const auto expert = scripted::parameters_for(scripted::Style::Expert);
  return expert.levels[static_cast<std::size_t>(expert.level_count - 1)];
}

std::vector<TumourPalpability> check_palpability(const io::CaseFile& file, const std::string& source) {
  const auto with = scene::Scene::build(file, source);
  io::CaseFile plain_file = file;
  plain_file.tumours.clear();
  const auto plain = scene::Scene::build(plain_file, source);
  const double share = deep_press_share();
  std::vector<TumourPalpability> out;
  for (std::size_t k = 0; k < file.tumours.size(); ++k) {
    const auto& t = file.tumours[k];
    TumourPalpability r;
    r.tumour = k;
    for (std::size_t b = 0; b < with.size(); ++b) {
      if (with.body(b).body.id() != t.body) continue;
      const Press p = press_over(with.body(b), Vec3(t.center[0], t.center[1], t.center[2]));
      if (!p.ok) break;
      r.thickness = p.thickness;
      r.indentation = share * p.thickness;
      r.force = press_force(with, p, r.indentation);
      r.plain_force = press_force(plain, p, r.indentation);
      r.contrast = r.plain_force > 0.0 ? r.force / r.plain_force : 0.0;
      r.palpable = r.contrast >= kPalpableContrast;
    }
    out.push_back(r);
  }
  return out;
}

}  // namespace palpa::author
