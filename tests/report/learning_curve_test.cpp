#include "palpa/report/learning_curve.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "palpa/report/cohort.hpp"
#include "palpa/report/encoding.hpp"
#include "palpa/report/images.hpp"
#include "report_fixture.hpp"

namespace palpa::report {
namespace {

TEST(Cusum, DesignValuesForP0Point1P1Point3) {
  const CusumDesign d;
  // s = ln(9/7) / ln(27/7), h = ln 9 / ln(27/7) (alpha = beta, so h0 = h1), by hand.
  EXPECT_NEAR(d.s(), std::log(9.0 / 7.0) / std::log(27.0 / 7.0), 1e-15);
  EXPECT_NEAR(d.s(), 0.186169, 1e-6);
  EXPECT_NEAR(d.h0(), 1.627662, 1e-6);
  EXPECT_NEAR(d.h1(), 1.627662, 1e-6);
  const CusumDesign asym{0.1, 0.3, 0.05, 0.2};
  EXPECT_NEAR(asym.h0(), std::log(0.95 / 0.2) / std::log(27.0 / 7.0), 1e-12);
  EXPECT_NEAR(asym.h1(), std::log(0.8 / 0.05) / std::log(27.0 / 7.0), 1e-12);
}

TEST(Cusum, PassingEveryAttemptIsAcceptableAtTheNinth) {
  const auto c = failure_cusum(std::vector<bool>(12, true));
  ASSERT_EQ(c.value.size(), 12u);
  const double s = CusumDesign{}.s();
  for (std::size_t i = 0; i < 12; ++i) EXPECT_NEAR(c.value[i], -s * static_cast<double>(i + 1), 1e-12);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(c.signal[i], CusumSignal::None) << i;
  EXPECT_EQ(c.signal[8], CusumSignal::Acceptable);  // 9 s = 1.676 >= h0 = 1.628
  EXPECT_EQ(c.verdict, CusumSignal::Acceptable);
}

TEST(Cusum, TwoFailuresInARowReachTheUpperLimit) {
  const auto c = failure_cusum({false, false});
  EXPECT_EQ(c.signal[0], CusumSignal::None);
  EXPECT_EQ(c.signal[1], CusumSignal::Unacceptable);  // 2 (1 - s) = h1 exactly
  EXPECT_EQ(c.verdict, CusumSignal::Unacceptable);
  EXPECT_EQ(failure_cusum({false, true, false}).verdict, CusumSignal::None);  // 2 - 3 s < h1
  EXPECT_EQ(failure_cusum({}).verdict, CusumSignal::None);
}

TEST(Cusum, EachSignalRestartsTheTest) {
  // Two failures (unacceptable), then nine passes fall h0 below that point.
  std::vector<bool> passed{false, false};
  passed.insert(passed.end(), 9, true);
  const auto c = failure_cusum(passed);
  EXPECT_EQ(c.signal[1], CusumSignal::Unacceptable);
  for (std::size_t i = 2; i < 10; ++i) EXPECT_EQ(c.signal[i], CusumSignal::None) << i;
  EXPECT_EQ(c.signal[10], CusumSignal::Acceptable);
  EXPECT_EQ(c.verdict, CusumSignal::Acceptable);
}

TEST(LearningCurve, TraineeCsvHasOneRowPerAttempt) {
  auto h = testing::synthetic_header();
  std::vector<Attempt> attempts;
  auto s = testing::synthetic_score();
  attempts.push_back(attempt_of(h, s));
  s.passed = true;
  s.score = 0.9;
  h.started_at = "2026-11-23T10:00:00Z";
  h.file = "b,c.palpa";
  attempts.push_back(attempt_of(h, s));
  const auto cusum = failure_cusum({false, true});
  const auto csv = trainee_csv(attempts, cusum);
  const double s1 = 1.0 - CusumDesign{}.s(), s2 = s1 - CusumDesign{}.s();
  const std::string expected =
      "attempt,started_at,file,session_id,score,passed,sensitivity,coverage,deep_coverage,cusum,signal\n"
      "1,2026-11-22T16:40:00Z,sessions/alice-1.palpa,3f2a9c,0.6125,0,0.5,0.4,0.1," + number_text(s1) + ",\n"
      "2,2026-11-23T10:00:00Z,\"b,c.palpa\",3f2a9c,0.9,1,0.5,0.4,0.1," + number_text(s2) + ",\n";
  EXPECT_EQ(csv, expected);
  const auto image = learning_curve_plot("alice", attempts, cusum);
  EXPECT_EQ(image.cols, 900);
  EXPECT_EQ(image.rows, 640);
}

TEST(LearningCurve, TraineeIdsBecomeSafeDistinctFileNames) {
  EXPECT_EQ(trainee_file_stem("alice"), "alice");
  EXPECT_EQ(trainee_file_stem("A.B_c-1"), "A.B_c-1");
  const auto evil = trainee_file_stem("../../etc/passwd");
  EXPECT_EQ(evil.find('/'), std::string::npos);
  EXPECT_NE(evil.front(), '.');
  EXPECT_NE(trainee_file_stem("a b"), trainee_file_stem("a_b"));
  EXPECT_EQ(trainee_file_stem("a b").rfind("a_b-", 0), 0u);
  EXPECT_EQ(trainee_file_stem("a b"), trainee_file_stem("a b"));  // deterministic
  EXPECT_FALSE(trainee_file_stem("").empty());
  EXPECT_LE(trainee_file_stem(std::string(300, 'x')).size(), 64u + 9u);
  EXPECT_EQ(trainee_file_stem("\xC3\xA9t\xC3\xA9").find_first_not_of(
                "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-"),
            std::string::npos);
}

TEST(Cohort, PageListsTraineesVerdictsImagesAndSkippedFiles) {
  TraineeCurve t;
  t.trainee = "<bob>";
  t.file_stem = trainee_file_stem(t.trainee);
  auto s = testing::synthetic_score();
  t.attempts.push_back(attempt_of(testing::synthetic_header(), s));
  s.score = 0.8;
  t.attempts.push_back(attempt_of(testing::synthetic_header(), s));
  t.cusum = failure_cusum({false, false});
  t.png = png_bytes(learning_curve_plot(t.trainee, t.attempts, t.cusum));
  const auto html = cohort_html({t}, {{"bad.palpa", "bad.palpa: meta: not a Palpa session <x>"}});
  EXPECT_EQ(html.find("<bob>"), std::string::npos);
  EXPECT_NE(html.find("&lt;bob&gt;"), std::string::npos);
  EXPECT_NE(html.find("unacceptable"), std::string::npos);
  EXPECT_NE(html.find("0 %"), std::string::npos);      // pass rate
  EXPECT_NE(html.find("70.6"), std::string::npos);     // mean score (61.25 + 80) / 2 = 70.625
  EXPECT_NE(html.find("80.0"), std::string::npos);     // last score
  EXPECT_NE(html.find("data:image/png;base64,"), std::string::npos);
  EXPECT_NE(html.find("bad.palpa: meta: not a Palpa session &lt;x&gt;"), std::string::npos);
}

}  // namespace
}  // namespace palpa::report
