// Files that are not sessions, damaged sessions and hand-edited ones: each is refused with
// a SessionError whose message starts with the file and names the reason, never a crash.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <random>

#include "palpa/session/session_reader.hpp"
#include "palpa/session/session_writer.hpp"
#include "session_test_support.hpp"

namespace palpa::session {
namespace {

using test::sql;

class SessionCorrupt : public ::testing::Test {
 protected:
  // A finished session of 3000 samples (several hundred kB, many pages) and two events.
  std::filesystem::path good(const std::string& name) {
    const auto path = dir_ / name;
    // Format 1: these tests damage the samples table by hand (format 2's blocks:
    // session_format2_test.cpp).
    SessionWriter writer(path, test::flat_case_info(), test::kRows);
    Event e;
    e.kind = EventKind::Start;
    writer.event(e);
    for (std::uint64_t k = 0; k < 3000; ++k) writer.append(test::sample_at(k));
    e.t = 1.0;
    e.kind = EventKind::Mark;
    e.mark = 1;
    e.position = {0.01, 0.02, 0.03};
    writer.event(e);
    writer.finish();
    return path;
  }
  std::filesystem::path file_with(const std::string& name, const std::string& bytes) {
    const auto path = dir_ / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
  // The reader's refusal: what() starts with the file and contains `expected`.
  void expect_refused(const std::filesystem::path& path, const std::string& expected, const ReadOptions& options = {}) {
    try {
      read_session(path, options);
      ADD_FAILURE() << path << " was read; expected: " << expected;
    } catch (const SessionError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path.string() + ": ", 0), 0u) << what;
      EXPECT_NE(what.find(expected), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
  test::ScratchDir dir_;
};

TEST_F(SessionCorrupt, FilesThatAreNotSQLiteAreNamedSo) {
  expect_refused(dir_ / "missing.palpa", "file: no such file");
  expect_refused(dir_.path(), "is a folder");
  expect_refused(file_with("empty.palpa", ""), "file: not a Palpa session (empty file)");
  expect_refused(file_with("text.palpa", "t,x,y,z\n0,0.1,0.2,0.3\n"), "file: not a Palpa session (not an SQLite database)");
  std::mt19937 random(12345);
  std::string noise(20000, '\0');
  for (auto& c : noise) c = static_cast<char>(random() & 0xFF);
  expect_refused(file_with("noise.palpa", noise), "not an SQLite database");
  // The SQLite magic followed by noise gets past the first look; SQLite itself must refuse it.
  const std::string magic("SQLite format 3\0", 16);
  expect_refused(file_with("magic-noise.palpa", magic + noise), "file: not a Palpa session (not an SQLite database)");
}

TEST_F(SessionCorrupt, TruncatedSessionsAreRefused) {
  const auto path = good("whole.palpa");
  std::ifstream in(path, std::ios::binary);
  const std::string whole((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(whole.size(), 100000u);
  EXPECT_NO_THROW(read_session(path));
  expect_refused(file_with("cut-10.palpa", whole.substr(0, 10)), "file: not a Palpa session (not an SQLite database)");
  for (std::size_t length : {std::size_t{100}, std::size_t{4096}, whole.size() / 2, whole.size() - 4096}) {
    const auto cut = file_with("cut-" + std::to_string(length) + ".palpa", whole.substr(0, length));
    SCOPED_TRACE(length);
    expect_refused(cut, "damaged file");
    EXPECT_THROW(read_session(cut, ReadOptions{false}), SessionError);  // a listing notices too
  }
}

TEST_F(SessionCorrupt, SQLiteFilesThatAreNotSessions) {
  const auto other = dir_ / "other.db";
  sql(other, "CREATE TABLE patients(name TEXT); INSERT INTO patients VALUES('x');");
  expect_refused(other, "file: not a Palpa session (an SQLite database without Palpa's tables)");

  const auto foreign = good("foreign.palpa");
  sql(foreign, "PRAGMA application_id = 42;");
  expect_refused(foreign, "application_id: not a Palpa session (application_id is 0x0000002A");

  const auto format = good("format.palpa");
  sql(format, "UPDATE meta SET value = 'palpa-case' WHERE key = 'format';");
  expect_refused(format, "meta format: not a Palpa session");
}

TEST_F(SessionCorrupt, NewerFormatVersionsAreRefusedEvenForAListing) {
  const auto path = good("v2.palpa");
  sql(path, "UPDATE meta SET value = '3' WHERE key = 'format_version';");
  expect_refused(path, "meta format_version: format version 3 is newer than this Palpa reads (2)");
  EXPECT_THROW(read_session(path, ReadOptions{false}), SessionError);
}

TEST_F(SessionCorrupt, MissingMetaKeysAndTablesAreNamed) {
  const auto no_trainee = good("no-trainee.palpa");
  sql(no_trainee, "DELETE FROM meta WHERE key = 'trainee';");
  expect_refused(no_trainee, "meta trainee: missing");
  const auto no_events = good("no-events.palpa");
  sql(no_events, "DROP TABLE events;");
  expect_refused(no_events, "events: table is missing");
  const auto rate = good("rate.palpa");
  sql(rate, "UPDATE meta SET value = '-1000' WHERE key = 'rate_hz';");
  expect_refused(rate, "meta rate_hz: not a finite number > 0");
  const auto seed = good("seed.palpa");
  sql(seed, "INSERT INTO meta VALUES('seed', '12abc');");
  expect_refused(seed, "meta seed: not an unsigned 64-bit integer");
  const auto extra = good("extra.palpa");
  sql(extra, "UPDATE meta SET value = '{\"a\": ' WHERE key = 'extra';");
  expect_refused(extra, "meta extra: ");
}

TEST_F(SessionCorrupt, AnInvalidCaseDocumentIsReportedWithItsPointer) {
  const auto path = good("case.palpa");
  sql(path, "UPDATE meta SET value = json_set(value, '$.bodies[0].rows', -3) WHERE key = 'case';");
  try {
    read_session(path);
    FAIL();
  } catch (const SessionError& e) {
    EXPECT_EQ(e.where().rfind("meta case /bodies/0", 0), 0u) << e.what();
  }
  sql(path, "UPDATE meta SET value = 'not json' WHERE key = 'case';");
  expect_refused(path, "meta case line 1, column");
}

TEST_F(SessionCorrupt, HandEditedSamplesAreCheckedRowByRow) {
  const auto text = good("text-x.palpa");
  sql(text, "UPDATE samples SET x = 'left' WHERE tick = 12;");
  expect_refused(text, "samples tick 12: column x: not a number");

  const auto backwards = good("backwards.palpa");
  sql(backwards, "UPDATE samples SET t = 0.25 WHERE tick = 500;");  // tick 499 is at 0.499 s
  expect_refused(backwards, "samples tick 500: column t: time goes backwards (0.25 s after 0.499 s)");

  const auto body = good("body.palpa");
  sql(body, "UPDATE samples SET body = 3 WHERE tick = 7;");  // the case has one body
  expect_refused(body, "samples tick 7: column body: must be in 0..0, not 3");

  // Contact parameters out of the format's ranges (u = 4.2e213 reached an int cast in the
  // coverage grid: undefined behaviour) and a press deeper than the body is thick.
  const auto far = good("far-u.palpa");
  sql(far, "UPDATE samples SET u = 4.2e213 WHERE tick = 8;");  // every third tick is out of contact
  expect_refused(far, "samples tick 8: column u: outside [0, 1]: 4.2e+213");
  const auto negative = good("negative-v.palpa");
  sql(negative, "UPDATE samples SET v = -0.5 WHERE tick = 10;");
  expect_refused(negative, "samples tick 10: column v: outside [0, 1]: -0.5");
  const auto deep = good("deep.palpa");
  sql(deep, "UPDATE samples SET depth = 3.0 WHERE tick = 11;");
  expect_refused(deep, "samples tick 11: column depth: outside [0, ");
  const auto round_off = good("round-off.palpa");  // a writer's round-off is accepted and clamped
  sql(round_off, "UPDATE samples SET u = 1.0000000001 WHERE tick = 13;");
  EXPECT_EQ(read_session(round_off).samples.at(13).u, 1.0);

  const auto contact = good("contact.palpa");
  sql(contact, "UPDATE samples SET depth = NULL WHERE tick = 8;");  // in contact, depth missing
  expect_refused(contact, "samples tick 8: column depth: missing (NULL)");

  const auto inf = good("inf.palpa");
  sql(inf, "UPDATE samples SET fz = 9e999 WHERE tick = 9;");
  expect_refused(inf, "samples tick 9: column fz: not a finite number");

  // Gaps in the ticks are accepted (a hand-trimmed session), order is what matters.
  const auto gap = good("gap.palpa");
  sql(gap, "DELETE FROM samples WHERE tick BETWEEN 100 AND 199;");
  EXPECT_EQ(read_session(gap).samples.size(), 2900u);
}

TEST_F(SessionCorrupt, HandEditedEventsAreChecked) {
  const auto kind = good("kind.palpa");
  sql(kind, "PRAGMA ignore_check_constraints = ON; INSERT INTO events(t, kind) VALUES(0.5, 'dance');");
  expect_refused(kind, "column kind: unknown event kind 'dance'");
  const auto mark = good("mark.palpa");
  sql(mark, "UPDATE events SET mark = 0 WHERE kind = 'mark';");
  expect_refused(mark, "events id 2: column mark: must be >= 1, not 0");
  const auto where = good("where.palpa");
  sql(where, "UPDATE events SET y = NULL WHERE kind = 'mark';");
  expect_refused(where, "column y: missing (NULL)");
}

TEST_F(SessionCorrupt, ViewsAndTriggersAreRefused) {
  // A view in place of a table: it could compute anything; a session has real tables.
  const auto view = good("view.palpa");
  sql(view, "ALTER TABLE events RENAME TO old_events; CREATE VIEW events AS SELECT * FROM old_events;");
  expect_refused(view, "events: table is missing");
  // Beside the tables, a view or a trigger is not Palpa's: a hand-made or hostile file.
  const auto extra_view = good("extra-view.palpa");
  sql(extra_view, "CREATE VIEW marks AS SELECT * FROM events WHERE kind = 'mark';");
  expect_refused(extra_view, "file: not a Palpa session (holds a view 'marks'; sessions have none)");
  const auto trigger = good("trigger.palpa");
  sql(trigger, "CREATE TRIGGER wipe AFTER INSERT ON events BEGIN DELETE FROM samples; END;");
  expect_refused(trigger, "file: not a Palpa session (holds a trigger 'wipe'; sessions have none)");
  EXPECT_THROW(read_session(trigger, ReadOptions{false}), SessionError);
}

TEST_F(SessionCorrupt, OnlyTheDocumentedSchemaIsReadNotWhatTheFileDefines) {
  // A generated column is evaluated on reading: here `t` would build a 400 MB blob per row
  // (46 s and 2 GB for a 5.6 kB file before this check). Refused before a row is read.
  const auto generated = good("generated.palpa");
  sql(generated,
      "CREATE TABLE s2(tick INTEGER PRIMARY KEY, t REAL GENERATED ALWAYS AS (length(zeroblob(400000000)) * 0.0) "
      "VIRTUAL, x REAL NOT NULL, y REAL NOT NULL, z REAL NOT NULL, fx REAL NOT NULL, fy REAL NOT NULL, fz REAL NOT "
      "NULL, body INTEGER, u REAL, v REAL, depth REAL, buttons INTEGER NOT NULL, overrun INTEGER NOT NULL, fault "
      "INTEGER NOT NULL); INSERT INTO s2(tick, x, y, z, fx, fy, fz, body, u, v, depth, buttons, overrun, fault) "
      "SELECT tick, x, y, z, fx, fy, fz, body, u, v, depth, buttons, overrun, fault FROM samples; DROP TABLE samples; "
      "ALTER TABLE s2 RENAME TO samples;");
  const auto started = std::chrono::steady_clock::now();
  expect_refused(generated, "its schema has column samples.t REAL notnull 0 default NULL pk 0 hidden 2");
  EXPECT_THROW(read_session(generated, ReadOptions{false}), SessionError);  // the review's header read too
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), 1.0);
  // A generated column added beside the others, an index (its expression runs on reads that
  // use it), a table of its own and a column whose type changed: each named.
  const auto added = good("added.palpa");
  sql(added, "ALTER TABLE samples ADD COLUMN w REAL GENERATED ALWAYS AS (x * 2) VIRTUAL;");
  expect_refused(added, "its schema has column samples.w REAL");
  const auto index = good("index.palpa");
  sql(index, "CREATE INDEX slow ON samples(length(zeroblob(1000)));");
  expect_refused(index, "its schema has index slow on samples");
  const auto table = good("table.palpa");
  sql(table, "CREATE TABLE notes(text TEXT);");
  expect_refused(table, "its schema has table notes on notes");
  const auto retyped = good("retyped.palpa");
  sql(retyped, "ALTER TABLE events ADD COLUMN colour TEXT;");
  expect_refused(retyped, "its schema has column events.colour TEXT");
}

TEST_F(SessionCorrupt, MoreSamplesThanASessionMayHoldAreRefusedBeforeReadingThem) {
  const auto path = good("long.palpa");  // 3000 samples
  ReadOptions options;
  EXPECT_EQ(options.max_samples, 72'000'000);  // 20 h at 1 kHz
  options.max_samples = 2999;
  expect_refused(path, "samples: 3000 rows: more than a session may hold (2999;", options);
  options.max_samples = 3000;
  EXPECT_EQ(read_session(path, options).samples.size(), 3000u);
}

TEST_F(SessionCorrupt, ALiveSessionCopiedWithoutItsWalIsNamedSo) {
  const auto live = dir_ / "live.palpa";
  SessionWriter writer(live, test::flat_case_info());
  for (std::uint64_t k = 0; k < 100; ++k) writer.append(test::sample_at(k));
  writer.commit();
  ASSERT_TRUE(std::filesystem::exists(dir_ / "live.palpa-wal"));
  std::filesystem::create_directory(dir_ / "copy");
  const auto copy = dir_ / "copy" / "live.palpa";
  std::filesystem::copy_file(live, copy);  // the .palpa alone, as a careless copy would
  const std::string reason = "file: recorded in WAL mode and holds no samples without its -wal";
  expect_refused(copy, reason);
  expect_refused(copy, reason);  // again, now that SQLite has left an empty -wal beside it
  EXPECT_EQ(read_session(live).samples.size(), 100u);  // the original, with its -wal, reads
}

}  // namespace
}  // namespace palpa::session
