// Writing a session and reading it back: every field, bit-exact doubles, events of every
// kind, loop statistics, standing marks, and the writer's refusals.
#include <gtest/gtest.h>

#include <fstream>
#include <limits>

#include "palpa/engine/loop_stats.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/session/session_writer.hpp"
#include "session_test_support.hpp"

namespace palpa::session {
namespace {

using test::flat_case_info;
using test::sample_at;
using test::ScratchDir;

Event make_event(double t, EventKind kind, std::int64_t mark = -1, std::array<double, 3> at = {}, std::string note = {}) {
  Event e;
  e.t = t;
  e.kind = kind;
  e.mark = mark;
  e.position = at;
  e.note = std::move(note);
  return e;
}

TEST(SessionEventKind, NamesRoundTripAndUnknownNamesAreRefused) {
  for (auto kind : {EventKind::Start, EventKind::Mark, EventKind::Unmark, EventKind::Pause, EventKind::Resume,
                    EventKind::End}) {
    EXPECT_EQ(event_kind_from_string(to_string(kind)), kind);
  }
  EXPECT_EQ(to_string(EventKind::Unmark), "unmark");
  EXPECT_FALSE(event_kind_from_string("Mark"));  // names are lower case, as stored
  EXPECT_FALSE(event_kind_from_string(""));
}

TEST(SessionStandingMarks, PlacedAndNotRemovedInPlacementOrder) {
  const std::vector<Event> events{
      make_event(0.0, EventKind::Start),
      make_event(1.0, EventKind::Mark, 1, {0.01, 0.02, 0.03}),
      make_event(2.0, EventKind::Mark, 2, {0.04, 0.05, 0.06}),
      make_event(2.5, EventKind::Unmark, 9),  // unknown id: ignored
      make_event(3.0, EventKind::Mark, 3, {0.07, 0.08, 0.09}),
      make_event(4.0, EventKind::Unmark, 1),
      make_event(5.0, EventKind::Pause),
      make_event(6.0, EventKind::Unmark, 1),  // already removed: ignored
      make_event(7.0, EventKind::End),
  };
  const auto marks = standing_marks(events);
  ASSERT_EQ(marks.size(), 2u);
  EXPECT_EQ(marks[0].id, 2);
  EXPECT_EQ(marks[0].t, 2.0);
  EXPECT_EQ(marks[0].position[1], 0.05);
  EXPECT_EQ(marks[1].id, 3);
  EXPECT_EQ(marks[1].position[2], 0.09);
  EXPECT_TRUE(standing_marks({}).empty());
}

TEST(SessionFile, EverythingWrittenIsReadBackExactly) {
  ScratchDir dir;
  const auto path = dir / "s.palpa";
  auto info = flat_case_info();
  info.seed = 18446744073709551557ull;  // above 2^63: must survive as unsigned decimal text
  info.rate_hz = 1000.0 / 3.0;
  info.extra = {{"style", "free"}, {"gui", {{"mode", "2d"}, {"zoom", 0.1}}}, {"list", {1, 2.5, "x"}}};

  engine::LoopStats stats;
  for (int k = 0; k < 1000; ++k) stats.record(1e-3 + 1e-6 * (k % 10), 2e-4 + 1e-6 * (k % 5), k % 250 == 0);

  const std::uint64_t n = 3000;
  {
    SessionWriter writer(path, info, test::kRows);
    EXPECT_EQ(writer.path(), path);
    writer.event(make_event(0.0, EventKind::Start, -1, {}, "begin"));
    for (std::uint64_t k = 0; k < n; ++k) {
      writer.append(sample_at(k));
      if (k == 1000) writer.commit();
    }
    EXPECT_EQ(writer.samples_written(), n);
    // Events written out of time order come back in time order.
    writer.event(make_event(2.0, EventKind::Unmark, 1));
    writer.event(make_event(1.0, EventKind::Mark, 1, {1.0 / 3.0, -0.0125, 0.0305}));
    writer.event(make_event(1.5, EventKind::Mark, 2, {0.02, 2.0 / 7.0, 1e-17}));
    writer.event(make_event(2.2, EventKind::Pause));
    writer.event(make_event(2.4, EventKind::Resume, -1, {}, "back"));
    writer.event(make_event(2.999, EventKind::End, -1, {}, "time is up"));
    writer.set_loop_stats(stats);
    writer.finish();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "s.palpa-wal"));
  EXPECT_FALSE(std::filesystem::exists(dir / "s.palpa-shm"));

  const Session s = read_session(path);
  EXPECT_EQ(s.info.id, info.id);
  EXPECT_EQ(s.info.trainee, info.trainee);
  EXPECT_EQ(s.info.device, info.device);
  EXPECT_EQ(s.info.software_version, info.software_version);
  EXPECT_EQ(s.info.started_at, info.started_at);
  EXPECT_TRUE(test::same_bits(s.info.rate_hz, info.rate_hz));
  EXPECT_EQ(s.info.case_source, info.case_source);
  EXPECT_EQ(s.info.case_document, info.case_document);
  ASSERT_TRUE(s.info.seed.has_value());
  EXPECT_EQ(*s.info.seed, 18446744073709551557ull);
  EXPECT_EQ(s.info.extra, info.extra);

  ASSERT_EQ(s.samples.size(), n);
  std::uint64_t in_contact = 0;
  for (std::uint64_t k = 0; k < n; ++k) {
    ASSERT_TRUE(test::same_sample(s.samples[k], sample_at(k))) << "tick " << k;
    in_contact += s.samples[k].body >= 0 ? 1u : 0u;
  }
  EXPECT_EQ(in_contact, 2000u);  // ticks not divisible by 3

  ASSERT_EQ(s.events.size(), 7u);
  const std::vector<EventKind> kinds{EventKind::Start, EventKind::Mark,   EventKind::Mark, EventKind::Unmark,
                                     EventKind::Pause, EventKind::Resume, EventKind::End};
  for (std::size_t i = 0; i < kinds.size(); ++i) EXPECT_EQ(s.events[i].kind, kinds[i]) << i;
  EXPECT_EQ(s.events[0].note, "begin");
  EXPECT_EQ(s.events[0].mark, -1);
  EXPECT_EQ(s.events[1].mark, 1);
  EXPECT_TRUE(test::same_bits(s.events[1].position[0], 1.0 / 3.0));
  EXPECT_EQ(s.events[1].position[1], -0.0125);
  EXPECT_TRUE(test::same_bits(s.events[2].position[1], 2.0 / 7.0));
  EXPECT_EQ(s.events[2].position[2], 1e-17);
  EXPECT_EQ(s.events[3].mark, 1);
  EXPECT_EQ(s.events[5].note, "back");
  EXPECT_EQ(s.events[6].note, "time is up");
  EXPECT_TRUE(s.complete);
  const auto marks = standing_marks(s.events);
  ASSERT_EQ(marks.size(), 1u);
  EXPECT_EQ(marks[0].id, 2);

  ASSERT_TRUE(s.loop_stats.is_object());
  EXPECT_EQ(s.loop_stats["ticks"], 1000);
  EXPECT_EQ(s.loop_stats["missed"], 4);
  EXPECT_EQ(s.loop_stats["period_s"]["max"].get<double>(), stats.max_period());
  EXPECT_EQ(s.loop_stats["period_s"]["p50"].get<double>(), stats.period_percentile(0.5));
  EXPECT_EQ(s.loop_stats["compute_s"]["p999"].get<double>(), stats.compute_percentile(0.999));
  EXPECT_EQ(s.loop_stats["compute_s"]["mean"].get<double>(), stats.mean_compute());
  EXPECT_NEAR(s.loop_stats["rate_hz"].get<double>(), 1.0 / stats.mean_period(), 1e-9);

  // A fast listing reads everything but the samples.
  const Session listing = read_session(path, ReadOptions{false});
  EXPECT_TRUE(listing.samples.empty());
  EXPECT_EQ(listing.events.size(), 7u);
  EXPECT_EQ(listing.info.trainee, info.trainee);
}

TEST(SessionFile, WithoutSeedOrStatsTheyReadBackAbsent) {
  ScratchDir dir;
  Session session;
  session.info = flat_case_info();
  session.info.id.clear();          // filled in by the writer
  session.info.started_at.clear();  // likewise (now, UTC)
  session.samples = {sample_at(1), sample_at(2)};
  session.events = {make_event(0.0, EventKind::Start)};
  write_session(dir / "a.palpa", session, test::kRows);
  const auto s = read_session(dir / "a.palpa");
  EXPECT_FALSE(s.info.seed.has_value());
  EXPECT_TRUE(s.loop_stats.is_null());
  EXPECT_FALSE(s.complete);  // no End event
  EXPECT_EQ(s.info.id.size(), 32u);
  EXPECT_EQ(s.info.started_at.size(), 20u);  // YYYY-MM-DDTHH:MM:SSZ
  EXPECT_EQ(s.info.started_at.back(), 'Z');
  EXPECT_EQ(s.samples.size(), 2u);
  EXPECT_TRUE(test::same_sample(s.samples[1], sample_at(2)));

  // write_session keeps the loop statistics given as JSON.
  session.loop_stats = {{"ticks", 2}, {"missed", 0}};
  session.events.push_back(make_event(0.5, EventKind::End));
  write_session(dir / "b.palpa", session, test::kRows);
  const auto b = read_session(dir / "b.palpa");
  EXPECT_EQ(b.loop_stats, session.loop_stats);
  EXPECT_TRUE(b.complete);
}

TEST(SessionFile, NegativeZeroReadsBackAsZero) {
  // SQLite stores integral REAL values as integers, so -0.0 comes back as +0.0 (equal, but
  // not the same bits); docs/session-format.md says so. Every other double is exact.
  ScratchDir dir;
  SessionWriter writer(dir / "z.palpa", flat_case_info());
  auto s = sample_at(3);
  s.force = {-0.0, 0.0, 1e300};
  writer.append(s);
  writer.finish();
  const auto back = read_session(dir / "z.palpa").samples.at(0);
  EXPECT_EQ(back.force[0], 0.0);
  EXPECT_FALSE(std::signbit(back.force[0]));
  EXPECT_TRUE(test::same_bits(back.force[2], 1e300));
}

TEST(SessionFile, AWriterDestroyedWithoutFinishLeavesAReadableIncompleteSession) {
  ScratchDir dir;
  const auto path = dir / "cut.palpa";
  {
    SessionWriter writer(path, flat_case_info());
    writer.event(make_event(0.0, EventKind::Start));
    for (std::uint64_t k = 0; k < 500; ++k) writer.append(sample_at(k));
    writer.commit();
    for (std::uint64_t k = 500; k < 700; ++k) writer.append(sample_at(k));  // committed by the destructor
  }
  const auto s = read_session(path);
  EXPECT_FALSE(s.complete);
  EXPECT_TRUE(s.loop_stats.is_null());
  ASSERT_EQ(s.samples.size(), 700u);
  EXPECT_TRUE(test::same_sample(s.samples[699], sample_at(699)));
}

TEST(SessionWriter, RefusesAnExistingFileAndLeavesItUntouched) {
  ScratchDir dir;
  const auto path = dir / "taken.palpa";
  {
    std::ofstream(path) << "precious";
  }
  try {
    SessionWriter writer(path, flat_case_info());
    FAIL() << "an existing file was opened for writing";
  } catch (const SessionError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path.string() + ": file: already exists", 0), 0u) << e.what();
  }
  std::ifstream in(path);
  std::string content;
  in >> content;
  EXPECT_EQ(content, "precious");

  // A finished session is refused the same way.
  write_session(dir / "done.palpa", Session{flat_case_info(), {}, {}, nullptr, false});
  EXPECT_THROW(SessionWriter(dir / "done.palpa", flat_case_info()), SessionError);
}

TEST(SessionWriter, AMissingFolderOrInvalidInfoIsAClearError) {
  ScratchDir dir;
  const auto path = dir / "no-such-folder" / "s.palpa";
  try {
    SessionWriter writer(path, flat_case_info());
    FAIL();
  } catch (const SessionError& e) {
    EXPECT_EQ(e.file(), path.string());
    EXPECT_EQ(e.where(), "file");
    EXPECT_NE(e.reason().find("does not exist"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "no-such-folder"));  // not created

  const auto refused = [&](SessionInfo info, const std::string& where) {
    try {
      SessionWriter writer(dir / "bad.palpa", info);
      ADD_FAILURE() << "accepted; expected a problem at " << where;
    } catch (const SessionError& e) {
      EXPECT_EQ(e.where().rfind(where, 0), 0u) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.palpa")) << "a refused session leaves no file";
  };
  auto info = flat_case_info();
  info.trainee.clear();
  refused(info, "trainee");
  info = flat_case_info();
  info.rate_hz = 0.0;
  refused(info, "rate_hz");
  info.rate_hz = std::nan("");
  refused(info, "rate_hz");
  info = flat_case_info();
  info.case_document = nlohmann::json::array();
  refused(info, "case");
  info.case_document = {{"format", "palpa-case"}, {"version", 1}};  // an object, but no bodies
  refused(info, "case /");
}

TEST(SessionWriter, RefusesSamplesAndEventsTheReaderWouldReject) {
  ScratchDir dir;
  SessionWriter writer(dir / "s.palpa", flat_case_info());
  auto s = sample_at(1);
  s.force[1] = std::numeric_limits<double>::infinity();
  try {
    writer.append(s);
    FAIL();
  } catch (const SessionError& e) {
    EXPECT_EQ(e.where(), "samples tick 0: column fy") << e.what();
  }
  EXPECT_EQ(writer.samples_written(), 0u);
  EXPECT_THROW(writer.event(make_event(1.0, EventKind::Mark, 0, {0.0, 0.0, 0.0})), SessionError);
  EXPECT_THROW(writer.event(make_event(std::nan(""), EventKind::Pause)), SessionError);
  writer.append(sample_at(0));
  writer.finish();
  EXPECT_THROW(writer.append(sample_at(1)), SessionError);  // finished: closed for writing
  EXPECT_EQ(read_session(dir / "s.palpa").samples.size(), 1u);
}

TEST(SessionWriter, RefusesTimeGoingBackwardsAndBodiesTheCaseDoesNotHave) {
  ScratchDir dir;
  SessionWriter writer(dir / "s.palpa", flat_case_info());
  auto s = sample_at(500);  // t = 0.5 s
  writer.append(s);
  s.t = 0.4;
  try {
    writer.append(s);
    FAIL();
  } catch (const SessionError& e) {
    EXPECT_EQ(e.where(), "samples tick 1: column t") << e.what();
    EXPECT_EQ(e.reason(), "time goes backwards (0.4 s after 0.5 s)") << e.what();
  }
  s = sample_at(501);
  s.body = 1;  // flat-5x5 has one body
  try {
    writer.append(s);
    FAIL();
  } catch (const SessionError& e) {
    EXPECT_EQ(e.where(), "samples tick 1: column body") << e.what();
  }
  s.t = 0.5;  // equal times are allowed (the reader refuses only t decreasing)
  s.body = 0;
  writer.append(s);
  writer.finish();
  EXPECT_EQ(read_session(dir / "s.palpa").samples.size(), 2u);
}

TEST(SessionWriter, AppendRepairingStoresBadTicksAsFaultsInsteadOfRefusingThem) {
  ScratchDir dir;
  const auto path = dir / "s.palpa";
  SessionWriter writer(path, flat_case_info(), test::kRows);
  EXPECT_TRUE(writer.append_repairing(sample_at(1)));  // tick 1: in contact, t = 0.001
  auto s = sample_at(2);
  s.fault = false;
  s.position[1] = std::nan("");
  s.force[2] = -std::numeric_limits<double>::infinity();
  EXPECT_FALSE(writer.append_repairing(s));
  s = sample_at(4);
  s.t = 0.0005;  // before the previous tick
  EXPECT_FALSE(writer.append_repairing(s));
  s = sample_at(5);
  s.body = 7;  // no such body
  EXPECT_FALSE(writer.append_repairing(s));
  s = sample_at(7);
  s.depth = std::nan("");
  EXPECT_FALSE(writer.append_repairing(s));
  s = sample_at(8);
  s.t = std::nan("");
  EXPECT_FALSE(writer.append_repairing(s));
  EXPECT_TRUE(writer.append_repairing(sample_at(10)));
  EXPECT_EQ(writer.samples_written(), 7u);
  EXPECT_EQ(writer.samples_repaired(), 5u);
  writer.set_loop_stats(engine::LoopStats{}, 3);
  writer.finish();

  const auto back = read_session(path);
  ASSERT_EQ(back.samples.size(), 7u);
  EXPECT_TRUE(test::same_sample(back.samples[0], sample_at(1)));
  const auto& nan_sample = back.samples[1];
  EXPECT_TRUE(nan_sample.fault);
  EXPECT_EQ(nan_sample.position[1], 0.0);
  EXPECT_EQ(nan_sample.force[2], 0.0);
  EXPECT_EQ(nan_sample.position[0], sample_at(2).position[0]);  // the finite values are kept
  EXPECT_EQ(back.samples[2].t, 0.002);                           // the previous tick's t
  EXPECT_TRUE(back.samples[2].fault);
  EXPECT_EQ(back.samples[3].body, -1);  // unknown body: out of contact
  EXPECT_TRUE(back.samples[3].fault);
  EXPECT_EQ(back.samples[4].body, -1);
  EXPECT_EQ(back.samples[5].t, 0.007);
  EXPECT_TRUE(test::same_sample(back.samples[6], sample_at(10)));
  EXPECT_EQ(back.loop_stats["dropped"].get<std::uint64_t>(), 3u);
  EXPECT_EQ(back.loop_stats["repaired"].get<std::uint64_t>(), 5u);
}

TEST(SessionWriter, TextThatIsNotUtf8IsRefusedWithTheFieldNamedAndNoFileLeft) {
  ScratchDir dir;
  const auto path = dir / "bad.palpa";
  const auto refused = [&](const SessionInfo& info, const std::string& where) {
    try {
      SessionWriter writer(path, info);
      ADD_FAILURE() << "accepted; expected a problem at " << where;
    } catch (const SessionError& e) {
      EXPECT_EQ(e.where(), where) << e.what();
      EXPECT_NE(e.reason().find("UTF-8"), std::string::npos) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not a SessionError: " << e.what();
    }
    for (const char* suffix : {"", "-wal", "-shm", "-journal"}) {
      EXPECT_FALSE(std::filesystem::exists(path.string() + suffix)) << suffix;
    }
  };
  auto info = flat_case_info();
  info.extra = {{"note", "caf\xE9"}};  // Latin-1, not UTF-8
  refused(info, "extra");
  info = flat_case_info();
  info.trainee = "M\xFCller";
  refused(info, "trainee");
  info.trainee = "\xC0\x80";  // an overlong NUL
  refused(info, "trainee");
  info.trainee = "\xED\xA0\x80";  // a UTF-16 surrogate
  refused(info, "trainee");
  info.trainee = "abc\xE2\x82";  // cut short
  refused(info, "trainee");
  info = flat_case_info();
  info.case_source = "cases/\xFF.json";
  refused(info, "case_source");
  info = flat_case_info();
  info.case_document["comment"] = "\x80";
  refused(info, "case");

  info = flat_case_info();
  info.trainee = "Zo\xC3\xAB \xE5\xAD\xA6\xE7\x94\x9F \xF0\x9F\x99\x82";  // "Zoë 学生 🙂": valid
  {
    SessionWriter writer(path, info);
    Event e;
    e.kind = EventKind::Pause;
    e.note = "stopped at \xFF";
    try {
      writer.event(e);
      ADD_FAILURE() << "a non-UTF-8 note was accepted";
    } catch (const SessionError& error) {
      EXPECT_EQ(error.where(), "events pause at t=0: note") << error.what();
    }
    writer.finish();
  }
  EXPECT_EQ(read_session(path).info.trainee, info.trainee);
}

TEST(SessionWriter, FinishWithAReaderOpenCommitsAndLeavesWalModeAsAWarning) {
  ScratchDir dir;
  const auto path = dir / "watched.palpa";
  SessionWriter writer(dir / "plain.palpa", flat_case_info());
  writer.finish();
  EXPECT_EQ(writer.warning(), "");  // alone: one file, no warning

  SessionWriter live(path, flat_case_info());
  for (std::uint64_t k = 0; k < 100; ++k) live.append(sample_at(k));
  live.event(make_event(0.1, EventKind::End));
  live.commit();
  // Another program (a viewer) has the live file open, as Python or sqlite3 would.
  sqlite3* viewer = nullptr;
  ASSERT_EQ(sqlite3_open_v2(path.string().c_str(), &viewer, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(viewer, "SELECT count(*) FROM samples", nullptr, nullptr, nullptr), SQLITE_OK);
  EXPECT_NO_THROW(live.finish());
  EXPECT_NE(live.warning().find("left in write-ahead-log mode"), std::string::npos) << live.warning();
  const auto s = read_session(path);  // everything is there, with the viewer still open
  EXPECT_TRUE(s.complete);
  EXPECT_EQ(s.samples.size(), 100u);
  sqlite3_close(viewer);
  EXPECT_EQ(read_session(path).samples.size(), 100u);
}

}  // namespace
}  // namespace palpa::session
