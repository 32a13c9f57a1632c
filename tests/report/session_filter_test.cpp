#include "palpa/report/session_filter.hpp"

#include <gtest/gtest.h>

#include "report_fixture.hpp"

namespace palpa::report {
namespace {

TEST(Iso8601, DatesAndTimesAsSecondsSinceTheEpoch) {
  EXPECT_EQ(parse_iso8601("1970-01-01"), 0.0);
  EXPECT_EQ(parse_iso8601("1970-01-02T00:00:01Z"), 86401.0);
  // 2026-11-22: 20779 days after 1970-01-01 (56 years, 14 leap days, 325 days into 2026).
  EXPECT_EQ(parse_iso8601("2026-11-22"), 20779.0 * 86400.0);
  EXPECT_EQ(parse_iso8601("2026-11-22T16:40:00Z"), 20779.0 * 86400.0 + 16 * 3600.0 + 40 * 60.0);
  EXPECT_EQ(parse_iso8601("2026-11-22T16:40"), parse_iso8601("2026-11-22T16:40:00Z"));
  EXPECT_EQ(parse_iso8601("2026-11-22T17:40:00+01:00"), parse_iso8601("2026-11-22T16:40:00Z"));
  EXPECT_EQ(parse_iso8601("2026-11-22T16:40:00.5Z"), *parse_iso8601("2026-11-22T16:40:00Z") + 0.5);
  EXPECT_EQ(parse_iso8601("2024-02-29"), parse_iso8601("2024-03-01").value() - 86400.0);  // leap day
  bool date_only = false;
  parse_iso8601("2026-11-30", &date_only);
  EXPECT_TRUE(date_only);
  parse_iso8601("2026-11-30T00:00:00Z", &date_only);
  EXPECT_FALSE(date_only);
}

TEST(Iso8601, RefusesWhatIsNotADate) {
  for (const char* bad : {"", "2026-13-01", "2026-04-31", "2025-02-29", "2026-11-22T24:00:00Z", "26-11-22",
                          "2026/11/22", "2026-11-22T16:40:00Q", "2026-11-22x", "yesterday", "2026-11-22T16:40:00.Z"})
    EXPECT_FALSE(parse_iso8601(bad).has_value()) << bad;
}

TEST(SessionFilter, DatesCoverWholeDaysAndTimesAreInclusive) {
  auto h = testing::synthetic_header();  // started 2026-11-22T16:40:00Z
  SessionFilter f;
  EXPECT_TRUE(f.matches(h));
  f.since = "2026-11-22";
  f.until = "2026-11-22";
  EXPECT_TRUE(f.matches(h));
  f.until = "2026-11-22T16:40:00Z";
  EXPECT_TRUE(f.matches(h));
  f.until = "2026-11-22T16:39:59Z";
  EXPECT_FALSE(f.matches(h));
  f.until.clear();
  f.since = "2026-11-23";
  EXPECT_FALSE(f.matches(h));
  h.started_at = "not a time";
  f.since = "2000-01-01";
  EXPECT_FALSE(f.matches(h));  // a start that cannot be read is outside every range
}

TEST(SessionFilter, CaseByIdOrFileAndTraineeExactly) {
  auto h = testing::synthetic_header();
  h.case_file = "default.json";
  h.case_id = "urn:palpa:case:default";
  for (const char* key : {"default", "default.json", "urn:palpa:case:default"}) {
    SessionFilter f;
    f.case_key = key;
    EXPECT_TRUE(f.matches(h)) << key;
  }
  SessionFilter f;
  f.case_key = "flat-5x5";
  EXPECT_FALSE(f.matches(h));
  f.case_key.clear();
  f.trainee = "alice";
  EXPECT_TRUE(f.matches(h));
  f.trainee = "Alice";
  EXPECT_FALSE(f.matches(h));
}

TEST(SessionFilter, DescribesItselfAndNamesTheBadOption) {
  SessionFilter f;
  EXPECT_EQ(f.describe(), "");
  f.since = "2026-11-01";
  f.until = "2026-11-30";
  f.case_key = "default";
  EXPECT_EQ(f.describe(), "sessions from 2026-11-01 to 2026-11-30, case default");
  SessionFilter t;
  t.trainee = "alice";
  EXPECT_EQ(t.describe(), "sessions of trainee alice");
  f.validate();
  f.since = "2026-12-01";
  EXPECT_THROW(f.validate(), FilterError);
  f.since = "2026-13-01";
  try {
    f.validate();
    FAIL() << "a bad date was taken";
  } catch (const FilterError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("--since: \"2026-13-01\" is not a date", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace palpa::report
