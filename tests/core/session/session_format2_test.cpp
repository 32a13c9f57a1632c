// Format 2 (docs/session-format.md, "Version 2"): a finished session's ticks compacted into
// zlib-compressed blocks of integers in fixed units. Values read back within half a unit
// (and short decimals exactly), the file is much smaller than format 1, and damaged or
// hand-made blocks are refused naming the block.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "palpa/session/session_reader.hpp"
#include "palpa/session/session_upgrade.hpp"
#include "palpa/session/session_writer.hpp"
#include "session_test_support.hpp"

namespace palpa::session {
namespace {

using test::ScratchDir;
using test::sql;

std::int64_t query_int(const std::filesystem::path& path, const char* query) {
  sqlite3* db = nullptr;
  sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
  sqlite3_stmt* st = nullptr;
  std::int64_t value = -999;
  if (sqlite3_prepare_v2(db, query, -1, &st, nullptr) == SQLITE_OK && sqlite3_step(st) == SQLITE_ROW) {
    value = sqlite3_column_int64(st, 0);
  }
  sqlite3_finalize(st);
  sqlite3_close(db);
  return value;
}

void record(const std::filesystem::path& path, std::uint64_t n, const WriterOptions& options = {}) {
  SessionWriter writer(path, test::flat_case_info(), options);
  Event start;
  writer.event(start);
  for (std::uint64_t k = 0; k < n; ++k) writer.append(test::sample_at(k));
  Event end;
  end.t = static_cast<double>(n) / 1000.0;
  end.kind = EventKind::End;
  writer.event(end);
  writer.finish();
  EXPECT_EQ(writer.warning(), "");
}

void expect_refused(const std::filesystem::path& path, const std::string& expected) {
  try {
    read_session(path);
    ADD_FAILURE() << path << " was read; expected: " << expected;
  } catch (const SessionError& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

TEST(SessionFormat2, AFinishedSessionIsCompactedAndReadsBackWithinHalfAUnit) {
  ScratchDir dir;
  const auto path = dir / "s.palpa";
  record(path, 3000);
  EXPECT_EQ(query_int(path, "PRAGMA user_version"), 2);
  EXPECT_EQ(query_int(path, "SELECT value FROM meta WHERE key = 'format_version'"), 2);
  EXPECT_EQ(query_int(path, "SELECT count(*) FROM sqlite_schema WHERE name = 'samples'"), 0);
  // 3000 ticks in blocks of 1024: 1024, 1024, 952.
  EXPECT_EQ(query_int(path, "SELECT count(*) FROM sample_blocks"), 3);
  EXPECT_EQ(query_int(path, "SELECT first_tick FROM sample_blocks ORDER BY first_tick LIMIT 1 OFFSET 2"), 2048);
  EXPECT_EQ(query_int(path, "SELECT count FROM sample_blocks WHERE first_tick = 2048"), 952);
  const Session s = read_session(path);
  EXPECT_EQ(s.format_version, 2);
  EXPECT_TRUE(s.complete);
  ASSERT_EQ(s.samples.size(), 3000u);
  for (std::uint64_t k = 0; k < 3000; ++k) ASSERT_TRUE(test::near_sample(s.samples[k], test::sample_at(k))) << k;
  EXPECT_FALSE(std::filesystem::exists(path.string() + "-wal"));
}

TEST(SessionFormat2, ValuesThatAreWholeUnitsReadBackExactly) {
  ScratchDir dir;
  Session session;
  session.info = test::flat_case_info();
  for (int k = 0; k < 50; ++k) {
    engine::Sample s;
    s.t = k / 1000.0;  // 1 ms ticks: whole microseconds
    s.position = {k / 8000.0, -0.0125, 0.03};  // the doubles nearest to whole micrometres
    s.force = {k / 1000.0, -2.5, 0.25};
    s.body = k % 2 == 0 ? 0 : -1;
    if (s.body == 0) {
      s.u = 0.5;
      s.v = k / 1e6;
      s.depth = 0.002;
    }
    s.buttons = k == 7 ? 3u : 0u;
    session.samples.push_back(s);
  }
  write_session(dir / "d.palpa", session);
  const Session back = read_session(dir / "d.palpa");
  ASSERT_EQ(back.samples.size(), 50u);
  for (std::size_t k = 0; k < 50; ++k) EXPECT_TRUE(test::same_sample(back.samples[k], session.samples[k])) << k;
}

TEST(SessionFormat2, AtLeastFourTimesSmallerThanFormat1) {
  ScratchDir dir;
  record(dir / "rows.palpa", 20000, test::kRows);
  record(dir / "blocks.palpa", 20000);
  const auto rows = std::filesystem::file_size(dir / "rows.palpa");
  const auto blocks = std::filesystem::file_size(dir / "blocks.palpa");
  EXPECT_LT(blocks * 4, rows) << blocks << " bytes against " << rows;
}

TEST(SessionFormat2, AValueBeyondTheUnitsKeepsTheSessionInFormat1WithAWarning) {
  ScratchDir dir;
  const auto path = dir / "far.palpa";
  {
    SessionWriter writer(path, test::flat_case_info());
    writer.append(test::sample_at(0));
    auto far = test::sample_at(1);
    far.position[0] = 1e12;  // 1e18 um: beyond the 2^53 units a block holds exactly
    writer.append(far);
    writer.finish();
    EXPECT_NE(writer.warning().find("kept in format 1"), std::string::npos) << writer.warning();
    EXPECT_NE(writer.warning().find("column x"), std::string::npos) << writer.warning();
  }
  const Session s = read_session(path);
  EXPECT_EQ(s.format_version, 1);
  ASSERT_EQ(s.samples.size(), 2u);
  EXPECT_EQ(s.samples[1].position[0], 1e12);
}

TEST(SessionFormat2, ASessionCutShortStaysFormat1AndReadsBack) {
  ScratchDir dir;
  const auto path = dir / "cut.palpa";
  {
    SessionWriter writer(path, test::flat_case_info());
    for (std::uint64_t k = 0; k < 100; ++k) writer.append(test::sample_at(k));
  }  // destroyed without finish()
  const Session s = read_session(path);
  EXPECT_EQ(s.format_version, 1);
  EXPECT_FALSE(s.complete);
  ASSERT_EQ(s.samples.size(), 100u);
  EXPECT_TRUE(test::same_sample(s.samples[99], test::sample_at(99)));
}

TEST(SessionFormat2, DamagedBlocksAreRefusedNamingTheBlock) {
  ScratchDir dir;
  const auto made = [&](const std::string& name, const std::string& damage) {
    const auto path = dir / name;
    record(path, 3000);
    sql(path, damage);
    return path;
  };
  expect_refused(made("noise.palpa", "UPDATE sample_blocks SET data = randomblob(300) WHERE first_tick = 1024;"),
                 "sample_blocks first_tick 1024: damaged block (zlib");
  expect_refused(made("short.palpa", "UPDATE sample_blocks SET count = 1000 WHERE first_tick = 0;"),
                 "sample_blocks first_tick 0: ");
  expect_refused(made("zero.palpa", "UPDATE sample_blocks SET count = 0 WHERE first_tick = 0;"),
                 "sample_blocks first_tick 0: column count: must be in 1..65536, not 0");
  expect_refused(made("text.palpa", "UPDATE sample_blocks SET data = 'abc' WHERE first_tick = 0;"),
                 "sample_blocks first_tick 0: column data: not a blob");
  // Block 2048's data under the name 1024: its ticks are not where the table says.
  expect_refused(made("moved.palpa", "DELETE FROM sample_blocks WHERE first_tick = 1024; "
                                     "UPDATE sample_blocks SET first_tick = 1024 WHERE first_tick = 2048;"),
                 "sample_blocks first_tick 1024: its first tick is 2048");
  // Two blocks overlapping: block 0's data again at 2048 goes back in time.
  expect_refused(made("again.palpa", "UPDATE sample_blocks SET data = (SELECT data FROM sample_blocks WHERE "
                                     "first_tick = 0), count = 1024 WHERE first_tick = 2048;"),
                 "sample_blocks first_tick 2048: its first tick is 0");
  expect_refused(made("rows.palpa", "CREATE TABLE samples(tick INTEGER PRIMARY KEY);"),
                 "not a Palpa session (its schema has table samples");
  expect_refused(made("v3.palpa", "UPDATE meta SET value = '3' WHERE key = 'format_version';"),
                 "meta format_version: format version 3 is newer than this Palpa reads (2)");
  expect_refused(made("v1.palpa", "UPDATE meta SET value = '1' WHERE key = 'format_version';"),
                 "samples: table is missing");
}

TEST(SessionFormat2, ACompactedCopyOfAFormat1FileHasItsMetaEventsAndSamples) {
  ScratchDir dir;
  record(dir / "old.palpa", 2500, test::kRows);
  sql(dir / "old.palpa", "INSERT INTO meta(key, value) VALUES('ended_at', '2026-11-22T16:45:00Z') "
                         "ON CONFLICT(key) DO UPDATE SET value = excluded.value;");
  write_compacted_copy(dir / "old.palpa", dir / "new.palpa");
  const Session old_one = read_session(dir / "old.palpa");
  const Session new_one = read_session(dir / "new.palpa");
  EXPECT_EQ(old_one.format_version, 1);
  EXPECT_EQ(new_one.format_version, 2);
  EXPECT_EQ(new_one.info.id, old_one.info.id);
  EXPECT_EQ(new_one.events.size(), old_one.events.size());
  ASSERT_EQ(new_one.samples.size(), 2500u);
  for (std::size_t k = 0; k < 2500; ++k) ASSERT_TRUE(test::near_sample(new_one.samples[k], old_one.samples[k])) << k;
  sqlite3* db = nullptr;
  sqlite3_open_v2((dir / "new.palpa").c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
  sqlite3_stmt* st = nullptr;
  sqlite3_prepare_v2(db, "SELECT value FROM meta WHERE key = 'ended_at'", -1, &st, nullptr);
  ASSERT_EQ(sqlite3_step(st), SQLITE_ROW);
  EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(st, 0)), "2026-11-22T16:45:00Z");
  sqlite3_finalize(st);
  sqlite3_close(db);
  EXPECT_LT(std::filesystem::file_size(dir / "new.palpa") * 4, std::filesystem::file_size(dir / "old.palpa"));
  // Neither replaces a file nor converts a format-2 one.
  EXPECT_THROW(write_compacted_copy(dir / "old.palpa", dir / "new.palpa"), SessionError);
  try {
    write_compacted_copy(dir / "new.palpa", dir / "newer.palpa");
    ADD_FAILURE() << "a format-2 file was converted";
  } catch (const SessionError& e) {
    EXPECT_NE(std::string(e.what()).find("format 2, not 1"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "newer.palpa"));
}

}  // namespace
}  // namespace palpa::session
