// score_from_json: a stored result reads back to the score that wrote it, maps and all,
// and JSON that is not one is refused with a message instead of a half-filled score.
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

#include "palpa/score/score.hpp"
#include "palpa/session/session_reader.hpp"

namespace palpa::score {
namespace {

Score scored(const char* name) {
  const auto path = std::filesystem::path(PALPA_SOURCE_DIR) / "data/sessions" / (std::string(name) + ".palpa");
  return score_session(session::read_session(path), path.string());
}

TEST(ScoreFromJson, ReadsBackEveryFieldOfThreeSessions) {
  for (const char* name : {"expert", "sloppy", "light"}) {
    const Score original = scored(name);
    ASSERT_FALSE(original.maps.empty()) << name;
    for (const bool with_maps : {false, true}) {
      const Score back = score_from_json(to_json(original, with_maps), original.thresholds);
      EXPECT_EQ(to_json(back, with_maps).dump(), to_json(original, with_maps).dump()) << name;
      EXPECT_EQ(back.maps.empty(), !with_maps);
    }
  }
}

TEST(ScoreFromJson, RefusesWhatIsNotAScore) {
  const Score original = scored("sloppy");
  auto missing = to_json(original, true);
  missing.erase("coverage");
  EXPECT_THROW(score_from_json(missing, original.thresholds), std::invalid_argument);
  auto wrong_kind = to_json(original);
  wrong_kind["pattern"]["kind"] = "spiral";
  EXPECT_THROW(score_from_json(wrong_kind, original.thresholds), std::invalid_argument);
  auto short_map = to_json(original, true);
  short_map["maps"][0]["level"].erase(0);
  EXPECT_THROW(score_from_json(short_map, original.thresholds), std::invalid_argument);
  auto far_mark = to_json(original);
  far_mark["marks"] = {{{"id", 1}, {"t", 1.0}, {"position", {0, 0, 0}}, {"duplicate", false}, {"tumour", 99},
                        {"nearest_mm", 1.0}}};
  EXPECT_THROW(score_from_json(far_mark, original.thresholds), std::invalid_argument);
  EXPECT_THROW(score_from_json(nlohmann::json::array(), original.thresholds), std::invalid_argument);
}

}  // namespace
}  // namespace palpa::score
