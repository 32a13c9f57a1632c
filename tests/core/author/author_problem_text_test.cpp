// The validation problems in the instructor's terms: the table's row (1-based), the field
// at fault, mm and kPa; palpa-cli's own messages stay as they are (io::Problem).
#include <gtest/gtest.h>

#include "palpa/author/case_draft.hpp"
#include "palpa/author/problem_text.hpp"
#include "palpa/render/surface_pick.hpp"
#include "palpa/scene/scene.hpp"

namespace palpa::author {
namespace {

TEST(AuthorProblemText, ATumourReachingBeyondTheSkinIsItsRadiusInMm) {
  const auto p = describe(io::Problem{"/tumors/1", "tumour (radius 0.04 m) is not inside body \"breast\": it reaches "
                                                   "0.02614 m beyond the surface"});
  EXPECT_EQ(p.text, "Tumour 2, radius: 40 mm reaches 26.1 mm beyond the skin");
  EXPECT_EQ(p.field, ProblemField::Radius);
  EXPECT_EQ(p.tumour, std::optional<std::size_t>(1));
  EXPECT_EQ(p.where, "/tumors/1");
  const auto above = describe(io::Problem{"/tumors/0", "tumour (radius 0.004 m) is not inside body \"slab\": its centre "
                                                       "is 0.0032 m outside the surface"});
  EXPECT_EQ(above.field, ProblemField::Depth);
  EXPECT_EQ(above.text, "Tumour 1, depth: its centre is outside the body (the tumour reaches 3.2 mm beyond the surface)");
}

TEST(AuthorProblemText, RangesAndModuliInTheWindowsUnits) {
  EXPECT_EQ(describe(io::Problem{"/tumors/0/radius", "radius 0.06 m is outside (0, 0.05] m"}).text,
            "Tumour 1, radius: 60 mm is outside (0, 50] mm");
  const auto modulus = describe(io::Problem{"/tumors/2/modulus", "modulus 2e+07 Pa is outside (0, 1e+07] Pa"});
  EXPECT_EQ(modulus.field, ProblemField::Material);
  EXPECT_EQ(modulus.text, "Tumour 3, material: 20000 kPa is outside (0, 10000] kPa");
  const auto rule = describe(io::Problem{"/tumors/0/placement/u", "u range [0.7, 0.3] is reversed"});
  EXPECT_EQ(rule.field, ProblemField::Placement);
  EXPECT_EQ(rule.text, "Tumour 1, random placement: along x range [0.7, 0.3] is reversed");
  const auto margin = describe(io::Problem{"/scoring/hit_margin", "hit_margin 2 is outside (0, 1] m"});
  EXPECT_EQ(margin.field, ProblemField::Scoring);
  EXPECT_EQ(margin.key, "hit_margin");
  EXPECT_EQ(margin.text, "Scoring, hit margin: 2000 mm is outside (0, 1000] mm");
  EXPECT_EQ(describe(io::Problem{"/scoring/min_coverage", "min_coverage 1.5 is outside [0, 1]"}).text,
            "Scoring, minimum coverage: 150 % is outside [0, 100] %");
  EXPECT_EQ(describe(io::Problem{"/scoring/deep_min", "light_max 0.6 must be below deep_min 0.55 (light < medium < "
                                                      "deep pressure)"}).text,
            "Scoring, deep pressure from: light pressure up to 60 % must be below deep pressure from 55 % (light < "
            "medium < deep pressure)");
  EXPECT_EQ(si_to_instructor_units("a body 0.0125 m thick of 3250 Pa"), "a body 12.5 mm thick of 3.25 kPa");
}

// From a real validation: a 40 mm tumour placed 12 mm under the slab's skin.
TEST(AuthorProblemText, AValidatedDraftNamesTheRowAndTheRadius) {
  CaseDraft draft(preset_defaults(Preset::Slab));
  const auto scene = scene::Scene::build(draft.valid_case(), "draft");
  const auto hit = render::TopContourPicker(scene).pick(palpa::Vec3(0, 0, 1.0), palpa::Vec3(0, 0, -1));
  ASSERT_TRUE(hit.has_value());
  const SurfacePoint top{hit->body, {hit->point.x(), hit->point.y(), hit->point.z()}, {0, 0, 1}};
  draft.add_tumour(top, {0.012, 0.004, 2000.0});
  draft.add_tumour(top, {0.012, 0.040, 2000.0});
  const auto problems = describe(draft.validate());
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].field, ProblemField::Radius);
  EXPECT_EQ(problems[0].tumour, std::optional<std::size_t>(1));
  EXPECT_EQ(problems[0].text.rfind("Tumour 2, radius: 40 mm reaches ", 0), 0u) << problems[0].text;
  EXPECT_NE(problems[0].text.find(" mm beyond the skin"), std::string::npos) << problems[0].text;
}

TEST(AuthorProblemText, PalpabilityWarningGivesTheNumbers) {
  TumourPalpability plain;
  plain.tumour = 1;
  plain.contrast = 1.06;
  plain.palpable = false;
  TumourPalpability felt;
  felt.contrast = 1.8;
  const auto warnings = palpability_warnings({felt, plain});
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_TRUE(warnings[0].warning);
  EXPECT_EQ(warnings[0].text,
            "Tumour 2 may not be palpable: at deep pressure it raises the force by 6 % (the scripted expert needs about 25 "
            "%)");
}

}  // namespace
}  // namespace palpa::author
