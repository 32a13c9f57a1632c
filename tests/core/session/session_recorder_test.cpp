// The recorder thread on a live haptic loop: every tick the loop produced is in the file,
// in order, with the events and the loop statistics, and the finished file stands alone.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <thread>

#include "palpa/engine/virtual_device.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/session/session_recorder.hpp"
#include "session_test_support.hpp"

namespace palpa::session {
namespace {

SessionInfo default_case_info() {
  auto info = test::flat_case_info();
  info.case_source = "data/cases/default.json";
  info.case_document = io::to_json(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"));
  return info;
}

std::int64_t query_int(const std::filesystem::path& file, const char* sql) {
  sqlite3* db = nullptr;
  sqlite3_open_v2(file.string().c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
  sqlite3_stmt* st = nullptr;
  sqlite3_prepare_v2(db, sql, -1, &st, nullptr);
  const std::int64_t value = sqlite3_step(st) == SQLITE_ROW ? sqlite3_column_int64(st, 0) : -999;
  sqlite3_finalize(st);
  sqlite3_close(db);
  return value;
}

TEST(SessionRecorder, RecordsEveryTickOfALiveLoopWithEventsAndStatistics) {
  test::ScratchDir dir;
  const auto path = dir / "live.palpa";
  const auto info = default_case_info();
  const auto scene = scene::Scene::build(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"), "default");
  engine::VirtualDevice device(0.01);
  device.set_target(palpa::Vec3(0.0245, 0.02, 0.030));  // pressing into the default case
  engine::Engine engine(scene, device);
  engine::RealtimeLoop loop(engine);
  SessionWriter writer(path, info);
  SessionRecorder recorder(loop, writer, 0.05);
  loop.start();
  recorder.start();
  Event e;
  e.kind = EventKind::Start;
  recorder.event(e);
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  e.t = 0.15;
  e.kind = EventKind::Mark;
  e.mark = 1;
  e.position = {0.0245, 0.02, 0.030};
  recorder.event(e);
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  // Mid-session the committed part is already readable by another connection.
  EXPECT_GT(read_session(path).samples.size(), 0u);
  loop.stop();
  recorder.finish(0.3, "time is up");
  EXPECT_EQ(recorder.error(), "");

  EXPECT_FALSE(std::filesystem::exists(dir / "live.palpa-wal"));
  EXPECT_FALSE(std::filesystem::exists(dir / "live.palpa-shm"));
  const Session s = read_session(path);
  const auto& stats = loop.stats();
  EXPECT_EQ(loop.dropped_samples(), 0u);
  ASSERT_EQ(s.samples.size(), stats.ticks() - loop.dropped_samples());
  ASSERT_GT(s.samples.size(), 30u);  // 0.3 s at 1 kHz, even on a loaded machine
  // Finished: compacted into format 2's blocks, every tick from 0 on.
  EXPECT_EQ(s.format_version, 2);
  EXPECT_EQ(query_int(path, "SELECT min(first_tick) FROM sample_blocks"), 0);
  EXPECT_EQ(query_int(path, "SELECT sum(count) FROM sample_blocks"), static_cast<std::int64_t>(s.samples.size()));
  for (std::size_t k = 1; k < s.samples.size(); ++k) ASSERT_GT(s.samples[k].t, s.samples[k - 1].t) << k;
  bool pressed = false;
  for (const auto& sample : s.samples) pressed = pressed || (sample.body == 0 && sample.depth > 0.0);
  EXPECT_TRUE(pressed);

  ASSERT_EQ(s.events.size(), 3u);
  EXPECT_EQ(s.events[0].kind, EventKind::Start);
  EXPECT_EQ(s.events[1].kind, EventKind::Mark);
  EXPECT_EQ(s.events[2].kind, EventKind::End);
  EXPECT_EQ(s.events[2].t, 0.3);
  EXPECT_EQ(s.events[2].note, "time is up");
  EXPECT_TRUE(s.complete);
  ASSERT_TRUE(s.loop_stats.is_object());
  EXPECT_EQ(s.loop_stats["ticks"].get<std::uint64_t>(), stats.ticks());
  // Dropped ticks leave a trace (none here: the ring never filled), and so do repaired ones.
  ASSERT_TRUE(s.loop_stats.contains("dropped")) << s.loop_stats.dump();
  EXPECT_EQ(s.loop_stats["dropped"].get<std::uint64_t>(), loop.dropped_samples());
  EXPECT_EQ(s.loop_stats["repaired"].get<std::uint64_t>(), 0u);
  EXPECT_GT(s.loop_stats["compute_s"]["p50"].get<double>(), 0.0);
}

TEST(SessionRecorder, AQueuedEndIsNotDoubled) {
  test::ScratchDir dir;
  const auto scene = scene::Scene::build(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"), "default");
  engine::VirtualDevice device(0.01);
  engine::Engine engine(scene, device);
  {
    engine::RealtimeLoop loop(engine);
    SessionWriter writer(dir / "end.palpa", default_case_info());
    SessionRecorder recorder(loop, writer);
    loop.start();
    recorder.start();
    Event end;
    end.t = 0.05;
    end.kind = EventKind::End;
    end.note = "trainee finished";
    recorder.event(end);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    loop.stop();
    recorder.finish(0.06, "not this one");
    const auto s = read_session(dir / "end.palpa");
    ASSERT_EQ(s.events.size(), 1u);
    EXPECT_EQ(s.events[0].note, "trainee finished");
    EXPECT_TRUE(s.complete);
  }
}

// Holds the write lock of a session from another connection, so that the writer thread's
// next insert fails ("database is locked" after its busy timeout): a real write failure.
class WriteLockHolder {
 public:
  explicit WriteLockHolder(const std::filesystem::path& file) {
    if (sqlite3_open(file.string().c_str(), &db_) != SQLITE_OK) throw std::runtime_error("cannot open");
    if (sqlite3_exec(db_, "BEGIN IMMEDIATE", nullptr, nullptr, nullptr) != SQLITE_OK) {
      throw std::runtime_error(sqlite3_errmsg(db_));
    }
  }
  ~WriteLockHolder() { release(); }
  void release() {
    if (db_ == nullptr) return;
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    sqlite3_close(db_);
    db_ = nullptr;
  }

 private:
  sqlite3* db_ = nullptr;
};

TEST(SessionRecorder, AWriterErrorIsKeptNotFatalAndTheSessionStaysIncomplete) {
  test::ScratchDir dir;
  const auto scene = scene::Scene::build(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"), "default");
  engine::VirtualDevice device(0.01);
  engine::Engine engine(scene, device);
  engine::RealtimeLoop loop(engine);
  const auto path = dir / "error.palpa";
  SessionWriter writer(path, default_case_info());
  SessionRecorder recorder(loop, writer, 0.05);
  WriteLockHolder lock(path);  // before the first insert: the thread's first drain fails
  loop.start();
  recorder.start();
  // Wait for the failure (the writer's busy timeout is 200 ms); no assertion on the time.
  for (int k = 0; k < 500 && recorder.error().empty(); ++k) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  lock.release();
  loop.stop();
  EXPECT_NO_THROW(recorder.finish(0.1));
  EXPECT_NE(recorder.error().find("database is locked"), std::string::npos) << recorder.error();
  const auto s = read_session(path);
  EXPECT_FALSE(s.complete);  // no End after a failure: the session is cut short
  EXPECT_TRUE(s.samples.empty());
}

Session record_briefly(const std::filesystem::path& path, const std::function<void(SessionRecorder&)>& during,
                       const std::function<void(SessionRecorder&, engine::RealtimeLoop&)>& end) {
  const auto scene = scene::Scene::build(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"), "default");
  engine::VirtualDevice device(0.01);
  engine::Engine engine(scene, device);
  engine::RealtimeLoop loop(engine);
  SessionWriter writer(path, default_case_info());
  SessionRecorder recorder(loop, writer, 0.05);
  loop.start();
  recorder.start();
  during(recorder);
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  end(recorder, loop);
  EXPECT_EQ(recorder.error(), "");
  return read_session(path);
}

TEST(SessionRecorder, FinishAfterStopStillWritesTheEndAndEventsAfterStopAreRefused) {
  test::ScratchDir dir;
  const auto s = record_briefly(
      dir / "stopped.palpa", [](SessionRecorder&) {},
      [](SessionRecorder& recorder, engine::RealtimeLoop& loop) {
        loop.stop();
        recorder.stop();
        recorder.stop();  // a second stop does nothing
        Event late;
        late.t = 0.2;
        late.kind = EventKind::Pause;
        try {
          recorder.event(late);
          ADD_FAILURE() << "an event after stop() was accepted";
        } catch (const SessionError& e) {
          EXPECT_EQ(e.where(), "events") << e.what();
          EXPECT_NE(e.reason().find("stopped"), std::string::npos) << e.what();
        }
        recorder.finish(0.25, "stopped first");
      });
  EXPECT_TRUE(s.complete);
  ASSERT_EQ(s.events.size(), 1u);
  EXPECT_EQ(s.events[0].kind, EventKind::End);
  EXPECT_EQ(s.events[0].t, 0.25);
  EXPECT_EQ(s.events[0].note, "stopped first");
  ASSERT_TRUE(s.loop_stats.is_object());  // stored by the first stop()
  EXPECT_GT(s.samples.size(), 0u);
}

TEST(SessionRecorder, BadEventsAreRefusedByEventAndTheRecordingGoesOn) {
  test::ScratchDir dir;
  const auto s = record_briefly(
      dir / "events.palpa",
      [](SessionRecorder& recorder) {
        Event bad;
        bad.t = 0.01;
        bad.kind = EventKind::Mark;
        bad.mark = 0;
        try {
          recorder.event(bad);
          ADD_FAILURE() << "mark id 0 was accepted";
        } catch (const SessionError& e) {
          EXPECT_NE(e.reason().find("a mark id must be >= 1, not 0"), std::string::npos) << e.what();
        }
        bad.mark = 1;
        bad.position = {0.01, std::nan(""), 0.0};
        EXPECT_THROW(recorder.event(bad), SessionError);
        bad.position = {0.01, 0.02, 0.03};
        bad.t = std::numeric_limits<double>::infinity();
        EXPECT_THROW(recorder.event(bad), SessionError);
        bad.t = 0.01;
        bad.note = "\xff";
        EXPECT_THROW(recorder.event(bad), SessionError);
        bad.note = "left upper quadrant";
        recorder.event(bad);  // the good one after the bad ones is recorded
      },
      [](SessionRecorder& recorder, engine::RealtimeLoop& loop) {
        std::this_thread::sleep_for(std::chrono::milliseconds(100));  // several commits
        loop.stop();
        recorder.finish(0.2);
      });
  EXPECT_TRUE(s.complete);
  ASSERT_EQ(s.events.size(), 2u);
  EXPECT_EQ(s.events[0].kind, EventKind::Mark);
  EXPECT_EQ(s.events[0].note, "left upper quadrant");
  EXPECT_EQ(s.events[1].kind, EventKind::End);
}

TEST(SessionRecorder, ACommitIntervalOutsideZeroToOneSecondIsRefused) {
  test::ScratchDir dir;
  const auto scene = scene::Scene::build(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"), "default");
  engine::VirtualDevice device(0.01);
  engine::Engine engine(scene, device);
  engine::RealtimeLoop loop(engine);
  SessionWriter writer(dir / "interval.palpa", default_case_info());
  for (double interval : {0.0, -0.25, 1.5, std::nan(""), std::numeric_limits<double>::infinity()}) {
    try {
      SessionRecorder recorder(loop, writer, interval);
      ADD_FAILURE() << "commit interval " << interval << " was accepted";
    } catch (const SessionError& e) {
      EXPECT_EQ(e.where(), "commit_interval") << e.what();
    }
  }
  EXPECT_NO_THROW(SessionRecorder(loop, writer, 1.0));
}

}  // namespace
}  // namespace palpa::session
