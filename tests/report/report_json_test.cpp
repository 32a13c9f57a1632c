#include "palpa/report/report_json.hpp"

#include <gtest/gtest.h>

#include "report_fixture.hpp"

namespace palpa::report {
namespace {

TEST(ReportJson, IsTheScoreJsonWithTheSession) {
  const auto h = testing::synthetic_header();
  const auto s = testing::synthetic_score();
  const auto j = report_json(h, s);
  // Everything score::to_json says, unchanged.
  const auto plain = score::to_json(s, false);
  for (const auto& [key, value] : plain.items()) EXPECT_EQ(j.at(key), value) << key;
  EXPECT_EQ(j["passed"], false);
  EXPECT_EQ(j["false_positives"], 1);
  EXPECT_DOUBLE_EQ(j["duration_s"].get<double>(), 183.25);
  const auto& session = j.at("session");
  EXPECT_EQ(session["id"], "3f2a9c");
  EXPECT_EQ(session["trainee"], "alice");
  EXPECT_EQ(session["case"], h.case_title);
  EXPECT_EQ(session["case_source"], "data/cases/flat-5x5.json");
  EXPECT_EQ(session["device"], "virtual");
  EXPECT_EQ(session["software_version"], "0.1.0");
  EXPECT_EQ(session["started_at"], "2026-11-22T16:40:00Z");
  EXPECT_EQ(session["file"], "sessions/alice-1.palpa");
}

TEST(ReportJson, HeaderComesFromTheSessionInfo) {
  session::SessionInfo info;
  info.id = "abc";
  info.trainee = "t";
  info.case_document = {{"title", "Case T"}};
  info.case_source = "c.json";
  info.started_at = "2026-01-01T00:00:00Z";
  const auto h = header_of(info, "dir/x.palpa");
  EXPECT_EQ(h.case_title, "Case T");
  EXPECT_EQ(h.file, "dir/x.palpa");
  info.case_document = {{"title", 3}};  // not a string: no title
  EXPECT_EQ(header_of(info, "x").case_title, "");
}

}  // namespace
}  // namespace palpa::report
