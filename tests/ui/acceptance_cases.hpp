#pragma once
// The cases the acceptance exams run besides the bundled files: the instructor's presets
// with a tumour (long form), the default breast with two tumours, and without one.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "palpa/author/presets.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/render/surface_pick.hpp"
#include "palpa/scene/scene.hpp"

namespace acceptance_cases {

using palpa::Vec3;
inline const std::string kCases = PALPA_SOURCE_DIR "/data/cases/";

/// The skin (the top contour's point) over plan position (x, y) of a case's scene.
inline palpa::render::SurfacePick skin_at(const palpa::scene::Scene& scene, double x, double y) {
  const auto skin = palpa::render::TopContourPicker(scene).pick(Vec3(x, y, 1.0), Vec3(0, 0, -1));
  if (!skin) throw std::invalid_argument("no skin at the tumour's plan position");
  return *skin;
}

/// A tumour of `radius` whose centre is the skeleton point (mid-depth) under the skin at
/// plan position (x, y): the foot point of the skin's point there.
inline palpa::mat::Tumour tumour_under(const palpa::io::CaseFile& file, double x, double y, double radius, double stiffness) {
  const auto scene = palpa::scene::Scene::build(file, "case");
  const auto& sb = scene.body(0);
  const auto foot = sb.search.closest(sb.body.skeleton(), skin_at(scene, x, y).point);
  return {sb.body.id(), {foot.point.x(), foot.point.y(), foot.point.z()}, radius, stiffness};
}

/// A tumour of `radius` whose centre is `depth` under the skin at plan position (x, y),
/// along the skin's inward normal.
inline palpa::mat::Tumour tumour_below_skin(const palpa::io::CaseFile& file, double x, double y, double depth, double radius,
                                     double stiffness) {
  const auto scene = palpa::scene::Scene::build(file, "case");
  const auto skin = skin_at(scene, x, y);
  const Vec3 c = skin.point - depth * skin.normal;
  return {scene.body(0).body.id(), {c.x(), c.y(), c.z()}, radius, stiffness};
}

/// The long form's cases: every instructor preset with a tumour at mid-depth.
inline std::vector<std::pair<std::string, palpa::io::CaseFile>> preset_cases() {
  std::vector<std::pair<std::string, palpa::io::CaseFile>> cases;
  using palpa::author::Preset;
  for (const Preset p : {Preset::Breast, Preset::Prostate, Preset::Patch, Preset::Slab}) {
    const auto params = palpa::author::preset_defaults(p);
    // As the instructor window makes it (tissue in N/m, as a new window starts): the
    // preset's body and its organ's scoring.
    auto file = palpa::author::make_preset_case(params, std::string("preset ") + palpa::author::to_string(p));
    // Off-centre, a third of the way out; the radius a fifth of the thickness (a 4-10 mm
    // nodule), five times the tissue's stiffness (carcinoma-like: docs/case-format.md).
    const double radius = std::clamp(0.2 * params.thickness, 0.003, 0.008);
    const double x = 0.15 * params.width, y = -0.15 * params.length;
    // The prostate's nodule where a rectal exam looks for it: a 6 mm nodule 5 mm under the
    // surface (Gerling 2010 found nodules of 4 mm and more at 5 mm depth in 21 kPa tissue).
    file.tumours.push_back(p == Preset::Prostate ? tumour_below_skin(file, x, y, 0.005 + 0.003, 0.003, 5.0 * params.stiffness)
                                                 : tumour_under(file, x, y, radius, 5.0 * params.stiffness));
    file.document = palpa::io::to_json(file);
    cases.emplace_back(file.title, palpa::io::parse_case(file.document.dump(), file.title));
  }
  return cases;
}

/// The default breast with two fixed tumours, one on each side.
inline palpa::io::CaseFile two_tumour_case() {
  auto two = palpa::io::load_case(kCases + "default.json");
  // The default case's carcinoma (19.4 kPa, stiffening 11.1, 14 mm) on each side.
  const auto carcinoma = two.tumours.front();
  two.tumours.clear();
  for (const auto& [x, y] : {std::pair{0.025, 0.02}, std::pair{-0.025, -0.03}}) {
    auto t = tumour_under(two, x, y, carcinoma.radius, carcinoma.stiffness);
    t.modulus = carcinoma.modulus;
    t.stiffening = carcinoma.stiffening;
    two.tumours.push_back(t);
  }
  two.document.erase("tumors");
  two.document = palpa::io::to_json(two);
  return palpa::io::parse_case(two.document.dump(), "two tumours");
}

/// The default breast without its tumour: "Is there a tumour?"
inline palpa::io::CaseFile no_tumour_case() {
  auto none = palpa::io::load_case(kCases + "default.json");
  none.tumours.clear();
  none.document.erase("tumors");
  none.document = palpa::io::to_json(none);
  return palpa::io::parse_case(none.document.dump(), "no tumour");
}

}  // namespace acceptance_cases
