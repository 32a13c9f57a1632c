// Thresholds from a case's "scoring" and "exam_region" fields (docs/scoring.md, "Case
// fields"): defaults, overrides, and every kind of error with its JSON pointer, also as
// parse_case reports them.
#include <gtest/gtest.h>

#include "palpa/io/thresholds.hpp"
#include "palpa/score/score.hpp"  // scoring names the thresholds as its own
#include "score_fixture.hpp"

namespace palpa::score {
namespace {

using nlohmann::json;

Thresholds read(const json& extra, std::vector<io::Problem>& problems) {
  return thresholds_from_case(test::flat_case({}, extra), problems);
}

TEST(ScoreThresholds, DefaultsWithoutScoringFields) {
  std::vector<io::Problem> problems;
  const Thresholds t = thresholds_from_case(test::flat_case(), problems);
  EXPECT_TRUE(problems.empty());
  // The literature defaults (docs/scoring.md): hit within radius + 10 mm, <= 1 false
  // positive, >= 90 % coverage, >= 80 % deep coverage, 7.5 mm pad, 20 % / 50 % cut points.
  EXPECT_DOUBLE_EQ(t.hit_margin, 0.010);
  EXPECT_EQ(t.max_false_positives, 1);
  EXPECT_DOUBLE_EQ(t.min_coverage, 0.90);
  EXPECT_DOUBLE_EQ(t.min_deep_coverage, 0.80);
  EXPECT_DOUBLE_EQ(t.pad_radius, 0.0075);
  EXPECT_DOUBLE_EQ(t.light_max, 0.20);
  EXPECT_DOUBLE_EQ(t.deep_min, 0.50);
  EXPECT_DOUBLE_EQ(t.strip_spacing, 0.015);
  EXPECT_TRUE(t.exam_region.empty());
}

TEST(ScoreThresholds, OverridesOnlyTheGivenKeys) {
  std::vector<io::Problem> problems;
  const Thresholds t = read({{"scoring", {{"min_coverage", 0.8}, {"max_false_positives", 2}, {"weight_pattern", 0},
                                          {"pad_radius", 0.01}, {"max_force", 12.5}}}},
                            problems);
  EXPECT_TRUE(problems.empty());
  EXPECT_DOUBLE_EQ(t.min_coverage, 0.8);
  EXPECT_EQ(t.max_false_positives, 2);
  EXPECT_DOUBLE_EQ(t.weight_pattern, 0.0);
  EXPECT_DOUBLE_EQ(t.pad_radius, 0.01);
  EXPECT_DOUBLE_EQ(t.max_force, 12.5);
  EXPECT_DOUBLE_EQ(t.min_deep_coverage, Thresholds{}.min_deep_coverage);
  EXPECT_DOUBLE_EQ(t.hit_margin, Thresholds{}.hit_margin);
}

TEST(ScoreThresholds, IntegralFloatCountsAsInteger) {
  std::vector<io::Problem> problems;
  const Thresholds t = read({{"scoring", {{"max_false_positives", 3.0}}}}, problems);
  EXPECT_TRUE(problems.empty());
  EXPECT_EQ(t.max_false_positives, 3);
}

struct BadCase {
  json scoring;
  std::string pointer;
  std::string word;
};

TEST(ScoreThresholds, EachErrorNamesItsPointerAndKeepsTheDefault) {
  const std::vector<BadCase> cases = {
      {{{"min_coverage", 1.5}}, "/scoring/min_coverage", "outside"},
      {{{"min_covrage", 0.9}}, "/scoring/min_covrage", "unknown"},
      {{{"pad_radius", 0.0}}, "/scoring/pad_radius", "outside"},
      {{{"hit_margin", 2.0}}, "/scoring/hit_margin", "outside"},
      {{{"max_force", "20"}}, "/scoring/max_force", "number"},
      {{{"max_force", 5000}}, "/scoring/max_force", "outside"},
      {{{"max_false_positives", 1.5}}, "/scoring/max_false_positives", "integer"},
      {{{"max_false_positives", -1}}, "/scoring/max_false_positives", "outside"},
      {{{"expert_coverage", 0.4}}, "/scoring/expert_coverage", "outside"},
      {{{"weight_coverage", -1}}, "/scoring/weight_coverage", "outside"},
      {{{"light_max", 0.6}, {"deep_min", 0.5}}, "/scoring/deep_min", "below"},
      {{{"palpate_ratio_low", 1.4}, {"palpate_ratio_high", 1.2}}, "/scoring/palpate_ratio_high", "above"},
      {{{"weight_sensitivity", 0}, {"weight_false_positives", 0}, {"weight_localization", 0}, {"weight_coverage", 0},
        {"weight_deep_coverage", 0}, {"weight_pattern", 0}, {"weight_pressure", 0}},
       "/scoring",
       "sum"},
      {json::array(), "/scoring", "object"},
  };
  const Thresholds defaults;
  for (const auto& c : cases) {
    std::vector<io::Problem> problems;
    const Thresholds t = read({{"scoring", c.scoring}}, problems);
    ASSERT_EQ(problems.size(), 1u) << c.scoring.dump();
    EXPECT_EQ(problems[0].where, c.pointer) << c.scoring.dump();
    EXPECT_NE(problems[0].reason.find(c.word), std::string::npos) << problems[0].reason;
    // The rejected fields hold their defaults.
    EXPECT_DOUBLE_EQ(t.min_coverage, defaults.min_coverage);
    EXPECT_DOUBLE_EQ(t.pad_radius, defaults.pad_radius);
    EXPECT_DOUBLE_EQ(t.max_force, defaults.max_force);
    EXPECT_EQ(t.max_false_positives, defaults.max_false_positives);
    EXPECT_DOUBLE_EQ(t.light_max, defaults.light_max);
    EXPECT_DOUBLE_EQ(t.deep_min, defaults.deep_min);
    EXPECT_DOUBLE_EQ(t.weight_coverage, defaults.weight_coverage);
  }
}

TEST(ScoreThresholds, ExamRegionParts) {
  std::vector<io::Problem> problems;
  const Thresholds t = read({{"exam_region", {{{"body", "flat"}, {"u", {0.0, 0.5}}}, {{"body", "flat"}, {"u", {0.6, 0.9}}, {"v", {0.1, 0.2}}}}}},
                            problems);
  EXPECT_TRUE(problems.empty());
  ASSERT_EQ(t.exam_region.size(), 2u);
  EXPECT_EQ(t.exam_region[0].body, "flat");
  EXPECT_DOUBLE_EQ(t.exam_region[0].u0, 0.0);
  EXPECT_DOUBLE_EQ(t.exam_region[0].u1, 0.5);
  EXPECT_DOUBLE_EQ(t.exam_region[0].v0, 0.0);  // v left out: the whole range
  EXPECT_DOUBLE_EQ(t.exam_region[0].v1, 1.0);
  EXPECT_DOUBLE_EQ(t.exam_region[1].u0, 0.6);
  EXPECT_DOUBLE_EQ(t.exam_region[1].v1, 0.2);
}

TEST(ScoreThresholds, ExamRegionErrors) {
  const std::vector<std::pair<json, std::string>> cases = {
      {json::array(), "/exam_region"},
      {{{{"body", "nope"}}}, "/exam_region/0/body"},
      {{{{"body", 3}}}, "/exam_region/0/body"},
      {{{{"u", {0.0, 1.0}}}}, "/exam_region/0"},
      {{{{"body", "flat"}, {"u", {0.5, 0.5}}}}, "/exam_region/0/u"},
      {{{{"body", "flat"}, {"v", {-0.1, 0.5}}}}, "/exam_region/0/v"},
      {{{{"body", "flat"}, {"u", {0.2}}}}, "/exam_region/0/u"},
      {{{{"body", "flat"}, {"w", {0.2, 0.4}}}}, "/exam_region/0/w"},
      {{{{"body", "flat"}}, 7}, "/exam_region/1"},
  };
  for (const auto& [region, pointer] : cases) {
    std::vector<io::Problem> problems;
    const Thresholds t = read({{"exam_region", region}}, problems);
    ASSERT_EQ(problems.size(), 1u) << region.dump();
    EXPECT_EQ(problems[0].where, pointer) << region.dump() << ": " << problems[0].reason;
    EXPECT_TRUE(t.exam_region.empty()) << "a bad region leaves the default (whole body)";
  }
}

TEST(ScoreThresholds, ParseCaseRejectsBadScoringFields) {
  const json bad = test::flat_case({}, {{"scoring", {{"min_coverage", 2.0}}}, {"exam_region", {{{"body", "x"}}}}});
  try {
    io::parse_case(bad.dump(), "bad.json");
    FAIL() << "parse_case accepted a bad scoring object";
  } catch (const io::CaseError& e) {
    const auto lines = e.lines();
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[0].rfind("bad.json: /scoring/min_coverage: ", 0), 0u) << lines[0];
    EXPECT_EQ(lines[1].rfind("bad.json: /exam_region/0/body: unknown body", 0), 0u) << lines[1];
  }
  const json good = test::flat_case({}, {{"scoring", {{"min_coverage", 0.8}}}, {"exam_region", {{{"body", "flat"}}}}});
  EXPECT_NO_THROW(io::parse_case(good.dump(), "good.json"));
}

TEST(ScoreThresholds, JsonRoundTrip) {
  Thresholds t;
  t.min_coverage = 0.7;
  t.max_false_positives = 3;
  t.weight_pressure = 0.5;
  t.light_max = 0.1;
  const json scoring = to_json(t);
  EXPECT_EQ(scoring.size(), 22u);  // every Thresholds number
  std::vector<io::Problem> problems;
  const Thresholds back = read({{"scoring", scoring}}, problems);
  EXPECT_TRUE(problems.empty());
  EXPECT_DOUBLE_EQ(back.min_coverage, 0.7);
  EXPECT_EQ(back.max_false_positives, 3);
  EXPECT_DOUBLE_EQ(back.weight_pressure, 0.5);
  EXPECT_DOUBLE_EQ(back.light_max, 0.1);
}

}  // namespace
}  // namespace palpa::score
