#include <cmath>

#include <gtest/gtest.h>

#include "palpa/report/summary_csv.hpp"
#include "palpa/report/xapi.hpp"
#include "report_fixture.hpp"

namespace palpa::report {
namespace {

/// An RFC 4180 line split into fields (an independent parser, quotes and all).
std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

TEST(SummaryCsv, HeaderIsTheDocumentedContract) {
  EXPECT_EQ(csv_header(),
            "file,session_id,trainee,case,started_at,passed,score,sensitivity,false_positives,"
            "localization_error_mm,coverage,deep_coverage,duration_s,contact_time_s,peak_force_n,"
            "safe,palpate_search_ratio,pattern,light_s,medium_s,deep_s,complete,samples,"
            "outcome,mode,case_file,case_id,score_100,station");
}

TEST(SummaryCsv, RowValuesLineUpWithTheHeader) {
  auto h = testing::synthetic_header();
  h.trainee = "Smith, \"Jo\"";
  h.station = "room-2";
  const auto s = testing::synthetic_score();
  const auto names = split_csv(csv_header());
  const auto row = csv_row(h, s);
  const auto values = split_csv(row);
  ASSERT_EQ(values.size(), names.size());
  std::map<std::string, std::string> v;
  for (std::size_t i = 0; i < names.size(); ++i) v[names[i]] = values[i];
  EXPECT_EQ(v["trainee"], "Smith, \"Jo\"");
  EXPECT_NE(row.find("\"Smith, \"\"Jo\"\"\""), std::string::npos);
  EXPECT_EQ(v["case"], "Flat 5x5: plane skeleton, polynomial radius");
  EXPECT_EQ(v["passed"], "0");
  EXPECT_EQ(v["score"], "0.613");  // fractions to 0.001 (csv_number.hpp)
  EXPECT_EQ(v["score_100"], "61.3");
  EXPECT_EQ(v["station"], "room-2");
  EXPECT_EQ(v["false_positives"], "1");
  EXPECT_EQ(v["localization_error_mm"], "3.0");  // mean of 2.5 and 3.5, to 0.1 mm
  EXPECT_EQ(v["duration_s"], "183.25");
  EXPECT_EQ(v["safe"], "1");
  EXPECT_EQ(v["pattern"], "sporadic");
  EXPECT_EQ(v["deep_s"], "30.50");
  EXPECT_EQ(v["complete"], "1");
  EXPECT_EQ(v["samples"], "183250");
  EXPECT_EQ(v["file"], "sessions/alice-1.palpa");
}

TEST(SummaryCsv, LocalizationErrorIsEmptyWhenNothingWasFound) {
  auto s = testing::synthetic_score();
  s.localization_error_mm.clear();
  const auto values = split_csv(csv_row(testing::synthetic_header(), s));
  EXPECT_EQ(values[9], "");
  EXPECT_TRUE(std::isnan(mean_localization_error_mm(s)));
}

TEST(SummaryCsv, ControlAndBidiCharactersInTextCellsAreWrittenEscaped) {
  EXPECT_EQ(csv_text("alice"), "alice");
  EXPECT_EQ(csv_text("O'Neil, Bob"), "\"O'Neil, Bob\"");            // plain text: as csv_field
  EXPECT_EQ(csv_text("=1+1"), "\"'=1+1\"");                          // the formula guard stays
  EXPECT_EQ(csv_text("a\x1b[2Jb"), "a\\x1b[2Jb");                  // ESC
  EXPECT_EQ(csv_text("a\nb"), "a\\x0ab");                          // no raw line break
  EXPECT_EQ(csv_text(std::string("a\0b", 3)), "a\\x00b");           // NUL
  EXPECT_EQ(csv_text("x\xE2\x80\xAEy"), "x\\u{202e}y");           // RIGHT-TO-LEFT OVERRIDE
  const std::string long_id(100000, 'x');
  EXPECT_EQ(csv_text(long_id), long_id);  // escaped, never shortened: the cell keeps the value
  auto header = testing::synthetic_header();
  header.trainee = "eve\x1b]0;owned\x07";
  const auto row = csv_row(header, testing::synthetic_score());
  EXPECT_EQ(row.find('\x1b'), std::string::npos);
  EXPECT_NE(row.find("eve\\x1b]0;owned\\x07"), std::string::npos);
}

TEST(Xapi, DurationIsIso8601InHundredths) {
  EXPECT_EQ(iso8601_duration(183.25), "PT183.25S");
  EXPECT_EQ(iso8601_duration(60.0), "PT60S");
  EXPECT_EQ(iso8601_duration(0.5), "PT0.5S");
  EXPECT_EQ(iso8601_duration(0.05), "PT0.05S");
  EXPECT_EQ(iso8601_duration(59.999), "PT60S");
  EXPECT_EQ(iso8601_duration(0.0), "PT0S");
  EXPECT_EQ(iso8601_duration(-3.0), "PT0S");
  EXPECT_EQ(iso8601_duration(std::nan("")), "PT0S");
}

TEST(Xapi, StatementHasTheXapiStructureAndValues) {
  const auto h = testing::synthetic_header();
  auto s = testing::synthetic_score();
  const auto x = xapi_statement(h, s);
  // uuid.uuid5(uuid.uuid5(uuid.NAMESPACE_URL, "urn:palpa"), "3f2a9c") in Python
  EXPECT_EQ(x["id"], "3b29596d-fd0f-5655-93d7-d06c1aff8eff");
  EXPECT_EQ(x["actor"]["objectType"], "Agent");
  EXPECT_EQ(x["actor"]["account"]["homePage"], "urn:palpa");
  EXPECT_EQ(x["actor"]["account"]["name"], "alice");
  EXPECT_EQ(x["verb"]["id"], "http://adlnet.gov/expapi/verbs/failed");
  EXPECT_EQ(x["verb"]["display"]["en-US"], "failed");
  EXPECT_EQ(x["object"]["objectType"], "Activity");
  EXPECT_EQ(x["object"]["id"], "urn:palpa:case:flat-5x5-plane-skeleton-polynomial-radius");
  EXPECT_EQ(x["object"]["definition"]["name"]["en-US"], h.case_title);
  EXPECT_EQ(x["object"]["definition"]["type"], "http://adlnet.gov/expapi/activities/simulation");
  const auto& r = x["result"];
  EXPECT_DOUBLE_EQ(r["score"]["scaled"].get<double>(), 0.6125);
  EXPECT_DOUBLE_EQ(r["score"]["raw"].get<double>(), 61.25);
  EXPECT_EQ(r["score"]["min"], 0);
  EXPECT_EQ(r["score"]["max"], 100);
  EXPECT_EQ(r["success"], false);
  EXPECT_EQ(r["completion"], true);
  EXPECT_EQ(r["duration"], "PT183.25S");
  EXPECT_DOUBLE_EQ(r["extensions"]["urn:palpa:xapi:sensitivity"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(r["extensions"]["urn:palpa:xapi:localization_error_mm"].get<double>(), 3.0);
  EXPECT_EQ(r["extensions"]["urn:palpa:xapi:false_positives"], 1);
  EXPECT_DOUBLE_EQ(r["extensions"]["urn:palpa:xapi:peak_force_n"].get<double>(), 7.25);
  EXPECT_EQ(x["context"]["platform"], "Palpa 0.1.0");
  EXPECT_EQ(x["context"]["extensions"]["urn:palpa:xapi:session_id"], "3f2a9c");
  EXPECT_EQ(x["timestamp"], "2026-11-22T16:40:00Z");
  // Every extension key is an IRI.
  for (const auto& [key, value] : r["extensions"].items()) EXPECT_EQ(key.rfind("urn:palpa:xapi:", 0), 0u) << key;

  s.passed = true;
  s.complete = false;
  s.localization_error_mm.clear();
  const auto y = xapi_statement(h, s);
  EXPECT_EQ(y["verb"]["id"], "http://adlnet.gov/expapi/verbs/passed");
  EXPECT_EQ(y["verb"]["display"]["en-US"], "passed");
  EXPECT_EQ(y["result"]["success"], true);
  EXPECT_EQ(y["result"]["completion"], false);
  EXPECT_TRUE(y["result"]["extensions"]["urn:palpa:xapi:localization_error_mm"].is_null());
  EXPECT_EQ(y["id"], x["id"]);  // derived from the session id alone: re-scoring keeps it
}

TEST(Xapi, CaseWithoutTitleIsNamedByItsFile) {
  auto h = testing::synthetic_header();
  h.case_title.clear();
  const auto x = xapi_statement(h, testing::synthetic_score());
  EXPECT_EQ(x["object"]["id"], "urn:palpa:case:flat-5x5");
  EXPECT_EQ(x["object"]["definition"]["name"]["en-US"], "flat-5x5.json");
  h.case_title = "Étude";  // letters outside ASCII are dropped from the slug
  EXPECT_EQ(xapi_statement(h, testing::synthetic_score())["object"]["id"], "urn:palpa:case:tude");
  h.case_title = "\xC3\x89\xC3\x89";  // no ASCII letter at all: a hash of the title
  const std::string id = xapi_statement(h, testing::synthetic_score())["object"]["id"];
  EXPECT_EQ(id.rfind("urn:palpa:case:sha1-", 0), 0u);
  EXPECT_EQ(id.size(), std::string("urn:palpa:case:sha1-").size() + 12);
}

}  // namespace
}  // namespace palpa::report
