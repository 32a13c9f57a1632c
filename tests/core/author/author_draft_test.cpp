// The instructor's case draft: undoable edits, tumours placed under picked points, save and
// load, and problems reported at the field that causes them.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "palpa/author/case_draft.hpp"
#include "palpa/scripted/tumour_placement.hpp"
#include "palpa/mat/layer_stiffness.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/io/thresholds.hpp"
#include "palpa/render/surface_pick.hpp"

namespace palpa::author {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  fs::path dir = fs::temp_directory_path() / (std::string("palpa_author_") + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

bool has_problem_at(const std::vector<io::Problem>& problems, const std::string& where) {
  for (const auto& p : problems) {
    if (p.where == where) return true;
  }
  return false;
}

// The point of the slab's top contour above (x, y), picked as the window does.
SurfacePoint pick_top(const CaseDraft& draft, double x, double y) {
  const auto scene = scene::Scene::build(draft.valid_case(), "draft");
  const render::TopContourPicker picker(scene);
  const auto hit = picker.pick(palpa::Vec3(x, y, 1.0), palpa::Vec3(0, 0, -1));
  EXPECT_TRUE(hit.has_value());
  return {hit->body, {hit->point.x(), hit->point.y(), hit->point.z()}, {hit->normal.x(), hit->normal.y(), hit->normal.z()}};
}

TEST(AuthorDraft, NewDraftIsAValidBreastAndClean) {
  CaseDraft draft;
  EXPECT_TRUE(draft.validate().empty());
  EXPECT_FALSE(draft.dirty());
  EXPECT_FALSE(draft.can_undo());
  ASSERT_TRUE(draft.preset().has_value());
  EXPECT_EQ(draft.preset()->preset, Preset::Breast);
}

TEST(AuthorDraft, ACaseNotMadeFromAPresetOffersItsOwnSizeAndTissue) {
  // The bundled default case (no "preset"): 140 x 160 mm of medial points, by hand from
  // data/cases/make_cases.py; fibroglandular tissue, 3.24 kPa, stiffening 3.593.
  const auto draft = CaseDraft::load(PALPA_SOURCE_DIR "/data/cases/default.json");
  ASSERT_FALSE(draft.preset().has_value());
  const auto p = draft.preset_or_nearest();
  EXPECT_EQ(p.preset, Preset::Breast);
  EXPECT_NEAR(p.width, 0.14, 1e-9);
  EXPECT_NEAR(p.length, 0.16, 1e-9);
  double largest = 0.0;
  for (const auto& r : draft.document()["bodies"][0]["radius"]) largest = std::max(largest, r.get<double>());
  EXPECT_NEAR(p.thickness, 2.0 * largest, 1e-12);
  EXPECT_NEAR(p.modulus, 3240.0, 1e-9);
  EXPECT_NEAR(p.stiffening, 3.593, 1e-9);
  // A case in N/m offers its mean stiffness; a preset case its own parameters.
  auto doc = draft.document();
  auto& body = doc["bodies"][0];
  body.erase("modulus");
  body.erase("stiffening");
  body["stiffness"] = std::vector<double>(body["radius"].size(), 150.0);
  const auto springs = CaseDraft::from_document(doc, "springs.json").preset_or_nearest();
  EXPECT_EQ(springs.modulus, 0.0);
  EXPECT_NEAR(springs.stiffness, 150.0, 1e-9);
  CaseDraft made;
  EXPECT_EQ(made.preset_or_nearest(), *made.preset());
}

TEST(AuthorDraft, UndoRestoresTheExactDocumentAndRedoReapplies) {
  CaseDraft draft;
  const nlohmann::json before = draft.document();
  draft.set_title("Lump in the upper-outer quadrant");
  const nlohmann::json after_title = draft.document();
  PresetParams p = preset_defaults(Preset::Breast);
  p.width = 0.12;
  draft.apply_preset(p);
  const nlohmann::json after_preset = draft.document();
  EXPECT_NE(after_preset, after_title);

  ASSERT_TRUE(draft.undo());
  EXPECT_EQ(draft.document(), after_title);
  ASSERT_TRUE(draft.undo());
  EXPECT_EQ(draft.document(), before);
  EXPECT_FALSE(draft.can_undo());
  EXPECT_FALSE(draft.undo());

  ASSERT_TRUE(draft.redo());
  EXPECT_EQ(draft.document(), after_title);
  ASSERT_TRUE(draft.redo());
  EXPECT_EQ(draft.document(), after_preset);
  EXPECT_FALSE(draft.can_redo());

  // A new edit after an undo drops the redo branch.
  ASSERT_TRUE(draft.undo());
  draft.set_title("Another");
  EXPECT_FALSE(draft.can_redo());
  EXPECT_EQ(draft.title(), "Another");
}

TEST(AuthorDraft, TumourLiesTheSetDepthBelowThePickedPoint) {
  PresetParams slab = preset_defaults(Preset::Slab);  // flat top at z = thickness over its middle
  CaseDraft draft(slab);
  // The middle of the slab is flat (by symmetry), its top at z = thickness (the skeleton
  // at T/2 plus radius T/2); the tessellated pick is within its 0.1 mm tolerance.
  const SurfacePoint where = pick_top(draft, 0.0, 0.0);
  EXPECT_NEAR(where.point[2], slab.thickness, 1e-4);
  const double depth = 0.012;
  const std::size_t k = draft.add_tumour(where, {depth, 0.004, 1500.0});
  const auto t = draft.tumour(k);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(t->center[2], slab.thickness - depth, 1e-4);
  EXPECT_NEAR(t->center[0], 0.0, 1e-6);
  EXPECT_NEAR(t->center[1], 0.0, 1e-6);
  EXPECT_EQ(t->body, "slab");
  EXPECT_TRUE(draft.validate().empty());
  const auto spec = draft.spec(k);
  ASSERT_TRUE(spec.has_value());
  EXPECT_NEAR(spec->depth, depth, 1e-12);

  // Editing the depth moves the centre along the normal; radius and stiffness follow.
  draft.edit_tumour(k, {0.02, 0.005, 1800.0});
  EXPECT_NEAR(draft.tumour(k)->center[2], where.point[2] - 0.02, 1e-6);
  EXPECT_DOUBLE_EQ(draft.tumour(k)->radius, 0.005);
  EXPECT_DOUBLE_EQ(draft.tumour(k)->stiffness, 1800.0);

  // Moving keeps the depth, now along the (slightly tilted) normal of the new point: the
  // rounded edge tilts it by less than 0.1 rad at x = -0.03.
  const SurfacePoint other = pick_top(draft, -0.03, 0.0);
  draft.move_tumour(k, other);
  const auto moved = draft.tumour(k)->center;
  EXPECT_NEAR(std::hypot(moved[0] - other.point[0], moved[1] - other.point[1], moved[2] - other.point[2]), 0.02, 1e-12);
  EXPECT_NEAR(moved[0], -0.03, 0.02 * 0.1);
  EXPECT_NEAR(moved[2], other.point[2] - 0.02, 0.02 * 0.01);

  draft.remove_tumour(k);
  EXPECT_EQ(draft.tumour_count(), 0u);
  ASSERT_TRUE(draft.undo());
  EXPECT_EQ(draft.tumour_count(), 1u);
}

TEST(AuthorDraft, PlacedCaseSavedAndLoadedRoundTripsExactly) {
  const fs::path dir = temp_dir();
  CaseDraft draft(preset_defaults(Preset::Slab));
  const auto k = draft.add_tumour(pick_top(draft, 0.0, 0.0), {0.015, 0.005, 2000.0});
  draft.set_placement(k, scripted::Placement{{0.3, 0.7}, {0.25, 0.75}, {0.45, 0.55}});
  ASSERT_TRUE(draft.validate().empty());
  ASSERT_TRUE(draft.dirty());
  draft.save(dir / "authored.json");
  EXPECT_FALSE(draft.dirty());

  // The draft reads back equal, rule and anchor included.
  const CaseDraft loaded = CaseDraft::load(dir / "authored.json");
  EXPECT_EQ(loaded.document(), draft.document());
  ASSERT_TRUE(loaded.placement(0).has_value());
  EXPECT_EQ(loaded.placement(0)->v[0], 0.25);

  // A seeded exercise's placed case round-trips bit for bit.
  const io::CaseFile placed = scripted::place_tumours(loaded.valid_case(), 42, "authored");
  io::save_case(placed, dir / "placed.json");
  const io::CaseFile again = io::load_case(dir / "placed.json");
  ASSERT_EQ(again.tumours.size(), 1u);
  EXPECT_EQ(again.tumours[0].center, placed.tumours[0].center);
  EXPECT_NE(again.tumours[0].center, draft.tumour(0)->center);  // it was moved
  EXPECT_EQ(io::to_json(again), io::to_json(placed));
  fs::remove_all(dir);
}

TEST(AuthorDraft, DirtyFollowsUndoBackToTheSavedState) {
  const fs::path dir = temp_dir();
  CaseDraft draft;
  draft.set_title("a");
  draft.save(dir / "a.json");
  EXPECT_FALSE(draft.dirty());
  draft.set_title("b");
  EXPECT_TRUE(draft.dirty());
  draft.undo();
  EXPECT_FALSE(draft.dirty());
  draft.undo();
  EXPECT_TRUE(draft.dirty());
  draft.redo();
  EXPECT_FALSE(draft.dirty());
  fs::remove_all(dir);
}

TEST(AuthorDraft, ProblemsPointAtTheOffendingTumourField) {
  CaseDraft draft(preset_defaults(Preset::Slab));
  const SurfacePoint top = pick_top(draft, 0.0, 0.0);
  draft.add_tumour(top, {0.015, 0.005, 2000.0});
  // Radius 0: the structural check names the field.
  draft.add_tumour(pick_top(draft, 0.03, 0.03), {0.01, 0.0, 2000.0});
  auto problems = draft.validate();
  EXPECT_TRUE(has_problem_at(problems, "/tumors/1/radius")) << problems.front().where;
  EXPECT_THROW((void)draft.valid_case(), io::CaseError);
  draft.undo();
  // Above the skin: the scene check names the tumour.
  draft.add_tumour(top, {-0.01, 0.004, 2000.0});
  problems = draft.validate();
  ASSERT_FALSE(problems.empty());
  EXPECT_TRUE(has_problem_at(problems, "/tumors/1")) << problems.front().where << ": " << problems.front().reason;
  // Saving an invalid case writes nothing.
  const fs::path dir = temp_dir();
  EXPECT_THROW(draft.save(dir / "bad.json"), io::CaseError);
  EXPECT_FALSE(fs::exists(dir / "bad.json"));
  // A rule that can never be drawn (a tumour thicker than the slab) is found before a trainee meets it.
  draft.undo();
  draft.edit_tumour(0, {0.015, 0.005, 2000.0});
  draft.set_placement(0, scripted::Placement{{0.0, 0.02}, {0.0, 0.02}, {0.0, 0.05}});
  EXPECT_TRUE(has_problem_at(draft.validate(), "/tumors/0/placement"));
  fs::remove_all(dir);
}

TEST(AuthorDraft, InvalidDocumentLoadsForEditingAndNotJsonDoesNot) {
  const fs::path dir = temp_dir();
  CaseDraft draft(preset_defaults(Preset::Slab));
  nlohmann::json doc = draft.document();
  doc["bodies"][0]["radius"][0] = 0.01;  // boundary radius must be 0
  {
    std::ofstream(dir / "bad.json") << doc.dump(2);
    std::ofstream(dir / "notjson.json") << "{ \"format\": ";
  }
  const CaseDraft loaded = CaseDraft::load(dir / "bad.json");
  EXPECT_TRUE(has_problem_at(loaded.validate(), "/bodies/0/radius/0"));
  EXPECT_EQ(loaded.source(), (dir / "bad.json").string());
  EXPECT_THROW((void)CaseDraft::load(dir / "notjson.json"), io::CaseError);
  EXPECT_THROW((void)CaseDraft::load(dir / "missing.json"), io::CaseError);
  fs::remove_all(dir);
}

TEST(AuthorDraft, PresetChangeKeepsTumoursAndReportsOnesLeftOutside) {
  CaseDraft draft(preset_defaults(Preset::Slab));
  draft.add_tumour(pick_top(draft, 0.04, 0.0), {0.015, 0.005, 2000.0});
  PresetParams small = preset_defaults(Preset::Slab);
  small.width = 0.05;  // the tumour at x = 0.04 is now outside
  draft.apply_preset(small);
  EXPECT_TRUE(has_problem_at(draft.validate(), "/tumors/0"));
  // Out-of-range parameters change nothing.
  PresetParams huge = small;
  huge.width = 5.0;
  const auto doc = draft.document();
  EXPECT_THROW(draft.apply_preset(huge), std::invalid_argument);
  EXPECT_EQ(draft.document(), doc);
  draft.apply_preset(preset_defaults(Preset::Breast));
  EXPECT_EQ(draft.tumour(0)->body, "breast");
}

// The prostate's pressure bands come with the prostate and go with it, but an
// instructor's own pass marks stay whatever the preset.
TEST(AuthorDraft, PresetChangeSwapsTheOrgansPressureBands) {
  const auto bands = [](const CaseDraft& d) {
    std::vector<io::Problem> problems;
    const auto t = io::thresholds_from_case(d.document(), problems);
    EXPECT_TRUE(problems.empty());
    return std::pair{t.light_max, t.deep_min};
  };
  const io::Thresholds defaults;
  CaseDraft draft(preset_defaults(Preset::Breast));
  EXPECT_EQ(bands(draft), std::pair(defaults.light_max, defaults.deep_min));
  EXPECT_FALSE(draft.document().contains("scoring"));
  draft.apply_preset(preset_defaults(Preset::Prostate));
  EXPECT_EQ(bands(draft), std::pair(0.10, 0.20));
  EXPECT_TRUE(draft.validate().empty());
  draft.apply_preset(preset_defaults(Preset::Slab));
  EXPECT_EQ(bands(draft), std::pair(defaults.light_max, defaults.deep_min));
  EXPECT_FALSE(draft.document().contains("scoring"));  // nothing of the prostate's left
  // The instructor's own deep band and pass mark survive a change of preset.
  draft.apply_preset(preset_defaults(Preset::Prostate));
  auto doc = draft.document();
  doc["scoring"]["deep_min"] = 0.3;
  doc["scoring"]["min_coverage"] = 0.8;
  CaseDraft edited = CaseDraft::from_document(doc, "edited");
  edited.apply_preset(preset_defaults(Preset::Breast));
  EXPECT_EQ(bands(edited), std::pair(defaults.light_max, 0.3));
  EXPECT_EQ(edited.document()["scoring"]["min_coverage"], 0.8);
  // A new prostate case has them from the start.
  EXPECT_EQ(bands(CaseDraft(preset_defaults(Preset::Prostate))), std::pair(0.10, 0.20));
}

TEST(AuthorDraft, DepthOfATumourWithoutAnchorComesFromTheSurfaceAbove) {
  CaseDraft draft = CaseDraft::load(PALPA_SOURCE_DIR "/data/cases/default.json");
  ASSERT_TRUE(draft.validate().empty());
  const auto before = draft.tumour(0);
  const auto spec = draft.spec(0);
  ASSERT_TRUE(spec.has_value());
  // default.json's tumour sits on the skeleton: its depth is about the radius there (< 25 mm).
  EXPECT_GT(spec->depth, 0.005);
  EXPECT_LT(spec->depth, 0.025);
  // Re-applying the same spec leaves the centre where it was.
  draft.edit_tumour(0, *spec);
  for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(draft.tumour(0)->center[c], before->center[c], 1e-12);
}

TEST(AuthorDraft, StiffnessMapIsAnUndoableEdit) {
  CaseDraft draft(preset_defaults(Preset::Slab));
  const auto before = draft.document();
  StiffnessMap half{1, 2, {0.0, 1.0}};
  draft.apply_stiffness_map(0, half, 100.0, 300.0);
  const auto k = draft.document()["bodies"][0]["stiffness"];
  EXPECT_DOUBLE_EQ(k[0].get<double>(), 100.0);       // point (0, 0): v = 0
  EXPECT_DOUBLE_EQ(k[10].get<double>(), 300.0);      // point (0, 10): v = 1
  EXPECT_NEAR(k[5].get<double>(), 200.0, 1e-9);      // point (0, 5): v = 0.5
  EXPECT_TRUE(draft.validate().empty());
  draft.undo();
  EXPECT_EQ(draft.document(), before);
}

// The slab preset's document with its body given as 5 kPa instead of a stiffness.
nlohmann::json slab_in_pa(const CaseDraft& preset) {
  auto doc = preset.document();
  auto& body = doc["bodies"][0];
  body.erase("stiffness");
  body["modulus"] = std::vector<double>(body["radius"].size(), 5000.0);
  return doc;
}

TEST(AuthorDraft, AStiffnessMapOnABodyInKpaKeepsItsForceLaw) {
  // A map is authored in N/m: the body given by its modulus becomes one given by stiffness,
  // and keeps the calibrated law it had by default (no modulus left beside the stiffness).
  auto doc = slab_in_pa(CaseDraft(preset_defaults(Preset::Slab)));
  doc["bodies"][0]["poisson"] = 0.45;
  CaseDraft draft = CaseDraft::from_document(doc, "kpa.json");
  ASSERT_TRUE(draft.validate().empty());
  draft.apply_stiffness_map(0, StiffnessMap{1, 2, {0.0, 1.0}}, 100.0, 300.0);
  const auto& edited = draft.document()["bodies"][0];
  EXPECT_FALSE(edited.contains("modulus"));
  EXPECT_FALSE(edited.contains("poisson"));
  EXPECT_EQ(edited["force_model"], "calibrated");
  EXPECT_DOUBLE_EQ(edited["stiffness"][10].get<double>(), 300.0);
  EXPECT_TRUE(draft.validate().empty());
}

TEST(AuthorDraft, ATumourInPaIsListedAndAnEditInTheWindowWritesItInNm) {
  const CaseDraft preset(preset_defaults(Preset::Slab));
  auto doc = slab_in_pa(preset);
  const SurfacePoint centre = pick_top(preset, 0.0, 0.0);
  doc["tumors"] = nlohmann::json::array(
      {{{"body", doc["bodies"][0]["id"]}, {"center", {centre.point[0], centre.point[1], centre.point[2] - 0.01}},
        {"radius", 0.005}, {"modulus", 25000.0}}});
  CaseDraft draft = CaseDraft::from_document(doc, "kpa.json");
  ASSERT_TRUE(draft.validate().empty());
  const auto t = draft.tumour(0);
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->modulus, 25000.0);
  EXPECT_EQ(t->stiffness, 0.0);
  draft.edit_tumour(0, TumourSpec{0.010, 0.004, 2000.0});
  EXPECT_FALSE(draft.document()["tumors"][0].contains("modulus"));
  EXPECT_EQ(draft.document()["tumors"][0]["stiffness"], 2000.0);
  EXPECT_TRUE(draft.validate().empty());
}

TEST(AuthorDraft, ATumourSpecInPaIsWrittenAsItsModulusAndKeptThroughEdits) {
  const CaseDraft preset(preset_defaults(Preset::Slab));
  CaseDraft draft = CaseDraft::from_document(slab_in_pa(preset), "kpa.json");
  EXPECT_TRUE(draft.tissue_in_pa());
  EXPECT_FALSE(preset.tissue_in_pa());
  TumourSpec spec{0.010, 0.005, 0.0, 20e3};  // 20 kPa: an intermediate-grade carcinoma
  const auto k = draft.add_tumour(pick_top(preset, 0.0, 0.0), spec);
  const auto& t = draft.document()["tumors"][k];
  EXPECT_EQ(t["modulus"], 20e3);
  EXPECT_FALSE(t.contains("stiffness"));
  ASSERT_TRUE(draft.validate().empty());
  const auto read = draft.spec(k);
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(read->modulus, 20e3);
  // A new radius keeps the modulus; a modulus of 0 with a stiffness writes the tumour in N/m.
  spec = *read;
  spec.radius = 0.004;
  draft.edit_tumour(k, spec);
  EXPECT_EQ(draft.document()["tumors"][k]["modulus"], 20e3);
  EXPECT_EQ(draft.document()["tumors"][k]["radius"], 0.004);
  // Strain stiffening goes with the modulus, is read back, and goes away with it.
  spec.stiffening = 11.073;
  draft.edit_tumour(k, spec);
  EXPECT_EQ(draft.document()["tumors"][k]["stiffening"], 11.073);
  ASSERT_TRUE(draft.validate().empty());
  EXPECT_EQ(draft.spec(k)->stiffening, 11.073);
  EXPECT_EQ(io::parse_case(draft.document().dump(), "kpa.json").tumours.at(0).stiffening, 11.073);
  spec.modulus = 0.0;
  spec.stiffness = 1500.0;
  draft.edit_tumour(k, spec);
  EXPECT_FALSE(draft.document()["tumors"][k].contains("modulus"));
  EXPECT_FALSE(draft.document()["tumors"][k].contains("stiffening"));
  ASSERT_TRUE(draft.validate().empty());
  EXPECT_EQ(draft.document()["tumors"][k]["stiffness"], 1500.0);
  // A tumour in Pa inside a body in N/m is a problem at its modulus.
  CaseDraft in_nm(preset_defaults(Preset::Slab));
  in_nm.add_tumour(pick_top(preset, 0.0, 0.0), TumourSpec{0.010, 0.005, 0.0, 20e3});
  const auto problems = in_nm.validate();
  ASSERT_FALSE(problems.empty());
  EXPECT_EQ(problems.front().where, "/tumors/0/modulus");
}

TEST(AuthorDraft, AModulusMapSetsTheTissueInPaAndTheStiffnessFollowsTheLayer) {
  const CaseDraft preset(preset_defaults(Preset::Slab));
  auto doc = slab_in_pa(preset);
  doc["bodies"][0]["poisson"] = 0.45;
  CaseDraft draft = CaseDraft::from_document(doc, "kpa.json");
  const auto before = draft.document();
  draft.apply_modulus_map(0, StiffnessMap{1, 2, {0.0, 1.0}}, 3e3, 30e3);
  const auto& body = draft.document()["bodies"][0];
  EXPECT_FALSE(body.contains("stiffness"));
  EXPECT_EQ(body["poisson"], 0.45);
  EXPECT_DOUBLE_EQ(body["modulus"][0].get<double>(), 3e3);    // point (0, 0): v = 0
  EXPECT_DOUBLE_EQ(body["modulus"][10].get<double>(), 30e3);  // point (0, 10): v = 1
  ASSERT_TRUE(draft.validate().empty());
  // The stiffness the case derives at the centre point (5, 5): the layer formula solved
  // directly (not the table the parser uses) for the point's modulus and thickness 2R.
  const auto file = draft.valid_case();
  const std::size_t centre = 5 * 11 + 5;
  const double e = body["modulus"][centre].get<double>(), r = file.bodies[0].radius[centre];
  EXPECT_NEAR(e, 16.5e3, 1e-6);
  EXPECT_NEAR(file.bodies[0].stiffness[centre], mat::layer_stiffness(e, 0.45, mat::kFingertipPadRadius, 2 * r),
              1e-5 * file.bodies[0].stiffness[centre]);
  draft.undo();
  EXPECT_EQ(draft.document(), before);
  // A body in N/m has no modulus to map: refused, nothing recorded.
  CaseDraft in_nm(preset_defaults(Preset::Slab));
  EXPECT_THROW(in_nm.apply_modulus_map(0, StiffnessMap{1, 2, {0.0, 1.0}}, 3e3, 30e3), std::invalid_argument);
  EXPECT_FALSE(in_nm.can_undo());
}

// A body change keeps the tumour where it is and measures its depth to the new skin: the
// breast's apex 50 mm high with a tumour 10 mm below it; 60 mm thick, the reported depth is
// the distance from the (unmoved) centre up to the new apex, picked independently (about
// 20 mm); 30 mm thick, the tumour is above the skin: no depth, and validate() says so.
TEST(AuthorDraft, DepthAfterABodyChangeIsMeasuredToTheNewSkin) {
  PresetParams breast = preset_defaults(Preset::Breast);
  ASSERT_EQ(breast.thickness, 0.05);
  CaseDraft draft(breast);
  const SurfacePoint apex = pick_top(draft, 0.0, 0.0);
  const std::size_t k = draft.add_tumour(apex, {0.010, 0.004, 2000.0});
  const auto centre = draft.tumour(k)->center;

  breast.thickness = 0.06;
  draft.apply_preset(breast);
  EXPECT_EQ(draft.tumour(k)->center, centre);  // the tumour did not move
  const SurfacePoint new_apex = pick_top(draft, centre[0], centre[1]);
  const double truth = std::hypot(new_apex.point[0] - centre[0], new_apex.point[1] - centre[1],
                                  new_apex.point[2] - centre[2]);
  EXPECT_GT(new_apex.point[2], apex.point[2] + 0.008);  // the skin went up by about 10 mm
  auto spec = draft.spec(k);
  ASSERT_TRUE(spec.has_value());
  EXPECT_NEAR(spec->depth, truth, 1e-4);  // the picker's tessellation tolerance
  EXPECT_GT(spec->depth, 0.018);
  EXPECT_TRUE(draft.validate().empty());

  breast.thickness = 0.03;
  draft.apply_preset(breast);
  EXPECT_EQ(draft.tumour(k)->center, centre);
  EXPECT_FALSE(draft.spec(k).has_value());  // above the new skin: no depth below it
  EXPECT_TRUE(has_problem_at(draft.validate(), "/tumors/0"));

  // Undo brings the old bodies and the recorded anchor back: 10 mm again.
  ASSERT_TRUE(draft.undo());
  ASSERT_TRUE(draft.undo());
  spec = draft.spec(k);
  ASSERT_TRUE(spec.has_value());
  EXPECT_NEAR(spec->depth, 0.010, 1e-12);
}

// Editing a tumour's stiffness or radius leaves its centre exactly as written, even where
// recomputing it from its anchor and depth would round it (a tumour without anchor).
TEST(AuthorDraft, EditingStiffnessLeavesTheCentreBitIdentical) {
  CaseDraft draft = CaseDraft::load(PALPA_SOURCE_DIR "/data/cases/default.json");
  const auto before = *draft.tumour(0);
  auto spec = *draft.spec(0);
  spec.stiffness = before.stiffness * 1.5;
  spec.radius = 0.0003;
  draft.edit_tumour(0, spec);
  EXPECT_EQ(draft.tumour(0)->center, before.center);
  EXPECT_EQ(draft.tumour(0)->radius, 0.0003);
  EXPECT_EQ(draft.tumour(0)->stiffness, before.stiffness * 1.5);
  EXPECT_FALSE(draft.document()["tumors"][0].contains("anchor"));  // nothing else written
}

// Undo history is capped by memory as well as by count: with room for 3.5 documents of
// the same size, 10 title edits leave the 3 newest steps, the oldest dropped.
TEST(AuthorDraft, UndoHistoryIsCappedByMemory) {
  CaseDraft draft(preset_defaults(Preset::Slab));
  const auto title = [](int k) { return std::string("Title number ") + static_cast<char>('A' + k); };
  draft.set_title(title(0));
  const std::size_t one = approx_bytes(draft.document());
  EXPECT_GT(one, draft.document().dump().size());  // nodes take more room than their text
  draft.set_undo_limits({200, one * 7 / 2});
  EXPECT_LE(draft.history_bytes(), one);  // one step: the new case before its title
  std::vector<nlohmann::json> docs{draft.document()};
  for (int k = 1; k <= 10; ++k) {
    draft.set_title(title(k));
    docs.push_back(draft.document());
    EXPECT_LE(draft.history_bytes(), one * 7 / 2);
  }
  int undone = 0;
  while (draft.undo()) {
    ++undone;
    EXPECT_EQ(draft.document(), docs[docs.size() - 1 - static_cast<std::size_t>(undone)]);
  }
  EXPECT_EQ(undone, 3);
  // The undone documents now sit in redo, within the same cap; redo brings them all back.
  EXPECT_LE(draft.history_bytes(), one * 7 / 2);
  while (draft.redo()) {
  }
  EXPECT_EQ(draft.document(), docs.back());
  // A count limit of 2 keeps 2 steps.
  draft.set_undo_limits({2, std::size_t{1} << 30});
  draft.set_title("x");
  EXPECT_TRUE(draft.undo());
  EXPECT_TRUE(draft.undo());
  EXPECT_FALSE(draft.undo());
}

// Failed edits leave no undo step and change nothing.
TEST(AuthorDraft, FailedEditsLeaveNoUndoStep) {
  CaseDraft array = CaseDraft::from_document(nlohmann::json::array({1, 2}), "array");
  EXPECT_THROW(array.set_title("t"), std::invalid_argument);
  EXPECT_FALSE(array.can_undo());
  EXPECT_FALSE(array.dirty());
  EXPECT_EQ(array.document(), nlohmann::json::array({1, 2}));

  // A tumour with a recorded anchor in a document without bodies: moving it fails without
  // inserting a "bodies" member outside undo.
  nlohmann::json doc = {{"tumors", {{{"body", "b"}, {"center", {0.0, 0.0, 0.01}}, {"radius", 0.004},
                                      {"stiffness", 2000.0},
                                      {"anchor", {{"point", {0.0, 0.0, 0.02}}, {"normal", {0.0, 0.0, 1.0}}}}}}}};
  CaseDraft bodiless = CaseDraft::from_document(doc, "bodiless");
  EXPECT_THROW(bodiless.move_tumour(0, {0, {0.0, 0.0, 0.02}, {0.0, 0.0, 1.0}}), std::out_of_range);
  EXPECT_EQ(bodiless.document(), doc);
  EXPECT_FALSE(bodiless.can_undo());
  EXPECT_THROW((void)bodiless.add_tumour({0, {0.0, 0.0, 0.02}, {0.0, 0.0, 1.0}}, {}), std::out_of_range);
  EXPECT_EQ(bodiless.document(), doc);
}

}  // namespace
}  // namespace palpa::author

namespace palpa::author {
namespace {

// The depth range a randomized tumour can take: on the 30 mm slab a 40-50 % rule is
// 12-15 mm; on the breast (a dome) the centres scripted::place_tumours draws for many
// seeds all lie within the range given, and fill most of it.
TEST(AuthorDraft, RandomDepthRangeIsWhereSeededPlacementPutsTheCentre) {
  CaseDraft slab(preset_defaults(Preset::Slab));
  slab.add_tumour(pick_top(slab, 0.0, 0.0), {0.012, 0.004, 2000.0});
  EXPECT_FALSE(slab.random_depth_ranges()[0].has_value());
  slab.set_placement(0, scripted::Placement{{0.3, 0.7}, {0.3, 0.7}, {0.4, 0.5}});
  const auto flat = slab.random_depth_ranges()[0];
  ASSERT_TRUE(flat.has_value());
  EXPECT_NEAR((*flat)[0], 0.012, 2e-4);
  EXPECT_NEAR((*flat)[1], 0.015, 2e-4);

  CaseDraft breast(preset_defaults_in_kpa(Preset::Breast));
  breast.add_tumour(pick_top(breast, 0.0, 0.0), {0.012, 0.005, 0.0, 19440.0, 0.0});
  breast.set_placement(0, scripted::Placement{{0.3, 0.7}, {0.3, 0.7}, {0.4, 0.5}});
  const auto range = breast.random_depth_ranges()[0];
  ASSERT_TRUE(range.has_value());
  const auto file = breast.valid_case();
  io::CaseFile bodies = file;
  bodies.tumours.clear();
  const auto scene = scene::Scene::build(bodies, "breast");
  const render::TopContourPicker picker(scene);
  double lo = 1.0, hi = 0.0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    const auto placed = scripted::place_tumours(file, seed, "breast").tumours[0];
    // The depth below the skin straight above (the dome is nearly level where the rule puts it).
    const palpa::Vec3 c(placed.center[0], placed.center[1], placed.center[2]);
    const auto hit = picker.pick(c + palpa::Vec3(0, 0, 1.0), palpa::Vec3(0, 0, -1));
    ASSERT_TRUE(hit.has_value());
    const double depth = (hit->point - c).norm();
    lo = std::min(lo, depth);
    hi = std::max(hi, depth);
  }
  EXPECT_GE(lo, (*range)[0] - 0.5e-3) << lo << " " << (*range)[0];
  EXPECT_LE(hi, (*range)[1] + 0.5e-3) << hi << " " << (*range)[1];
  EXPECT_LT(lo, (*range)[0] + 0.3 * ((*range)[1] - (*range)[0]));
  EXPECT_GT(hi, (*range)[1] - 0.3 * ((*range)[1] - (*range)[0]));
}

}  // namespace
}  // namespace palpa::author

namespace palpa::author {
namespace {

// The exam settings the window edits: a description, scoring keys in SI and one rectangle
// of every body, each an undo step, read back by palpa-cli's own reader (thresholds).
TEST(AuthorDraft, ExamSettingsAreWrittenWhereTheFormatSaysAndUndone) {
  CaseDraft draft(preset_defaults(Preset::Slab));
  EXPECT_EQ(draft.exam_region_kind(), CaseDraft::RegionKind::Whole);
  draft.set_description("A slab with nothing in it.");
  draft.set_scoring("hit_margin", 0.008);
  draft.set_exam_region(ExamExtent{{0.1, 0.6}, {0.2, 0.8}});
  const auto& doc = draft.document();
  EXPECT_EQ(doc["description"], "A slab with nothing in it.");
  EXPECT_EQ(doc["scoring"]["hit_margin"], 0.008);
  EXPECT_EQ(doc["exam_region"], nlohmann::json::parse(R"([{"body": "slab", "u": [0.1, 0.6], "v": [0.2, 0.8]}])"));
  EXPECT_EQ(draft.exam_region_kind(), CaseDraft::RegionKind::Extent);
  EXPECT_EQ(draft.exam_extent(), (ExamExtent{{0.1, 0.6}, {0.2, 0.8}}));
  std::vector<io::Problem> problems;
  const auto t = io::thresholds_from_case(draft.valid_case().document, problems);
  EXPECT_TRUE(problems.empty());
  EXPECT_EQ(t.hit_margin, 0.008);
  EXPECT_EQ(draft.thresholds().hit_margin, 0.008);
  ASSERT_EQ(t.exam_region.size(), 1u);
  EXPECT_EQ(t.exam_region[0].u0, 0.1);
  // Two rectangles on one body: not what the window edits, kept as written.
  nlohmann::json two = draft.document();
  two["exam_region"].push_back({{"body", "slab"}, {"u", {0.7, 0.9}}});
  EXPECT_EQ(CaseDraft::from_document(two, "two").exam_region_kind(), CaseDraft::RegionKind::Custom);
  draft.undo();
  EXPECT_FALSE(draft.document().contains("exam_region"));
  draft.set_scoring("hit_margin", std::nullopt);
  EXPECT_FALSE(draft.document().contains("scoring"));
  draft.set_description("");
  EXPECT_FALSE(draft.document().contains("description"));
  // A description must be a string: the reader says so at its pointer.
  nlohmann::json bad = draft.document();
  bad["description"] = 3;
  const auto found = CaseDraft::from_document(bad, "bad").validate();
  ASSERT_FALSE(found.empty());
  EXPECT_EQ(found.front().where, "/description");
}

}  // namespace
}  // namespace palpa::author
