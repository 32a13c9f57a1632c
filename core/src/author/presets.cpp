#include "palpa/author/presets.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "palpa/mat/layer_stiffness.hpp"

namespace palpa::author {
namespace {

// Stiffness of tissue under a fingertip, modelled as a flat punch of radius a = 7.5 mm on
// an incompressible half-space: k = 2 a E / (1 - nu^2) = 0.02 m * E
// (Sneddon 1965; the moduli and their sources: docs/case-authoring.md, "Where the presets' stiffness values come from").
constexpr double kPunch = 0.02;  // m

// Breast: 300 N/m at the glandular centre (about 15 kPa, between Samani's 3 kPa fat and
// Krouskop's 28 kPa glandular tissue), as data/cases/default.json; the fatty periphery
// keeps default.json's ratio 120/300.
constexpr double kBreastCentre = 300.0;
constexpr double kBreastPeripheryRatio = 0.4;
// Prostate: Gerling 2010's normal gland, 21 kPa (up to 82 kPa): 420 N/m (1640 N/m).
constexpr double kProstate = kPunch * 21e3;
// Prostate pressure bands, shares of the gland's thickness (preset_scoring).
constexpr double kProstateLightMax = 0.10;
constexpr double kProstateDeepMin = 0.20;
// Skin/abdomen patch: subcutaneous fat at small strain, 3 kPa (Samani 2007): 60 N/m.
constexpr double kPatch = kPunch * 3e3;
// Generic slab: the 7 kPa silicone of the phantom pair in use: 140 N/m.
constexpr double kSlab = kPunch * 7e3;
// Moduli for presets in kPa (preset_defaults_in_kpa). Breast fat and fibroglandular
// tissue are about equally stiff at small strain, 3.25 and 3.24 kPa (Samani 2007), so the
// breast in kPa is uniform: its stiffness still grows where it is thin (the layer over the
// chest wall). Skin patch: subcutaneous fat. Prostate: Gerling's normal gland. Slab: the
// phantom's silicone.
constexpr double kFatModulus = 3.25e3;       // Pa
constexpr double kProstateModulus = 21e3;    // Pa
constexpr double kSiliconeModulus = 7e3;     // Pa
// Abdomen curvature: the patch's skeleton is a cylinder of this radius across its width.
constexpr double kAbdomenRadius = 0.2;  // m

// k-th of n evenly spaced values on [-1, 1], exactly +-1 at the ends.
double unit(int n, int k) { return (2.0 * k - (n - 1)) / (n - 1); }

// 1 at the centre, exactly 0 on the boundary of [-1, 1]^2.
double bump(double s, double t) { return (1.0 - s * s) * (1.0 - t * t); }

// A flat top with rounded edges: 1 - s^6 is flat over most of [-1, 1] and falls to 0 at
// the ends over a few grid points, so the spline through it does not overshoot.
double edge(double s) { return 1.0 - std::pow(s, 6); }

void check(const char* name, double value, const double range[2]) {
  if (!(value >= range[0] && value <= range[1])) {
    throw std::invalid_argument(fmt::format("{} {:f} is outside [{:f}, {:f}]", name, value, range[0], range[1]));
  }
}

void check_grid(const char* name, int value, const int range[2]) {
  if (value < range[0] || value > range[1]) {
    throw std::invalid_argument(fmt::format("{} {} is outside [{}, {}]", name, value, range[0], range[1]));
  }
}

}  // namespace

const char* to_string(Preset preset) {
  switch (preset) {
    case Preset::Breast: return "breast";
    case Preset::Prostate: return "prostate";
    case Preset::Patch: return "patch";
    case Preset::Slab: return "slab";
  }
  return "breast";
}

const char* label(Preset preset) {
  switch (preset) {
    case Preset::Breast: return "Breast";
    case Preset::Prostate: return "Prostate";
    case Preset::Patch: return "Skin/abdomen patch";
    case Preset::Slab: return "Generic slab";
  }
  return "Breast";
}

std::optional<Preset> preset_from_string(std::string_view name) {
  for (Preset p : {Preset::Breast, Preset::Prostate, Preset::Patch, Preset::Slab}) {
    if (name == to_string(p)) return p;
  }
  return std::nullopt;
}

PresetParams preset_defaults(Preset preset) {
  switch (preset) {
    case Preset::Breast: return {preset, 0.14, 0.16, 0.05, kBreastCentre, 9, 11};  // as default.json
    case Preset::Prostate: return {preset, 0.04, 0.035, 0.03, kProstate, 9, 9};    // ~4 x 3.5 x 3 cm
    case Preset::Patch: return {preset, 0.20, 0.20, 0.03, kPatch, 11, 11};
    case Preset::Slab: return {preset, 0.12, 0.12, 0.03, kSlab, 11, 11};
  }
  return {};
}

PresetParams preset_defaults_in_kpa(Preset preset) {
  PresetParams p = preset_defaults(preset);
  switch (preset) {
    case Preset::Breast: p.modulus = kFatModulus; break;
    case Preset::Prostate: p.modulus = kProstateModulus; break;
    case Preset::Patch: p.modulus = kFatModulus; break;
    case Preset::Slab: p.modulus = kSiliconeModulus; break;
  }
  return p;
}

PresetLimits preset_limits(Preset preset) {
  switch (preset) {
    // A taller or narrower dome's top contour bulges beyond its base by more than 2 %.
    // Moduli: 1 kPa (the softest fat) to 50 kPa (Krouskop 1998's glandular tissue
    // pre-compressed 20 %).
    case Preset::Breast: return {{0.10, 0.20}, {0.10, 0.22}, {0.02, 0.06}, {60.0, 2000.0}, {1e3, 50e3}, {5, 33}};
    // 21-82 kPa gland (Gerling 2010) and a little either side.
    case Preset::Prostate:
      return {{0.03, 0.06}, {0.025, 0.05}, {0.02, 0.045}, {400.0, 1700.0}, {15e3, 100e3}, {5, 33}};
    case Preset::Patch: return {{0.10, 0.30}, {0.10, 0.30}, {0.01, 0.05}, {20.0, 600.0}, {1e3, 30e3}, {5, 33}};
    // From soft gels to the 180 kPa inclusion silicone of the phantom pair in use.
    case Preset::Slab: return {{0.04, 0.30}, {0.04, 0.30}, {0.01, 0.08}, {20.0, 5000.0}, {1e3, 250e3}, {5, 33}};
  }
  return {};
}

mat::BodyGrid make_preset_body(const PresetParams& in) {
  const PresetParams defaults = preset_defaults(in.preset);
  const PresetLimits limits = preset_limits(in.preset);
  PresetParams p = in;
  if (p.rows == 0) p.rows = defaults.rows;
  if (p.cols == 0) p.cols = defaults.cols;
  check("width", p.width, limits.width);
  check("length", p.length, limits.length);
  check("thickness", p.thickness, limits.thickness);
  if (p.modulus > 0.0) {
    check("modulus", p.modulus, limits.modulus);
    const double stiffening[2] = {0.0, io::CaseLimits::kMaxStiffening};
    check("stiffening", p.stiffening, stiffening);
  } else {
    check("stiffness", p.stiffness, limits.stiffness);
  }
  check_grid("rows", p.rows, limits.grid);
  check_grid("cols", p.cols, limits.grid);

  mat::BodyGrid g;
  g.id = to_string(p.preset);
  // Every preset rests on something rigid: the chest wall, the pelvis, the body under a
  // skin patch, the table under a phantom slab. Only the top can be touched.
  g.support = mat::Support::Bottom;
  g.rows = p.rows;
  g.cols = p.cols;
  const double half_t = p.thickness / 2;
  for (int i = 0; i < p.rows; ++i) {
    for (int j = 0; j < p.cols; ++j) {
      const double s = unit(p.rows, i), t = unit(p.cols, j);
      const double x = s * p.width / 2, y = t * p.length / 2;
      const bool boundary = i == 0 || j == 0 || i == p.rows - 1 || j == p.cols - 1;
      double z = 0.0, profile = 0.0, k = p.stiffness;
      switch (p.preset) {
        case Preset::Breast:
          // As data/cases/make_cases.py: the skeleton is the mid-surface of a dome on the
          // chest wall (z = 0): z = T/2 f and radius T/2 f, so the bottom contour stays near
          // z = 0 and the top rises to T at the apex.
          profile = bump(s, t);
          z = half_t * profile;
          k = p.stiffness * (kBreastPeripheryRatio + (1.0 - kBreastPeripheryRatio) * profile);
          break;
        case Preset::Prostate:
          // An ellipsoid-like gland: flat skeleton at mid-height, radius sqrt of the bump
          // (an ellipse's half-height profile falls steeply at the rim).
          profile = std::sqrt(bump(s, t));
          z = half_t;
          break;
        case Preset::Patch:
          // A wide, thin patch on a gently curved abdomen (a cylinder across the width).
          profile = edge(s) * edge(t);
          z = half_t - x * x / (2.0 * kAbdomenRadius);
          break;
        case Preset::Slab:
          profile = edge(s) * edge(t);
          z = half_t;
          break;
      }
      g.medial.push_back({x, y, z});
      g.radius.push_back(boundary ? 0.0 : half_t * profile);
      g.stiffness.push_back(k);
    }
  }
  if (p.modulus > 0.0) {
    g.modulus.assign(g.radius.size(), p.modulus);
    g.stiffness = mat::layer_stiffness_field(g.modulus, g.radius, g.poisson);
    g.force_model = mat::ForceModel::Calibrated;
    g.stiffening = p.stiffening;
  }
  return g;
}

nlohmann::json preset_scoring(Preset preset) {
  if (preset != Preset::Prostate) return nlohmann::json::object();
  // A digital rectal exam presses the gland a few millimetres through the rectal wall;
  // nodules 5 mm deep are what it must find (Gerling 2010). Of a 30 mm gland: light below
  // 3 mm, deep from 6 mm. The default bands (20 % / 50 %, from breast exams) would ask for
  // a 15 mm press of a gland several times stiffer than breast tissue.
  return {{"light_max", kProstateLightMax}, {"deep_min", kProstateDeepMin}};
}

io::CaseFile make_modulus_slab(double width, double thickness, double modulus, mat::ForceModel model) {
  PresetParams p = preset_defaults(Preset::Slab);
  p.width = p.length = width;
  p.thickness = thickness;
  p.rows = p.cols = 13;
  io::CaseFile file;
  file.title = fmt::format("slab of {:f} kPa", modulus / 1000.0);
  file.bodies.push_back(make_preset_body(p));
  nlohmann::json doc = io::to_json(file);
  auto& body = doc["bodies"][0];
  body.erase("stiffness");
  body["modulus"] = std::vector<double>(body["radius"].size(), modulus);
  body["force_model"] = mat::to_string(model);
  return io::parse_case(doc.dump(), "slab in Pa");  // derives the stiffness from the modulus
}

io::CaseFile make_preset_case(const PresetParams& params, const std::string& title) {
  io::CaseFile file;
  file.title = title;
  file.bodies.push_back(make_preset_body(params));
  PresetParams stored = params;
  stored.rows = file.bodies.front().rows;
  stored.cols = file.bodies.front().cols;
  file.document = nlohmann::json::object();
  file.document["preset"] = to_json(stored);
  if (auto scoring = preset_scoring(params.preset); !scoring.empty()) file.document["scoring"] = std::move(scoring);
  file.document = io::to_json(file);
  return file;
}

nlohmann::json to_json(const PresetParams& p) {
  nlohmann::json out = {{"name", to_string(p.preset)}, {"width", p.width},         {"length", p.length},
                        {"thickness", p.thickness},    {"stiffness", p.stiffness}, {"rows", p.rows},
                        {"cols", p.cols}};
  if (p.modulus > 0.0) out["modulus"] = p.modulus;
  if (p.modulus > 0.0 && p.stiffening > 0.0) out["stiffening"] = p.stiffening;
  return out;
}

std::optional<PresetParams> preset_from_json(const nlohmann::json& v) {
  if (!v.is_object() || !v.contains("name") || !v["name"].is_string()) return std::nullopt;
  const auto preset = preset_from_string(v["name"].get<std::string>());
  if (!preset) return std::nullopt;
  PresetParams p = preset_defaults(*preset);
  for (auto [key, field] : {std::pair{"width", &p.width}, std::pair{"length", &p.length},
                            std::pair{"thickness", &p.thickness}, std::pair{"stiffness", &p.stiffness}}) {
    if (!v.contains(key) || !v[key].is_number()) return std::nullopt;
    *field = v[key].get<double>();
  }
  for (auto [key, field] : {std::pair{"rows", &p.rows}, std::pair{"cols", &p.cols}}) {
    if (!v.contains(key) || !v[key].is_number_integer()) return std::nullopt;
    *field = v[key].get<int>();
  }
  if (v.contains("modulus")) {
    if (!v["modulus"].is_number() || !(v["modulus"].get<double>() > 0.0)) return std::nullopt;
    p.modulus = v["modulus"].get<double>();
  }
  if (v.contains("stiffening")) {
    if (!v["stiffening"].is_number() || !(v["stiffening"].get<double>() >= 0.0)) return std::nullopt;
    p.stiffening = v["stiffening"].get<double>();
  }
  return p;
}

}  // namespace palpa::author
