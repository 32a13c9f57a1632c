#pragma once
// Body presets for instructor authoring: a valid case body (docs/case-format.md:
// rows x cols skeleton grid, radius 0 on the grid boundary, smooth fields) built from a
// few parameters in SI units. Each preset's defaults and limits are chosen so that every
// combination within the limits validates and fits (tests/core/author/author_presets_test.cpp).
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "palpa/io/case_file.hpp"
#include "palpa/mat/body_grid.hpp"

namespace palpa::author {

enum class Preset { Breast, Prostate, Patch, Slab };

/// "breast", "prostate", "patch" (skin/abdomen patch), "slab" (generic slab).
const char* to_string(Preset preset);
std::optional<Preset> preset_from_string(std::string_view name);
/// A label for menus: "Breast", "Prostate", "Skin/abdomen patch", "Generic slab".
const char* label(Preset preset);

struct PresetParams {
  Preset preset = Preset::Breast;
  double width = 0.0;      ///< m, extent along x (the grid rows, u)
  double length = 0.0;     ///< m, extent along y (the grid columns, v)
  double thickness = 0.0;  ///< m, tissue thickness 2R at the centre (top to bottom contour)
  double stiffness = 0.0;  ///< N/m per skeleton point (the breast's glandular centre; uniform otherwise)
  int rows = 0;            ///< grid points along u; 0: the preset's default
  int cols = 0;            ///< grid points along v; 0: the preset's default
  /// Pa; > 0: the tissue is given by this Young's modulus, uniform (written as "modulus",
  /// the calibrated force law, the stiffness derived over the local thickness) and
  /// `stiffness` is ignored; 0: by `stiffness` (N/m, the paper's springs).
  double modulus = 0.0;
  /// With a modulus: the tissue's strain stiffening b (docs/model.md), 0: none (fat's).
  double stiffening = 0.0;

  bool operator==(const PresetParams&) const = default;
};

/// Closed ranges [lo, hi] a preset accepts.
struct PresetLimits {
  double width[2];
  double length[2];
  double thickness[2];
  double stiffness[2];
  double modulus[2];  ///< Pa
  int grid[2];  ///< rows and cols
};

PresetParams preset_defaults(Preset preset);
/// The defaults with the tissue given as its Young's modulus from the literature
/// (docs/case-authoring.md, "Tissue presets in kPa"): breast and skin-patch fat 3.25 kPa
/// (Samani, Zubovits and Plewes 2007), a normal prostate 21 kPa (Gerling et al. 2009), the
/// 7 kPa silicone of a phantom slab. What the instructor window starts new cases with.
PresetParams preset_defaults_in_kpa(Preset preset);
PresetLimits preset_limits(Preset preset);

/// The body of a preset, its id the preset's name. Throws std::invalid_argument naming the
/// parameter when one is outside the preset's limits.
mat::BodyGrid make_preset_body(const PresetParams& params);

/// The scoring a preset's organ needs beyond the defaults (docs/scoring.md keys), an empty
/// object when the defaults fit. The prostate is pressed a few millimetres in a digital
/// rectal exam, not half its thickness: its pressure bands are shallower
/// (docs/case-authoring.md, "Presets").
nlohmann::json preset_scoring(Preset preset);

/// A whole case with that body, the preset's scoring (when it has any) and no tumours; its document carries the parameters in a
/// root field "preset" (unknown to format v1, so preserved by every tool) so that an
/// editor can change the size later.
io::CaseFile make_preset_case(const PresetParams& params, const std::string& title);

/// A square slab on a rigid support, `width` (m) wide and `thickness` (m) thick at its
/// centre, of uniform Young's modulus `modulus` (Pa): the layer of the finite-element
/// reference curves (data/reference), for comparing Palpa's forces with them. 13 x 13
/// points; `model` is written as the body's "force_model". Throws as make_preset_body.
io::CaseFile make_modulus_slab(double width, double thickness, double modulus, mat::ForceModel model);

/// {"name", "width", "length", "thickness", "stiffness", "rows", "cols"} (and "modulus"
/// when the tissue is given by it) and back; preset_from_json gives nothing for anything
/// malformed.
nlohmann::json to_json(const PresetParams& params);
std::optional<PresetParams> preset_from_json(const nlohmann::json& value);

}  // namespace palpa::author
