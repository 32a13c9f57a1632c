#include "palpa/report/learning_curve.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "palpa/report/cohort.hpp"
#include "palpa/report/cohort_tables.hpp"
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
  for (std::size_t i = 0; i < 9; ++i) EXPECT_NEAR(c.value[i], -s * static_cast<double>(i + 1), 1e-12);
  for (std::size_t i = 9; i < 12; ++i) EXPECT_NEAR(c.value[i], -s * static_cast<double>(i - 8), 1e-12);  // restarted
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

TEST(Cusum, EachSignalRestartsTheChartAtZero) {
  // Two failures (unacceptable), then nine passes fall h0 below the restart.
  std::vector<bool> passed{false, false};
  passed.insert(passed.end(), 9, true);
  const auto c = failure_cusum(passed);
  EXPECT_EQ(c.signal[1], CusumSignal::Unacceptable);
  for (std::size_t i = 2; i < 10; ++i) EXPECT_EQ(c.signal[i], CusumSignal::None) << i;
  EXPECT_EQ(c.signal[10], CusumSignal::Acceptable);
  EXPECT_EQ(c.verdict, CusumSignal::Acceptable);
  // The values by hand, s = ln(9/7) / ln(27/7): up 1 - s per failure, down s per pass,
  // from 0 again after the signal at attempt 2.
  const double s = std::log(9.0 / 7.0) / std::log(27.0 / 7.0);
  EXPECT_NEAR(c.value[0], 1 - s, 1e-12);
  EXPECT_NEAR(c.value[1], 2 * (1 - s), 1e-12);  // 1.6277: the signal
  for (std::size_t i = 2; i < 11; ++i) EXPECT_NEAR(c.value[i], -s * static_cast<double>(i - 1), 1e-12) << i;
}

TEST(Cusum, RestartedValuesMatchAHandComputedSequence) {
  // F F P P F F: 0.8138, 1.6277 (signal, restart), -0.1862, -0.3723, 0.4415, 1.2553.
  const auto c = failure_cusum({false, false, true, true, false, false});
  const std::vector<double> expected{0.81383106, 1.62766212, -0.18616894, -0.37233788, 0.44149318, 1.25532424};
  ASSERT_EQ(c.value.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(c.value[i], expected[i], 1e-8) << i;
  EXPECT_EQ(c.signal[5], CusumSignal::None);  // 1.2553 < h1: the restart forgot the first two failures
  EXPECT_EQ(cusum_words(c), "failure rate probably above 30 % (attempt 2)");
  EXPECT_EQ(cusum_words(failure_cusum({true})), "no signal yet");
}

TEST(Cusum, CaptionSaysTheStepsAndLimitsInWords) {
  EXPECT_EQ(cusum_caption(),
            "Each failure raises the line by 0.81, each pass lowers it by 0.19; touching the upper line (1.63) means "
            "the failure rate is probably above 30 %, touching the lower line (-1.63) that it is probably below 10 % "
            "(each wrong about 10 times in 100); the line then restarts at 0.");
}

std::vector<bool> attempts_of(const std::string& pf) {
  std::vector<bool> v;
  for (const char c : pf) v.push_back(c == 'P');
  return v;
}

TEST(Proficiency, LastThreePassedIsProficientWhateverCameBefore) {
  const auto p = proficiency(attempts_of("FFFFFFPPP"));
  EXPECT_TRUE(p.now());
  EXPECT_EQ(p.headline(), "proficient since attempt 9");
  for (std::size_t i = 0; i < 8; ++i) EXPECT_FALSE(p.proficient[i]) << i;
  EXPECT_EQ(p.verdict[7], "not yet: 2 of the last 5 passed");  // F F F P P
  // The CUSUM alone would still call her failure rate unacceptable.
  EXPECT_EQ(failure_cusum(attempts_of("FFFFFFPPP")).verdict, CusumSignal::Unacceptable);
}

TEST(Proficiency, FiveOfFiveIsProficientFromTheThird) {
  const auto p = proficiency(attempts_of("PPPPP"));
  EXPECT_EQ(p.proficient, (std::vector<bool>{false, false, true, true, true}));
  EXPECT_EQ(p.headline(), "proficient since attempt 3");
  EXPECT_EQ(p.verdict[0], "not yet: 1 of 1 passed");
  EXPECT_EQ(p.verdict[1], "not yet: 2 of 2 passed");
  EXPECT_EQ(failure_cusum(attempts_of("PPPPP")).verdict, CusumSignal::None);  // "undecided" before
}

TEST(Proficiency, TwoPassesAfterAFailureAreNotYet) {
  const auto p = proficiency(attempts_of("FPP"));
  EXPECT_FALSE(p.now());
  EXPECT_EQ(p.headline(), "not yet: 2 of 3 passed");
}

TEST(Proficiency, AFailureEndsItAndThreeNewPassesRegainIt) {
  // Proficient at attempts 4-9, failed attempt 10.
  const auto p = proficiency(attempts_of("FPPPPPPPPFPP"));
  EXPECT_EQ(p.verdict[8], "proficient since attempt 4");
  EXPECT_EQ(p.verdict[9], "proficient at attempts 4-9; failed attempt 10: not yet again (4 of the last 5 passed)");
  EXPECT_EQ(p.headline(), "proficient at attempts 4-9; failed attempt 10: not yet again (4 of the last 5 passed)");
  const auto back = proficiency(attempts_of("FPPPPPPPPFPPP"));
  EXPECT_EQ(back.headline(), "proficient since attempt 13");
  EXPECT_EQ(proficiency(attempts_of("PPPF")).headline(),
            "proficient at attempt 3; failed attempt 4: not yet again (3 of 4 passed)");
  EXPECT_EQ(proficiency({}).headline(), "no attempts");
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
  h.station = "room 2";
  attempts.push_back(attempt_of(h, s));
  const auto cusum = failure_cusum({false, true});
  const auto csv = trainee_csv(attempts, cusum, proficiency({false, true}));
  // cusum 1 - s = 0.8138 -> 0.81, then 1 - 2 s = 0.6277 -> 0.63; score 0.6125 -> 0.613, 61.3 of 100.
  const std::string expected =
      "attempt,started_at,file,session_id,score,passed,sensitivity,coverage,deep_coverage,cusum,signal,"
      "score_100,proficient,verdict,station\n"
      "1,2026-11-22T16:40:00Z,sessions/alice-1.palpa,3f2a9c,0.613,0,0.500,0.400,0.100,0.81,,61.3,0,"
      "not yet: 0 of 1 passed,\n"
      "2,2026-11-23T10:00:00Z,\"b,c.palpa\",3f2a9c,0.900,1,0.500,0.400,0.100,0.63,,90.0,0,"
      "not yet: 1 of 2 passed,room 2\n";
  EXPECT_EQ(csv, expected);
  const auto image = learning_curve_plot("alice", attempts, cusum, proficiency({false, true}));
  EXPECT_EQ(image.cols, 900);
  EXPECT_EQ(image.rows, 640);
}

TEST(LearningCurve, TraineeIdsBecomeSafeDistinctFileNames) {
  // "alice" and 16 hex digits of SHA-1("alice") = 522b276a356bdf39013dfabea2cd43e141ecc9e8
  EXPECT_EQ(trainee_file_stem("alice"), "alice-522b276a356bdf39");
  EXPECT_EQ(trainee_file_stem("A.B_c-1").rfind("A.B_c-1-", 0), 0u);
  // Names a station could pick to meet another's file: the sanitized form with the other's
  // hash, or the same letters in another case.
  const auto victim = trainee_file_stem("al ice");
  EXPECT_NE(trainee_file_stem("al_ice-" + victim.substr(victim.size() - 16)), victim);
  EXPECT_NE(trainee_file_stem("al_ice-" + victim.substr(victim.size() - 8)), victim);
  EXPECT_NE(trainee_file_stem("Alice"), trainee_file_stem("alice"));
  const auto evil = trainee_file_stem("../../etc/passwd");
  EXPECT_EQ(evil.find('/'), std::string::npos);
  EXPECT_NE(evil.front(), '.');
  EXPECT_NE(trainee_file_stem("a b"), trainee_file_stem("a_b"));
  EXPECT_EQ(trainee_file_stem("a b").rfind("a_b-", 0), 0u);
  EXPECT_EQ(trainee_file_stem("a b"), trainee_file_stem("a b"));  // deterministic
  EXPECT_FALSE(trainee_file_stem("").empty());
  EXPECT_EQ(trainee_file_stem(std::string(300, 'x')).size(), 48u + 17u);
  EXPECT_NE(trainee_file_stem(std::string(300, 'x')), trainee_file_stem(std::string(301, 'x')));
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
  t.proficiency = proficiency({false, false});
  t.png = png_bytes(learning_curve_plot(t.trainee, t.attempts, t.cusum, t.proficiency));
  const auto html = cohort_html({t}, {{"bad.palpa", "bad.palpa: meta: not a Palpa session <x>"}});
  EXPECT_EQ(html.find("<bob>"), std::string::npos);
  EXPECT_NE(html.find("&lt;bob&gt;"), std::string::npos);
  EXPECT_NE(html.find("not yet: 0 of 2 passed"), std::string::npos);
  EXPECT_NE(html.find("failure rate probably above 30 % (attempt 2)"), std::string::npos);
  EXPECT_NE(html.find("0 of 2"), std::string::npos);   // passed
  EXPECT_NE(html.find("70.6"), std::string::npos);     // mean score (61.25 + 80) / 2 = 70.625
  EXPECT_NE(html.find("80.0"), std::string::npos);     // last score
  EXPECT_NE(html.find("Covers every session given."), std::string::npos);
  EXPECT_NE(html.find("the line then restarts at 0."), std::string::npos);
  EXPECT_EQ(html.find("p0 ="), std::string::npos);     // the chart in words, not in symbols
  EXPECT_EQ(html.find("h1 ="), std::string::npos);
  EXPECT_NE(html.find("data:image/png;base64,"), std::string::npos);
  EXPECT_NE(html.find("bad.palpa: meta: not a Palpa session &lt;x&gt;"), std::string::npos);
}

TEST(Cohort, AProficientTraineeIsSaidSoAndTheSelectionIsNamed) {
  TraineeCurve t;
  t.trainee = "dana";
  t.file_stem = "dana";
  const auto passed = attempts_of("FFFFFFPPP");
  for (const bool ok : passed) {
    auto s = testing::synthetic_score();
    s.passed = ok;
    t.attempts.push_back(attempt_of(testing::synthetic_header(), s));
  }
  t.cusum = failure_cusum(passed);
  t.proficiency = proficiency(passed);
  const auto html = cohort_html({t}, {}, "sessions from 2026-11-01 to 2026-11-30, case default");
  EXPECT_NE(html.find("<td class=\"ok\">proficient since attempt 9</td>"), std::string::npos);
  EXPECT_NE(html.find("<h2 id=\"t-dana\">dana: proficient since attempt 9</h2>"), std::string::npos);
  EXPECT_NE(html.find("Covers sessions from 2026-11-01 to 2026-11-30, case default."), std::string::npos);
}

TEST(CaseFileStem, SlugIdsKeepTheirSlugAndAllCarryAHash) {
  EXPECT_EQ(case_file_stem("urn:palpa:case:default").rfind("default-", 0), 0u);
  EXPECT_NE(case_file_stem("default"), case_file_stem("urn:palpa:case:default"));  // never the same file
  EXPECT_EQ(case_file_stem("default").rfind("default-", 0), 0u);
  // An id made to look like another's stem does not meet it.
  const auto other = case_file_stem("default");
  EXPECT_NE(case_file_stem("urn:palpa:case:" + other), other);
  EXPECT_NE(case_file_stem("urn:palpa:case:a b"), case_file_stem("urn:palpa:case:a_b"));
  EXPECT_EQ(case_file_stem("urn:palpa:case:../x").find('/'), std::string::npos);
  EXPECT_NE(case_file_stem("urn:palpa:case:../x").front(), '.');
  EXPECT_FALSE(case_file_stem("").empty());
}

SessionHeader header_at(const std::string& trainee, const std::string& case_id, const std::string& station) {
  auto h = testing::synthetic_header();
  h.trainee = trainee;
  h.case_id = case_id;
  h.case_title = case_id + " title";
  h.station = station;
  return h;
}

TEST(GroupSummaries, CountPassRateMedianAndProficientTraineesPerCaseAndStation) {
  const std::vector<SessionHeader> h{header_at("ann", "c1", "s1"), header_at("ann", "c1", "s2"),
                                     header_at("ben", "c1", "s1"), header_at("ben", "c2", "s1"),
                                     header_at("cal", "c2", "")};
  // ann passes c1 twice, ben fails c1 and abandons c2, cal passes c2.
  const std::vector<SessionFacts> facts{{&h[0], 0.8, true, false}, {&h[1], 0.9, true, false},
                                        {&h[2], 0.4, false, false}, {&h[3], 0.0, false, true},
                                        {&h[4], 0.7, true, false}};
  const ProficientPairs proficient{{"ann", "c1"}, {"cal", "c2"}};
  const auto cases = case_summaries(facts, proficient);
  ASSERT_EQ(cases.size(), 2u);
  EXPECT_EQ(cases[0].key, "c1");
  EXPECT_EQ(cases[0].name, "c1 title");
  EXPECT_EQ(cases[0].sessions, 3u);
  EXPECT_EQ(cases[0].scored, 3u);
  EXPECT_EQ(cases[0].passed, 2u);
  EXPECT_DOUBLE_EQ(cases[0].median_score_100, 80.0);
  EXPECT_EQ(cases[0].trainees, 2u);
  EXPECT_EQ(cases[0].proficient_trainees, 1u);
  EXPECT_EQ(cases[1].scored, 1u);  // the abandoned attempt has no exam
  EXPECT_DOUBLE_EQ(cases[1].median_score_100, 70.0);
  const auto stations = station_summaries(facts, proficient);
  ASSERT_EQ(stations.size(), 3u);
  EXPECT_EQ(stations[0].key, "");  // not recorded sorts first
  EXPECT_EQ(stations[1].key, "s1");
  EXPECT_EQ(stations[1].sessions, 3u);
  EXPECT_DOUBLE_EQ(stations[1].median_score_100, 60.0);  // (40 + 80) / 2; the abandoned one left out
  EXPECT_EQ(stations[1].proficient_trainees, 1u);         // ann (c1), not ben
  EXPECT_EQ(cases_csv(cases),
            "case_id,case,sessions,scored,passed,pass_rate,median_score_100,trainees,proficient_trainees\n"
            "c1,c1 title,3,3,2,0.667,80.0,2,1\nc2,c2 title,2,1,1,1.000,70.0,2,1\n");
  EXPECT_EQ(stations_csv(stations).substr(0, stations_csv(stations).find('\n')),
            "station,sessions,scored,passed,pass_rate,median_score_100,trainees,proficient_trainees");
}

TEST(LeftOutNotes, NameTheSessionsAndTheOptionThatIncludesThem) {
  EXPECT_TRUE(left_out_notes({}).empty());
  LeftOut l;
  l.by_mode = {{"scripted", 12}, {"replay\x1b[2J", 1}};
  l.abandoned = 3;
  l.filtered = 2;
  l.filter = "sessions of trainee dana";
  l.filter_options = "--trainee";
  const auto notes = left_out_notes(l);
  ASSERT_EQ(notes.size(), 3u);
  EXPECT_EQ(notes[0], "1 replay\\x1b[2J, 12 scripted sessions are not in the learning curves: only trainee "
                      "exercises count; give --all-modes to include them.");
  EXPECT_EQ(notes[1], "3 abandoned attempts are not in the learning curves; give --include-abandoned to include them.");
  EXPECT_EQ(notes[2], "2 sessions are outside the selection (sessions of trainee dana) and in no output; run "
                      "without --trainee to include them.");
}

TEST(Cohort, UntrustedTextIsEscapedAndShortenedWithTheWholeValueInTheTitle) {
  TraineeCurve t;
  t.trainee = "\xE2\x80\xAE" "eve\x1b[31m" + std::string(1000, 'x');
  t.file_stem = trainee_file_stem(t.trainee);
  t.attempts.push_back(attempt_of(testing::synthetic_header(), testing::synthetic_score()));
  CohortPage page;
  page.trainees = {t};
  page.sessions = {{t.trainee, "2026-11-01T09:00:00Z", "failed", relative_href("sessions", "a b#?", ".html")}};
  page.notes = {"3 scripted sessions are not in the learning curves"};
  const auto html = cohort_html(page);
  EXPECT_EQ(html.find('\x1b'), std::string::npos);
  EXPECT_EQ(html.find("\xE2\x80\xAE"), std::string::npos);
  const std::string cell = "\\u{202e}eve\\x1b[31m" + std::string(60 - 9, 'x') + "\xE2\x80\xA6</span>";
  EXPECT_NE(html.find(cell), std::string::npos);  // 60 characters shown, then "…"
  EXPECT_NE(html.find("title=\"\\u{202e}eve\\x1b[31m" + std::string(1000, 'x') + "\""), std::string::npos);
  EXPECT_NE(html.find("overflow-wrap:anywhere"), std::string::npos);
  EXPECT_NE(html.find("href=\"sessions/a%20b%23%3F.html\""), std::string::npos);
  EXPECT_NE(html.find("<p class=\"note\">3 scripted sessions are not in the learning curves</p>"), std::string::npos);
}

}  // namespace
}  // namespace palpa::report
