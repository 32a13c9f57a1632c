// Body presets for instructor authoring: every preset, at its defaults and at the corners
// of its limits, is a valid case that fits, with the requested size.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "palpa/author/presets.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/mat/layer_stiffness.hpp"
#include "palpa/mat/mat_body.hpp"
#include "palpa/render/tessellation.hpp"
#include "palpa/scene/scene.hpp"

namespace palpa::author {
namespace {

constexpr std::array kPresets{Preset::Breast, Preset::Prostate, Preset::Patch, Preset::Slab};

// Validates the way palpa-cli validate does: the saved text parses, the body fits.
void expect_valid(const PresetParams& p) {
  SCOPED_TRACE(std::string(to_string(p.preset)) + " w=" + std::to_string(p.width) + " l=" +
               std::to_string(p.length) + " t=" + std::to_string(p.thickness) + " k=" + std::to_string(p.stiffness) +
               " grid=" + std::to_string(p.rows) + "x" + std::to_string(p.cols));
  const io::CaseFile made = make_preset_case(p, "t");
  try {
    const io::CaseFile parsed = io::parse_case(io::to_json(made).dump(), "preset");
    (void)scene::Scene::build(parsed, "preset");
  } catch (const io::CaseError& e) {
    ADD_FAILURE() << e.what();
  }
}

// Thickness 2R at the centre: top and bottom contours at (0.5, 0.5).
double centre_thickness(const mat::MatBody& body) {
  std::array<double, 3> top{}, bottom{};
  body.top().evaluate(0.5, 0.5, top, 3);
  body.bottom().evaluate(0.5, 0.5, bottom, 3);
  return std::hypot(top[0] - bottom[0], top[1] - bottom[1], top[2] - bottom[2]);
}

// Extent of the fitted body's contours along axis c (tessellated finely).
double extent(const mat::MatBody& body, std::size_t c) {
  double lo = 1e9, hi = -1e9;
  for (const auto* s : {&body.top(), &body.bottom()}) {
    render::Mesh mesh;
    render::tessellate(*s, {1e-5, 8, 256}, false, mesh);
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      lo = std::min<double>(lo, mesh.positions[3 * v + c]);
      hi = std::max<double>(hi, mesh.positions[3 * v + c]);
    }
  }
  return hi - lo;
}

TEST(AuthorPresets, NamesRoundTrip) {
  for (Preset p : kPresets) {
    EXPECT_EQ(preset_from_string(to_string(p)), p);
    const auto back = preset_from_json(to_json(preset_defaults(p)));
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(*back, preset_defaults(p));
  }
  EXPECT_FALSE(preset_from_string("kidney").has_value());
  EXPECT_FALSE(preset_from_json(nlohmann::json{{"name", "slab"}}).has_value());
}

TEST(AuthorPresets, DefaultsAreWithinLimits) {
  for (Preset p : kPresets) {
    const auto d = preset_defaults(p);
    const auto l = preset_limits(p);
    EXPECT_TRUE(d.width >= l.width[0] && d.width <= l.width[1]);
    EXPECT_TRUE(d.length >= l.length[0] && d.length <= l.length[1]);
    EXPECT_TRUE(d.thickness >= l.thickness[0] && d.thickness <= l.thickness[1]);
    EXPECT_TRUE(d.stiffness >= l.stiffness[0] && d.stiffness <= l.stiffness[1]);
  }
  // The prostate is the ~4 x 3.5 x 3 cm gland of the issue.
  const auto prostate = preset_defaults(Preset::Prostate);
  EXPECT_DOUBLE_EQ(prostate.width, 0.04);
  EXPECT_DOUBLE_EQ(prostate.length, 0.035);
  EXPECT_DOUBLE_EQ(prostate.thickness, 0.03);
}

TEST(AuthorPresets, EveryPresetValidatesAtDefaultsAndAtTheLimits) {
  for (Preset preset : kPresets) {
    const auto l = preset_limits(preset);
    expect_valid(preset_defaults(preset));
    for (int corner = 0; corner < 16; ++corner) {
      PresetParams p = preset_defaults(preset);
      p.width = l.width[corner & 1];
      p.length = l.length[(corner >> 1) & 1];
      p.thickness = l.thickness[(corner >> 2) & 1];
      p.stiffness = l.stiffness[(corner >> 3) & 1];
      expect_valid(p);
    }
    for (int g : {l.grid[0], l.grid[1]}) {
      PresetParams p = preset_defaults(preset);
      p.rows = p.cols = g;
      expect_valid(p);
    }
  }
}

TEST(AuthorPresets, BoundaryRadiusIsZeroAndStiffnessAsRequested) {
  for (Preset preset : kPresets) {
    const auto g = make_preset_body(preset_defaults(preset));
    for (int i = 0; i < g.rows; ++i) {
      for (int j = 0; j < g.cols; ++j) {
        if (i == 0 || j == 0 || i == g.rows - 1 || j == g.cols - 1) {
          EXPECT_EQ(g.radius[static_cast<std::size_t>(i * g.cols + j)], 0.0);
        }
      }
    }
    // The centre point carries the requested stiffness (the breast's glandular centre).
    EXPECT_DOUBLE_EQ(g.stiffness[static_cast<std::size_t>((g.rows / 2) * g.cols + g.cols / 2)], preset_defaults(preset).stiffness);
  }
}

// The size asked for is the size drawn: 2R at the centre within 1 %, the contours' extent
// along x and y within 2 % of width and length (the contours meet the skeleton's edge).
TEST(AuthorPresets, FittedBodyHasTheRequestedSize) {
  for (Preset preset : kPresets) {
    const auto l = preset_limits(preset);
    for (int corner = 0; corner < 8; ++corner) {
      PresetParams p = preset_defaults(preset);
      p.width = l.width[corner & 1];
      p.length = l.length[(corner >> 1) & 1];
      p.thickness = l.thickness[(corner >> 2) & 1];
      SCOPED_TRACE(std::string(to_string(preset)) + " corner " + std::to_string(corner));
      const auto body = mat::MatBody::fit(make_preset_body(p));
      EXPECT_NEAR(centre_thickness(body), p.thickness, 0.01 * p.thickness);
      EXPECT_NEAR(extent(body, 0), p.width, 0.02 * p.width);
      EXPECT_NEAR(extent(body, 1), p.length, 0.02 * p.length);
    }
  }
}

TEST(AuthorPresets, OutOfLimitsIsRejectedNamingTheParameter) {
  PresetParams p = preset_defaults(Preset::Slab);
  p.thickness = 0.5;
  try {
    (void)make_preset_body(p);
    FAIL() << "accepted a 0.5 m slab";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("thickness"), std::string::npos) << e.what();
  }
  p = preset_defaults(Preset::Slab);
  p.rows = 3;
  EXPECT_THROW((void)make_preset_body(p), std::invalid_argument);
}

// Presets in kPa: at the literature defaults and at the corners of the size and modulus
// limits, a valid case written by its modulus (no stiffness in the file), following the
// calibrated law, whose centre point's derived stiffness is the bonded-layer formula for
// the modulus over the centre's thickness (solved directly, not by the parser's table).
TEST(AuthorPresets, PresetsInKpaAreValidAndWrittenByTheirModulus) {
  for (Preset preset : kPresets) {
    const auto l = preset_limits(preset);
    const auto d = preset_defaults_in_kpa(preset);
    EXPECT_TRUE(d.modulus >= l.modulus[0] && d.modulus <= l.modulus[1]) << to_string(preset);
    expect_valid(d);
    for (int corner = 0; corner < 16; ++corner) {
      PresetParams p = d;
      p.width = l.width[corner & 1];
      p.length = l.length[(corner >> 1) & 1];
      p.thickness = l.thickness[(corner >> 2) & 1];
      p.modulus = l.modulus[(corner >> 3) & 1];
      expect_valid(p);
    }
    const auto file = make_preset_case(d, "t");
    const auto doc = io::to_json(file);
    const auto& body = doc["bodies"][0];
    EXPECT_FALSE(body.contains("stiffness"));
    ASSERT_TRUE(body.contains("modulus"));
    EXPECT_EQ(body["modulus"][0], d.modulus);
    const auto parsed = io::parse_case(doc.dump(), "preset");
    const auto& g = parsed.bodies.front();
    EXPECT_EQ(g.force_model, mat::ForceModel::Calibrated);
    const std::size_t centre = static_cast<std::size_t>((g.rows / 2) * g.cols + g.cols / 2);
    EXPECT_NEAR(g.stiffness[centre], mat::layer_stiffness(d.modulus, g.poisson, mat::kFingertipPadRadius,
                                                          2.0 * g.radius[centre]),
                1e-5 * g.stiffness[centre]);
    // The record round-trips with its modulus; an old record without one is in N/m.
    EXPECT_EQ(preset_from_json(file.document["preset"]), d);
    auto old = file.document["preset"];
    old.erase("modulus");
    EXPECT_EQ(preset_from_json(old)->modulus, 0.0);
  }
  PresetParams soft = preset_defaults_in_kpa(Preset::Breast);
  soft.modulus = 100.0;  // 0.1 kPa: softer than any tissue
  try {
    (void)make_preset_body(soft);
    FAIL() << "accepted 0.1 kPa";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("modulus"), std::string::npos) << e.what();
  }
}

TEST(AuthorPresets, CaseRecordsItsPreset) {
  const auto p = preset_defaults(Preset::Patch);
  const auto file = make_preset_case(p, "Abdomen");
  EXPECT_EQ(file.title, "Abdomen");
  ASSERT_TRUE(file.document.contains("preset"));
  EXPECT_EQ(preset_from_json(file.document["preset"]), p);
  EXPECT_EQ(file.bodies.front().id, "patch");
}

}  // namespace
}  // namespace palpa::author
