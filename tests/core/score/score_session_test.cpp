// Whole-session measures on the flat case (local thickness 2 R(x, y), R = 20 mm at the
// centre): pressure levels, active time with pauses and faults, peak force and safety,
// the palpate/search force ratio, gates, sub-scores, notes and the JSON result.
#include <gtest/gtest.h>

#include <cmath>

#include "palpa/score/score.hpp"
#include "score_fixture.hpp"

namespace palpa::score {
namespace {

using session::EventKind;
using test::flat_radius;

const Gate& gate(const Score& s, const std::string& name) {
  for (const auto& g : s.gates)
    if (g.name == name) return g;
  throw std::runtime_error("no gate " + name);
}

bool has_note(const Score& s, const std::string& text) {
  for (const auto& n : s.notes)
    if (n.find(text) != std::string::npos) return true;
  return false;
}

TEST(ScoreSession, PressureLevelsByDepthOverLocalThickness) {
  test::SessionBuilder b(test::flat_case());
  // Centre: thickness 40 mm. 4 mm = 0.1 light, 12 mm = 0.3 medium, 24 mm = 0.6 deep.
  for (int k = 0; k < 1000; ++k) b.flat_contact(0.0, 0.0, 0.004, 2.0);
  for (int k = 0; k < 2000; ++k) b.flat_contact(0.0, 0.0, 0.012, 4.0);
  for (int k = 0; k < 3000; ++k) b.flat_contact(0.0, 0.0, 0.024, 8.0);
  // 7 mm is light at the centre (0.175) but medium at x = 25 mm, where R = 15 mm (0.233).
  for (int k = 0; k < 500; ++k) b.flat_contact(0.0, 0.0, 0.007, 3.0);
  for (int k = 0; k < 700; ++k) b.flat_contact(0.025, 0.0, 0.007, 3.0);
  const Score s = score_session(b.finish(), "pressure.session");
  EXPECT_NEAR(s.pressure.light_s, 1.5, 1e-6);
  EXPECT_NEAR(s.pressure.medium_s, 2.7, 1e-6);
  EXPECT_NEAR(s.pressure.deep_s, 3.0, 1e-6);
  EXPECT_NEAR(s.contact_time_s, 7.2, 1e-6);
  // Every level has at least 10 % of the contact time: full pressure sub-score.
  EXPECT_EQ(s.subscores[6].name, "pressure");
  EXPECT_DOUBLE_EQ(s.subscores[6].value, 1.0);
}

TEST(ScoreSession, PressureSubScoreCreditsEachLevelUpToTenPercent) {
  test::SessionBuilder b(test::flat_case());
  for (int k = 0; k < 950; ++k) b.flat_contact(0.0, 0.0, 0.004, 2.0);  // light 95 %
  for (int k = 0; k < 50; ++k) b.flat_contact(0.0, 0.0, 0.012, 2.0);   // medium 5 %
  const Score s = score_session(b.finish(), "pressure.session");
  EXPECT_NEAR(s.subscores[6].value, (1.0 + 0.5 + 0.0) / 3.0, 1e-9);
}

TEST(ScoreSession, DurationIsActiveTimeWithoutPauses) {
  // 100 Hz, contact throughout: start 0, pause 10 s, resume 15 s, end 70 s.
  test::SessionBuilder b(test::flat_case(), 100.0);
  for (int k = 0; k < 7000; ++k) {
    if (k == 1000) b.event(EventKind::Pause);
    if (k == 1500) b.event(EventKind::Resume);
    b.flat_contact(0.0, 0.0, 0.004, 2.0);
  }
  const Score s = score_session(b.finish(), "pause.session");
  EXPECT_NEAR(s.duration_s, 65.0, 1e-9);
  EXPECT_NEAR(s.contact_time_s, 65.0, 1e-9);  // samples while paused do not count
  EXPECT_FALSE(s.short_exam);                 // >= 60 s
  EXPECT_FALSE(has_note(s, "short exam"));
}

TEST(ScoreSession, FaultSamplesAndGapsDoNotCount) {
  test::SessionBuilder b(test::flat_case(), 100.0);
  for (int k = 0; k < 1000; ++k) b.flat_contact(0.0, 0.0, 0.004, 2.0);
  for (int k = 0; k < 500; ++k) b.air(0.0, true);
  for (int k = 0; k < 1000; ++k) b.flat_contact(0.0, 0.0, 0.004, 2.0);
  session::Session s = b.finish();
  // A 5 s hole in the recording: the sample before it counts for at most 2 ticks.
  for (std::size_t k = 2000; k < s.samples.size(); ++k) s.samples[k].t += 5.0;
  s.events.back().t += 5.0;
  const Score r = score_session(s, "fault.session");
  EXPECT_NEAR(r.contact_time_s, 20.0 + 0.01, 1e-9);
  EXPECT_NEAR(r.duration_s, 30.0, 1e-9);
  EXPECT_TRUE(r.short_exam);
  EXPECT_TRUE(has_note(r, "short exam: 30 s"));
}

TEST(ScoreSession, IncompleteSessionEndsAtItsLastSample) {
  test::SessionBuilder b(test::flat_case(), 100.0);
  for (int k = 0; k < 1235; ++k) b.flat_contact(0.0, 0.0, 0.004, 2.0);
  const Score s = score_session(b.finish(false), "crash.session");
  EXPECT_FALSE(s.complete);
  EXPECT_NEAR(s.duration_s, 12.34, 1e-9);
  EXPECT_TRUE(has_note(s, "session incomplete")) << s.notes.front();
  EXPECT_TRUE(has_note(s, "t = 12.3 s"));
  EXPECT_EQ(s.samples, 1235u);
}

TEST(ScoreSession, PeakForceAndSafetyGate) {
  for (double peak : {15.0, 25.0}) {
    test::SessionBuilder b(test::flat_case());
    for (int k = 0; k < 100; ++k) b.flat_contact(0.0, 0.0, 0.004, 5.0);
    b.flat_contact(0.0, 0.0, 0.02, peak);
    b.air(3.0);
    const Score s = score_session(b.finish(), "force.session");
    EXPECT_DOUBLE_EQ(s.peak_force_n, peak);
    EXPECT_EQ(s.safe, peak <= 20.0);
    EXPECT_EQ(gate(s, "safety").passed, peak <= 20.0);
    EXPECT_DOUBLE_EQ(gate(s, "safety").threshold, 20.0);
    if (peak > 20.0) {
      EXPECT_FALSE(s.passed);
      EXPECT_NE(gate(s, "safety").message.find("25.0 N"), std::string::npos) << gate(s, "safety").message;
    }
  }
}

TEST(ScoreSession, PalpateSearchRatio) {
  test::SessionBuilder b(test::flat_case());
  b.mark(1, 0.01, 0.0);
  // 6 N within the 10 mm palpate radius of the mark (top-contour distance), 5 N elsewhere.
  for (int k = 0; k < 300; ++k) b.flat_contact(0.012, 0.003, 0.004, 6.0);
  for (int k = 0; k < 700; ++k) b.flat_contact(-0.03, -0.02, 0.004, 5.0);
  for (int k = 0; k < 100; ++k) b.flat_contact(0.01, 0.0, 0.004, 6.0);
  const Score s = score_session(b.finish(), "ratio.session");
  EXPECT_NEAR(s.palpate_search_ratio, 1.2, 1e-9);
  EXPECT_FALSE(has_note(s, "palpate/search"));  // inside the 1.1-1.3 band
}

TEST(ScoreSession, PalpateSearchRatioUndefinedWithoutMarks) {
  test::SessionBuilder b(test::flat_case());
  for (int k = 0; k < 100; ++k) b.flat_contact(0.0, 0.0, 0.004, 5.0);
  EXPECT_DOUBLE_EQ(score_session(b.finish(), "ratio.session").palpate_search_ratio, 0.0);
}

// A complete, good exam: the tumour found 1 mm off, a raster over the whole dome at deep
// pressure, below the force limit, for 64 s.
session::Session good_exam() {
  test::SessionBuilder b(test::flat_case({{0.010, 0.0, 0.005, 0.005}}), 100.0);
  for (int strip = 0; strip <= 9; ++strip) {
    const double x = -0.045 + 0.01 * strip;
    for (int k = 0; k <= 640; ++k) {
      const double a = k / 640.0;
      const double y = strip % 2 == 0 ? -0.045 + 0.09 * a : 0.045 - 0.09 * a;
      b.flat_contact(x, y, 0.6 * 2 * flat_radius(x, y), 8.0);
    }
  }
  b.mark(1, 0.011, 0.0);
  return b.finish();
}

TEST(ScoreSession, GoodExamPassesEveryGate) {
  const Score s = score_session(good_exam(), "good.session");
  ASSERT_EQ(s.gates.size(), 5u);
  for (const auto& g : s.gates) EXPECT_TRUE(g.passed) << g.name << ": " << g.message;
  EXPECT_TRUE(s.passed);
  EXPECT_EQ(gate(s, "sensitivity").message, "Found 1 of 1 tumours.");
  EXPECT_FALSE(s.short_exam);
  // Sub-scores by hand: everything full except localization (1 - 1.0 mm / 15 mm) and
  // pressure (deep only: 1/3); the pattern is efficient (strips, no revisits).
  EXPECT_EQ(to_string(s.pattern.kind), "efficient");
  const double loc = 1.0 - std::hypot(0.001, flat_radius(0.011, 0) - flat_radius(0.010, 0)) / 0.015;
  const std::vector<std::pair<std::string, double>> expected = {
      {"sensitivity", 1.0}, {"false_positives", 1.0}, {"localization", loc}, {"coverage", 1.0},
      {"deep_coverage", 1.0}, {"pattern", 1.0}, {"pressure", 1.0 / 3.0}};
  ASSERT_EQ(s.subscores.size(), expected.size());
  double total = 0.0, weights = 0.0;
  for (std::size_t k = 0; k < expected.size(); ++k) {
    EXPECT_EQ(s.subscores[k].name, expected[k].first);
    EXPECT_NEAR(s.subscores[k].value, expected[k].second, 1e-4) << expected[k].first;
    total += s.subscores[k].weight * expected[k].second;
    weights += s.subscores[k].weight;
  }
  EXPECT_NEAR(weights, 1.0, 1e-12);
  // Default weights 0.35 .. 0.05 already sum to 1.
  EXPECT_DOUBLE_EQ(s.subscores[0].weight, 0.35);
  EXPECT_NEAR(s.score, total, 1e-4);
}

TEST(ScoreSession, GatesFailWithTheirMessages) {
  // A short press far from the tumour: sensitivity, coverage and deep coverage fail.
  test::SessionBuilder b(test::flat_case({{0.010, 0.0, 0.005, 0.005}}));
  for (int k = 0; k < 200; ++k) b.flat_contact(-0.03, 0.0, 0.004, 3.0);
  const Score s = score_session(b.finish(), "bad.session");
  EXPECT_FALSE(s.passed);
  EXPECT_FALSE(gate(s, "sensitivity").passed);
  EXPECT_TRUE(gate(s, "false_positives").passed);
  EXPECT_FALSE(gate(s, "coverage").passed);
  EXPECT_FALSE(gate(s, "deep_coverage").passed);
  EXPECT_TRUE(gate(s, "safety").passed);
  EXPECT_NE(gate(s, "coverage").message.find("(90.0% needed)"), std::string::npos) << gate(s, "coverage").message;
  EXPECT_EQ(to_string(s.pattern.kind), "localized");
}

TEST(ScoreSession, ThresholdsFromTheCaseApply) {
  // The case lowers the force limit to 5 N: 8 N fails the safety gate.
  session::Session session = good_exam();
  session.info.case_document["scoring"] = {{"max_force", 5.0}};
  const Score s = score_session(session, "strict.session");
  EXPECT_DOUBLE_EQ(s.thresholds.max_force, 5.0);
  EXPECT_FALSE(gate(s, "safety").passed);
  EXPECT_FALSE(s.passed);
}

TEST(ScoreSession, InvalidCaseDocumentIsASessionError) {
  session::Session session = good_exam();
  session.info.case_document["scoring"] = {{"min_coverage", 3}};
  try {
    score_session(session, "x.session");
    FAIL() << "no error";
  } catch (const session::SessionError& e) {
    EXPECT_EQ(e.file(), "x.session");
    EXPECT_EQ(e.where(), "meta case");
    EXPECT_EQ(e.reason().rfind("/scoring/min_coverage: ", 0), 0u) << e.reason();
  }
  session.info.case_document.erase("scoring");
  session.info.case_document.erase("bodies");
  EXPECT_THROW(score_session(session, "x.session"), session::SessionError);
}

TEST(ScoreSession, JsonHasEveryKey) {
  const Score s = score_session(good_exam(), "good.session");
  const nlohmann::json j = to_json(s);
  for (const char* key : {"passed", "score", "sensitivity", "false_positives", "localization_error_mm", "coverage",
                          "deep_coverage", "duration_s", "peak_force_n", "contact_time_s", "safe", "short_exam",
                          "palpate_search_ratio", "pressure", "pattern", "gates", "subscores", "tumours", "marks",
                          "notes", "thresholds", "exam_region", "complete", "samples"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_FALSE(j.contains("maps"));
  EXPECT_EQ(j["passed"], true);
  EXPECT_EQ(j["localization_error_mm"].size(), 1u);
  EXPECT_EQ(j["pressure"]["deep_s"].get<double>(), s.pressure.deep_s);
  EXPECT_EQ(j["pattern"]["kind"], "efficient");
  EXPECT_EQ(j["gates"].size(), 5u);
  EXPECT_EQ(j["tumours"][0]["mark"], 1);
  EXPECT_EQ(j["marks"][0]["false_positive"], false);
  EXPECT_EQ(j["thresholds"]["max_false_positives"], 1);
  EXPECT_EQ(j["samples"], s.samples);

  const nlohmann::json with_maps = to_json(s, true);
  ASSERT_TRUE(with_maps.contains("maps"));
  const auto& m = with_maps["maps"][0];
  EXPECT_EQ(m["body"], "flat");
  const auto cells = m["rows"].get<std::size_t>() * m["cols"].get<std::size_t>();
  for (const char* key : {"area", "center", "level", "dwell_s", "peak_force_n"}) EXPECT_EQ(m[key].size(), cells) << key;

  const std::string card = summary_text(s);
  EXPECT_EQ(card.rfind("PASSED", 0), 0u) << card;
  EXPECT_NE(card.find("PASS Found 1 of 1 tumours."), std::string::npos) << card;
  EXPECT_NE(card.find("search pattern    efficient"), std::string::npos) << card;
}

}  // namespace
}  // namespace palpa::score

namespace palpa::score {
namespace {

TEST(ScoreSession, ExamRegionOnOneOfTwoBodies) {
  nlohmann::json doc = test::case_document("two-bodies.json");
  doc["exam_region"] = {{{"body", "left"}}};
  auto press = [&](int body) {
    test::SessionBuilder b(doc);
    for (int k = 0; k < 100; ++k) b.contact_uv(body, 0.5, 0.5, 0.002, 3.0);
    return score_session(b.finish(), "two.session");
  };
  const Score left = press(0), right = press(1);
  ASSERT_EQ(left.maps.size(), 2u);
  double right_area = 0.0;
  for (double a : left.maps[1].area) right_area += a;
  EXPECT_EQ(right_area, 0.0);  // the right body is not part of the region
  EXPECT_GT(left.coverage, 0.0);
  EXPECT_EQ(right.coverage, 0.0);
  EXPECT_NEAR(right.contact_time_s, 0.1, 1e-9);  // still contact, just outside the region
  EXPECT_EQ(right.maps[1].level[static_cast<std::size_t>((right.maps[1].rows / 2) * right.maps[1].cols +
                                                         right.maps[1].cols / 2)],
            1);
}

TEST(ScoreSession, SamplesWithoutUsableContactAreSkipped) {
  test::SessionBuilder b(test::flat_case());
  for (int k = 0; k < 100; ++k) b.flat_contact(0.0, 0.0, 0.004, 2.0);
  b.contact_uv(0, std::nan(""), 0.5, 0.004, 2.0);  // unusable parameters
  b.contact_uv(3, 0.5, 0.5, 0.004, 2.0);           // a body the case does not have
  const Score s = score_session(b.finish(), "odd.session");
  EXPECT_NEAR(s.contact_time_s, 0.1, 1e-9);
  EXPECT_TRUE(has_note(s, "1 samples name a body the case does not have"));
}

}  // namespace
}  // namespace palpa::score
