// One number, one rounding (palpa/score/figures.hpp): what the card, the CLI, the HTML
// report and review show, and what the gates judge.
#include <gtest/gtest.h>

#include "palpa/score/figures.hpp"
#include "palpa/score/score.hpp"

namespace palpa::score {
namespace {

TEST(ScoreFigures, PercentIsOneDecimalRoundedDown) {
  EXPECT_EQ(percent_text(0.8995), "89.9%");
  EXPECT_EQ(percent_text(0.7999), "79.9%");
  EXPECT_EQ(percent_text(0.9), "90.0%");    // 0.9 is 0.8999... in binary: still 90.0
  EXPECT_EQ(percent_text(0.95), "95.0%");
  EXPECT_EQ(percent_text(1.0), "100.0%");
  EXPECT_EQ(percent_text(0.0), "0.0%");
  EXPECT_DOUBLE_EQ(shown_percent(0.91), 91.0);
}

TEST(ScoreFigures, ForceIsOneDecimalRoundedUp) {
  EXPECT_EQ(force_text(20.01), "20.1 N");
  EXPECT_EQ(force_text(20.0), "20.0 N");
  EXPECT_EQ(force_text(5.0), "5.0 N");
  EXPECT_EQ(force_text(4.96), "5.0 N");
}

TEST(ScoreFigures, MillimetresRoundToNearest) {
  EXPECT_EQ(mm_text(3.24), "3.2 mm");
  EXPECT_EQ(mm_text(3.26), "3.3 mm");
}

TEST(ScoreFigures, GateTextsByKind) {
  const Gate coverage{"coverage", false, 0.8995, 0.9, ""};
  EXPECT_EQ(gate_value_text(coverage), "89.9%");
  EXPECT_EQ(gate_threshold_text(coverage), "90.0%");
  const Gate safety{"safety", true, 12.34, 20.0, ""};
  EXPECT_EQ(gate_value_text(safety), "12.4 N");
  const Gate fp{"false_positives", true, 2.0, 2.0, ""};
  EXPECT_EQ(gate_value_text(fp), "2");
}

// The summary the card and palpa-cli score print uses the same figures as the gate lines.
TEST(ScoreFigures, SummaryShowsTheGateFigure) {
  Score s;
  s.coverage = 0.8995;
  s.deep_coverage = 0.7996;
  s.peak_force_n = 19.951;
  s.gates.push_back({"coverage", false, s.coverage, 0.9, "Covered 89.9% of the exam region (90.0% needed)."});
  const std::string text = summary_text(s);
  EXPECT_NE(text.find("coverage          89.9% (deep 79.9%)"), std::string::npos) << text;
  EXPECT_NE(text.find("peak force        20.0 N"), std::string::npos) << text;
  EXPECT_EQ(text.find("90%"), std::string::npos) << text;
}

}  // namespace
}  // namespace palpa::score
