// The live coverage (live/live_coverage.hpp) measures what the score measures, from the
// contacts the GUI sees at its frame rate (every 16th haptic sample here).
#include <gtest/gtest.h>

#include <cmath>

#include "palpa/io/case_file.hpp"
#include "palpa/io/training.hpp"
#include "palpa/live/live_coverage.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/score/score.hpp"
#include "score_fixture.hpp"

namespace palpa::score {
namespace {

using test::flat_radius;

struct Fed {
  Score score;
  double live = 0.0, live_deep = 0.0;
};

// Strips along y at `spacing`, sliding at `speed` m/s, pressing `share` of the thickness;
// the GUI sees every `every`-th sample.
Fed raster(double spacing, double speed, double share, int every) {
  test::SessionBuilder b(test::flat_case());
  const int strips = static_cast<int>(std::floor(0.06 / spacing)) + 1;
  for (int strip = 0; strip < strips; ++strip) {
    const double x = -0.03 + spacing * strip;
    const double y0 = strip % 2 == 0 ? -0.03 : 0.03;
    const double length = 0.06;
    const int n = static_cast<int>(std::ceil(length / (speed * 0.001)));
    for (int k = 0; k <= n; ++k) {
      const double y = y0 + (strip % 2 == 0 ? 1.0 : -1.0) * length * k / n;
      b.flat_contact(x, y, share * 2 * flat_radius(x, y), 5.0);
    }
  }
  const session::Session session = b.finish();
  Fed out;
  out.score = score_session(session, "raster.session");
  const io::CaseFile file = io::parse_case(session.info.case_document.dump(), "flat.json");
  const scene::Scene scene = scene::Scene::build(file, "flat.json");
  live::LiveCoverage live(scene, out.score.thresholds);
  for (std::size_t k = 0; k < session.samples.size(); k += static_cast<std::size_t>(every)) {
    const auto& s = session.samples[k];
    live.contact(s.body, s.u, s.v, s.depth);
  }
  const auto& last = session.samples.back();  // the finger rests at the end: a frame sees it
  live.contact(last.body, last.u, last.v, last.depth);
  out.live = live.coverage();
  out.live_deep = live.deep_coverage();
  return out;
}

TEST(LiveCoverage, AgreesWithTheScoreAtTheFrameRate) {
  // A slow deep raster and a brisk light one (0.1 m/s: 1.6 mm between frames); the frames
  // cut the corners where the strips turn, a little.
  for (const auto& [speed, share] : {std::pair{0.03, 0.6}, std::pair{0.1, 0.1}}) {
    const Fed f = raster(0.012, speed, share, 16);
    EXPECT_GT(f.score.coverage, 0.2);
    EXPECT_NEAR(f.live, f.score.coverage, 0.01) << speed;
    EXPECT_NEAR(f.live_deep, f.score.deep_coverage, 0.01) << speed;
  }
}

TEST(LiveCoverage, AFastSlideLeavesNoGaps) {
  // One straight slide at 1 m/s, seen at 60 Hz: 16 mm between frames, more than the pad's
  // diameter; stamping only the frames would leave gaps between 15 mm discs.
  const Fed f = raster(0.1, 1.0, 0.1, 16);
  EXPECT_GT(f.score.coverage, 0.05);
  EXPECT_NEAR(f.live, f.score.coverage, 0.003);
}

TEST(LiveCoverage, NoContactCoversNothing) {
  const nlohmann::json doc = test::flat_case();
  const io::CaseFile file = io::parse_case(doc.dump(), "flat.json");
  const scene::Scene scene = scene::Scene::build(file, "flat.json");
  live::LiveCoverage live(scene, io::Thresholds{});
  const auto v0 = live.version();
  live.contact(-1, 0.5, 0.5, 0.0);
  live.lift();
  EXPECT_EQ(live.coverage(), 0.0);
  EXPECT_EQ(live.version(), v0);
  live.contact(0, 0.5, 0.5, 0.001);
  EXPECT_GT(live.coverage(), 0.0);
  EXPECT_NE(live.version(), v0);
}

// "training" in a case (io/training.hpp): optional, checked like "scoring".
TEST(CaseTraining, CoverageOverlayDefaultsOnAndMayBeTurnedOff) {
  EXPECT_TRUE(io::training_from_case(test::flat_case()).coverage_overlay);
  const auto off = test::flat_case({}, {{"training", {{"coverage_overlay", false}}}});
  EXPECT_FALSE(io::training_from_case(io::parse_case(off.dump(), "exam.json").document).coverage_overlay);
}

TEST(CaseTraining, BadTrainingFieldsAreErrors) {
  const auto bad = test::flat_case({}, {{"training", {{"coverage_overlay", "no"}, {"overlay", true}}}});
  try {
    io::parse_case(bad.dump(), "bad.json");
    FAIL() << "parse_case accepted a bad training object";
  } catch (const io::CaseError& e) {
    const auto lines = e.lines();
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[0], "bad.json: /training/coverage_overlay: coverage_overlay must be true or false, not string");
    EXPECT_EQ(lines[1], "bad.json: /training/overlay: unknown training field \"overlay\" (expected coverage_overlay)");
  }
  const auto not_object = test::flat_case({}, {{"training", 3}});
  EXPECT_THROW(io::parse_case(not_object.dump(), "bad.json"), io::CaseError);
}

}  // namespace
}  // namespace palpa::score
