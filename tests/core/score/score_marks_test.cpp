// Marks against tumours on the flat case, where the top contour is z = R(x, y) over the
// skeleton plane z = 0 (so a point's top-contour point is (x, y, R(x, y))): hits,
// localization error, duplicates, false positives and the greedy matching.
#include <gtest/gtest.h>

#include <cmath>

#include "palpa/score/score.hpp"
#include "score_fixture.hpp"

namespace palpa::score {
namespace {

using test::flat_radius;

// One tumour 10 mm across, centre at (10, 0, 5) mm: its top-contour point is
// (10, 0, R(10 mm, 0)) = (10, 0, 19.2) mm.
const std::array<double, 4> kTumour{0.010, 0.0, 0.005, 0.005};

Score with_marks(const std::vector<std::array<double, 4>>& tumours, const std::vector<std::array<double, 2>>& marks) {
  test::SessionBuilder b(test::flat_case(tumours));
  b.flat_contact(0.0, 0.0, 0.001, 1.0);
  std::int64_t id = 1;
  for (const auto& m : marks) b.mark(id++, m[0], m[1]);
  b.flat_contact(0.0, 0.0, 0.001, 1.0);
  return score_session(b.finish(), "marks.session");
}

TEST(ScoreMarks, MarkAboveTheTumourHitsWithZeroError) {
  const Score s = with_marks({kTumour}, {{0.010, 0.0}});
  ASSERT_EQ(s.tumours.size(), 1u);
  EXPECT_TRUE(s.tumours[0].found);
  EXPECT_EQ(s.tumours[0].mark, 1);
  ASSERT_EQ(s.localization_error_mm.size(), 1u);
  EXPECT_NEAR(s.localization_error_mm[0], 0.0, 1e-3);
  EXPECT_DOUBLE_EQ(s.sensitivity, 1.0);
  EXPECT_EQ(s.false_positives, 0);
  ASSERT_EQ(s.marks.size(), 1u);
  EXPECT_EQ(s.marks[0].tumour, 0);
  EXPECT_FALSE(s.marks[0].duplicate);
}

TEST(ScoreMarks, MarkFiveMillimetresOff) {
  const Score s = with_marks({kTumour}, {{0.015, 0.0}});
  // Top points (15, 0, R(15, 0)) and (10, 0, R(10, 0)) mm: 5 mm apart in x, 1 mm in z.
  const double expected = 1000.0 * std::hypot(0.005, flat_radius(0.015, 0.0) - flat_radius(0.010, 0.0));
  EXPECT_NEAR(expected, 5.099, 1e-3);
  ASSERT_TRUE(s.tumours[0].found);
  EXPECT_NEAR(s.localization_error_mm[0], expected, 0.01);
  EXPECT_NEAR(s.marks[0].nearest_mm, expected, 0.01);
  // Localization sub-score: 1 at 0 mm, 0 at radius + hit margin = 15 mm.
  EXPECT_NEAR(s.subscores[2].value, 1.0 - expected / 15.0, 1e-3);
  EXPECT_EQ(s.subscores[2].name, "localization");
}

TEST(ScoreMarks, FarMarkIsAFalsePositiveAndTheTumourIsMissed) {
  const Score s = with_marks({kTumour}, {{-0.03, -0.03}});
  EXPECT_FALSE(s.tumours[0].found);
  EXPECT_EQ(s.false_positives, 1);
  EXPECT_DOUBLE_EQ(s.sensitivity, 0.0);
  EXPECT_TRUE(s.localization_error_mm.empty());
  EXPECT_EQ(s.marks[0].tumour, -1);
  EXPECT_FALSE(s.marks[0].duplicate);
  const double nearest = 1000.0 * std::sqrt(0.04 * 0.04 + 0.03 * 0.03 +
                                            std::pow(flat_radius(-0.03, -0.03) - flat_radius(0.01, 0.0), 2));
  EXPECT_NEAR(s.marks[0].nearest_mm, nearest, 0.01);
  // The sensitivity gate fails and says which mass was missed: 10 mm across, its centre
  // 19.2 - 5 = 14.2 mm below the top contour.
  ASSERT_EQ(s.gates[0].name, "sensitivity");
  EXPECT_FALSE(s.gates[0].passed);
  EXPECT_NE(s.gates[0].message.find("Found 0 of 1 tumours"), std::string::npos) << s.gates[0].message;
  EXPECT_NE(s.gates[0].message.find("the 10 mm mass 14 mm deep"), std::string::npos) << s.gates[0].message;
  EXPECT_NE(s.gates[0].message.find("missed"), std::string::npos);
  // One false positive is allowed by default; the localization sub-score is 0.
  EXPECT_TRUE(s.gates[1].passed);
  EXPECT_DOUBLE_EQ(s.subscores[2].value, 0.0);
  EXPECT_FALSE(s.passed);
}

TEST(ScoreMarks, SecondMarkOnAFoundTumourIsADuplicate) {
  const Score s = with_marks({kTumour}, {{0.014, 0.0}, {0.011, 0.0}});
  ASSERT_EQ(s.marks.size(), 2u);
  // The closer mark (1 mm) finds it, whatever the order they were placed in.
  EXPECT_EQ(s.tumours[0].mark, 2);
  EXPECT_TRUE(s.marks[0].duplicate);
  EXPECT_EQ(s.marks[0].tumour, -1);
  EXPECT_FALSE(s.marks[1].duplicate);
  EXPECT_EQ(s.false_positives, 0);
  EXPECT_NEAR(s.localization_error_mm[0],
              1000.0 * std::hypot(0.001, flat_radius(0.011, 0.0) - flat_radius(0.010, 0.0)), 0.01);
}

TEST(ScoreMarks, GreedyMatchingFindsBothTumours) {
  // Tumours at x = 0 and 12 mm (6 mm across: reach 13 mm). Mark A at 6.5 mm is nearer the
  // second tumour (5.5 mm) than the first (6.5 mm), but mark B at 13 mm is nearer still
  // to the second (1 mm): matching by increasing distance gives B the second, A the first.
  const Score s = with_marks({{0.0, 0.0, 0.005, 0.003}, {0.012, 0.0, 0.005, 0.003}}, {{0.0065, 0.0}, {0.013, 0.0}});
  ASSERT_EQ(s.tumours.size(), 2u);
  EXPECT_TRUE(s.tumours[0].found);
  EXPECT_TRUE(s.tumours[1].found);
  EXPECT_EQ(s.tumours[0].mark, 1);
  EXPECT_EQ(s.tumours[1].mark, 2);
  EXPECT_EQ(s.false_positives, 0);
  EXPECT_DOUBLE_EQ(s.sensitivity, 1.0);
  ASSERT_EQ(s.localization_error_mm.size(), 2u);
  EXPECT_NEAR(s.localization_error_mm[0], 1000.0 * std::hypot(0.0065, flat_radius(0.0065, 0) - flat_radius(0, 0)),
              0.01);
}

TEST(ScoreMarks, UnmarkedMarksDoNotCount) {
  test::SessionBuilder b(test::flat_case({kTumour}));
  b.flat_contact(0.0, 0.0, 0.001, 1.0);
  b.mark(1, -0.03, -0.03);
  b.mark(2, 0.010, 0.0);
  b.event(session::EventKind::Unmark, 1);
  b.flat_contact(0.0, 0.0, 0.001, 1.0);
  const Score s = score_session(b.finish(), "unmark.session");
  ASSERT_EQ(s.marks.size(), 1u);
  EXPECT_EQ(s.marks[0].id, 2);
  EXPECT_EQ(s.false_positives, 0);
  EXPECT_TRUE(s.tumours[0].found);
}

TEST(ScoreMarks, SmallTumourIsNotDetectable) {
  // 2 mm across, below the 3 mm detectable diameter: not needed for the sensitivity gate.
  const Score s = with_marks({{0.0, 0.0, 0.005, 0.001}}, {});
  ASSERT_EQ(s.tumours.size(), 1u);
  EXPECT_FALSE(s.tumours[0].detectable);
  EXPECT_DOUBLE_EQ(s.sensitivity, 1.0);
  EXPECT_TRUE(s.gates[0].passed);
  bool noted = false;
  for (const auto& n : s.notes) noted = noted || n.find("detectable size") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST(ScoreMarks, TooManyFalsePositivesFailTheGate) {
  const Score s = with_marks({kTumour}, {{0.010, 0.0}, {-0.03, -0.03}, {-0.03, 0.03}});
  EXPECT_EQ(s.false_positives, 2);
  EXPECT_FALSE(s.gates[1].passed);
  EXPECT_EQ(s.gates[1].name, "false_positives");
  // 1 for none, 0 at 2 * max + 2 = 4: two false marks give 0.5.
  EXPECT_DOUBLE_EQ(s.subscores[1].value, 0.5);
}

}  // namespace
}  // namespace palpa::score
