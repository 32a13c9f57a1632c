// Randomized tumour placement: the "placement" rule in case files and place_tumours.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include <set>

#include "scripted_test_support.hpp"
#include "palpa/scripted/tumour_placement.hpp"

namespace palpa {
namespace {

using scripted_test::centre_of;
using scripted_test::column_through;
using scripted_test::default_case;

// The docs' minimal case with a tumour carrying `placement` (raw JSON).
std::string minimal_case(const std::string& placement) {
  return R"({"format": "palpa-case", "version": 1, "title": "t",
    "bodies": [{"id": "pad", "rows": 3, "cols": 3,
      "medial": [[-0.02,-0.02,0],[-0.02,0,0],[-0.02,0.02,0],[0,-0.02,0],[0,0,0.005],[0,0.02,0],[0.02,-0.02,0],[0.02,0,0],[0.02,0.02,0]],
      "radius": [0,0,0, 0,0.01,0, 0,0,0], "stiffness": [200,200,200, 200,300,200, 200,200,200]}],
    "tumors": [{"body": "pad", "center": [0, 0, 0.005], "radius": 0.003, "stiffness": 1500, "placement": )" +
         placement + "}]}";
}

std::vector<std::string> problem_places(const std::string& placement) {
  try {
    io::parse_case(minimal_case(placement), "t.json");
  } catch (const io::CaseError& e) {
    std::vector<std::string> where;
    for (const auto& p : e.problems()) where.push_back(p.where);
    return where;
  }
  return {};
}

TEST(TumourPlacement, ParseAcceptsAValidRuleAndKeepsTheAuthoredCentre) {
  const auto file = io::parse_case(minimal_case(R"({"u": [0.4, 0.6], "v": [0.5, 0.5], "depth": [0, 1]})"), "t.json");
  ASSERT_EQ(file.tumours.size(), 1u);
  EXPECT_EQ(file.tumours[0].center[2], 0.005);
  const auto rule = scripted::placement_of(file, 0);
  ASSERT_TRUE(rule.has_value());
  EXPECT_EQ(rule->u[0], 0.4);
  EXPECT_EQ(rule->v[1], 0.5);
  EXPECT_EQ(rule->depth[1], 1.0);
  EXPECT_TRUE(io::to_json(file)["tumors"][0].contains("placement"));  // preserved on save
}

TEST(TumourPlacement, ParseRejectsBadRulesWithPointers) {
  using V = std::vector<std::string>;
  EXPECT_EQ(problem_places("[0, 1]"), V{"/tumors/0/placement"});
  EXPECT_EQ(problem_places(R"({"u": [0, 1], "v": [0, 1]})"), V{"/tumors/0/placement"});  // missing depth
  EXPECT_EQ(problem_places(R"({"u": [0.1], "v": [0, 1], "depth": [0, 1]})"), V{"/tumors/0/placement/u"});
  EXPECT_EQ(problem_places(R"({"u": [0, 1], "v": [0.8, 0.2], "depth": [0, 1]})"), V{"/tumors/0/placement/v"});
  EXPECT_EQ(problem_places(R"({"u": [0, 1], "v": [0, 1], "depth": [0, 1.5]})"), V{"/tumors/0/placement/depth/1"});
  EXPECT_EQ(problem_places(R"({"u": [-0.1, 1], "v": [0, 1], "depth": [0, 1]})"), V{"/tumors/0/placement/u/0"});
  EXPECT_EQ(problem_places(R"({"u": ["a", 1], "v": [0, 1], "depth": [0, 1]})"), V{"/tumors/0/placement/u/0"});
  EXPECT_EQ(problem_places(R"({"u": [0, 1], "v": [0, 1], "depth": [0, 1], "w": [0, 1]})"),
            V{"/tumors/0/placement/w"});
}

TEST(TumourPlacement, SameSeedSameCentresOtherSeedsDiffer) {
  const auto file = default_case();
  const auto a = scripted::place_tumours(file, 42, "default.json");
  const auto b = scripted::place_tumours(file, 42, "default.json");
  EXPECT_EQ(a.tumours[0].center, b.tumours[0].center);
  std::set<std::array<double, 3>> centres;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) centres.insert(scripted::place_tumours(file, seed, "d").tumours[0].center);
  EXPECT_EQ(centres.size(), 5u);
  EXPECT_NE(a.tumours[0].center, file.tumours[0].center);
  // The document carries the placed centre, so the saved case is the ground truth.
  EXPECT_EQ(a.document["tumors"][0]["center"].get<std::vector<double>>(),
            std::vector<double>(a.tumours[0].center.begin(), a.tumours[0].center.end()));
  EXPECT_EQ(io::to_json(a)["tumors"][0]["center"], a.document["tumors"][0]["center"]);
}

TEST(TumourPlacement, SplitMixMatchesTheReferenceOutput) {
  // First outputs of SplitMix64 seeded with 0 (reference implementation, Vigna).
  scripted::SplitMix64 rng(0);
  EXPECT_EQ(rng.next(), 0xE220A8397B1DCDAFull);
  EXPECT_EQ(rng.next(), 0x6E789E6AA1B965F4ull);
  scripted::SplitMix64 r2(7);
  for (int k = 0; k < 1000; ++k) {
    const double x = r2.uniform();
    ASSERT_GE(x, 0.0);
    ASSERT_LT(x, 1.0);
  }
}

// Over many seeds: the centre lies on the column of a (u, v) inside the rule's rectangle,
// at a depth fraction inside its range, and the tumour is inside the breast (the scene
// builds). The column is recovered from the centre by the foot-point search.
TEST(TumourPlacement, CentresRespectTheRuleAndStayInsideTheBody) {
  const auto file = default_case();
  const auto rule = scripted::placement_of(file, 0);
  ASSERT_TRUE(rule.has_value());
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    const auto placed = scripted::place_tumours(file, seed, "default.json");
    const auto scene = scene::Scene::build(placed, "placed");  // throws for a tumour outside
    const auto& t = placed.tumours[0];
    const auto c = centre_of(t);
    const auto col = column_through(scene.body(0), c);
    EXPECT_GE(col.u, rule->u[0] - 1e-6) << seed;
    EXPECT_LE(col.u, rule->u[1] + 1e-6) << seed;
    EXPECT_GE(col.v, rule->v[0] - 1e-6) << seed;
    EXPECT_LE(col.v, rule->v[1] + 1e-6) << seed;
    EXPECT_LT((c - col.skeleton).cross(col.normal).norm(), 1e-6) << seed;  // on the normal line
    const double fraction = (col.top() - c).dot(col.normal) / (2.0 * col.radius);
    EXPECT_GE(fraction, rule->depth[0] - 1e-6) << seed;
    EXPECT_LE(fraction, rule->depth[1] + 1e-6) << seed;
    EXPECT_GE(scene::tumour_clearance(scene.body(0).body, scene.body(0).search, t), 0.0);
  }
}

// The default case's rule keeps the tumour deep enough that pressing deeper is what finds
// it: right over it, a press to half the thickness feels it more than 1.2 times firmer
// (the scripted expert's threshold is 1.18-1.20), and its excess force there is at least
// 1.5 times what a light press (the light trainee's deepest, 15 % of the thickness) feels.
// Whether the whole exam finds it: PlacedTumoursWholeExams (scripted_run_test.cpp).
TEST(TumourPlacement, DefaultRuleHidesTheTumourFromLightPressesOnly) {
  const auto file = default_case();
  double light_most = 0.0, deep_least = 10.0;
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    const auto placed = scripted::place_tumours(file, seed, "default.json");
    const auto scene = scene::Scene::build(placed, "placed");
    const auto col = column_through(scene.body(0), centre_of(placed.tumours[0]));
    auto contrast = [&](double fraction) {
      auto state = scene.make_state();
      const auto f = scene.probe(col.top() - fraction * 2.0 * col.radius * col.normal, state).force;
      return 1.0 + f.tumour.norm() / f.normal.norm();
    };
    const double light = contrast(0.15), deep = contrast(0.5);
    light_most = std::max(light_most, light);
    deep_least = std::min(deep_least, deep);
    EXPECT_GT(deep, 1.20) << seed;
    EXPECT_GT(deep - 1.0, 1.5 * (light - 1.0)) << seed << ": light " << light << ", deep " << deep;
  }
  std::printf("default rule over 40 seeds: light press at most %.3f, deep press at least %.3f\n", light_most,
              deep_least);
}

TEST(TumourPlacement, TwoPlacedTumoursNeverOverlap) {
  auto file = default_case();
  auto second = file.document["tumors"][0];
  second["radius"] = 0.01;
  second["placement"] = {{"u", {0.3, 0.7}}, {"v", {0.3, 0.7}}, {"depth", {0.5, 0.5}}};
  file.document["tumors"].push_back(second);
  file = io::parse_case(file.document.dump(), "two.json");
  ASSERT_EQ(file.tumours.size(), 2u);
  for (std::uint64_t seed = 0; seed < 30; ++seed) {
    const auto placed = scripted::place_tumours(file, seed, "two.json");
    const auto& a = placed.tumours[0];
    const auto& b = placed.tumours[1];
    EXPECT_GE((centre_of(a) - centre_of(b)).norm(), a.radius + b.radius) << seed;
  }
}

TEST(TumourPlacement, TumoursWithoutARuleKeepTheirCentre) {
  const auto file = io::parse_case(
      R"({"format": "palpa-case", "version": 1, "title": "t",
    "bodies": [{"id": "pad", "rows": 3, "cols": 3,
      "medial": [[-0.02,-0.02,0],[-0.02,0,0],[-0.02,0.02,0],[0,-0.02,0],[0,0,0.005],[0,0.02,0],[0.02,-0.02,0],[0.02,0,0],[0.02,0.02,0]],
      "radius": [0,0,0, 0,0.01,0, 0,0,0], "stiffness": [200,200,200, 200,300,200, 200,200,200]}],
    "tumors": [{"body": "pad", "center": [0.001, 0, 0.005], "radius": 0.003, "stiffness": 1500}]})",
      "t.json");
  EXPECT_EQ(scripted::place_tumours(file, 9, "t.json").tumours[0].center, file.tumours[0].center);
}

TEST(TumourPlacement, ImpossibleRuleIsACaseErrorAtThePlacement) {
  auto file = default_case();
  file.tumours[0].radius = 0.03;  // thicker than the breast anywhere but its very centre
  file.document["tumors"][0]["radius"] = 0.03;
  try {
    scripted::place_tumours(file, 1, "big.json");
    FAIL() << "expected a CaseError";
  } catch (const io::CaseError& e) {
    ASSERT_EQ(e.problems().size(), 1u);
    EXPECT_EQ(e.problems()[0].where, "/tumors/0/placement");
    EXPECT_EQ(e.lines()[0].rfind("big.json: /tumors/0/placement: ", 0), 0u) << e.lines()[0];
  }
}

}  // namespace
}  // namespace palpa
