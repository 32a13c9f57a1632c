// The recorder thread on a live haptic loop: every tick the loop produced is in the file,
// in order, with the events and the loop statistics, and the finished file stands alone.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
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
  device.set_target(engine::Vec3(0.0245, 0.02, 0.030));  // pressing into the default case
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
  EXPECT_EQ(query_int(path, "SELECT min(tick) FROM samples"), 0);
  EXPECT_EQ(query_int(path, "SELECT max(tick) FROM samples"), static_cast<std::int64_t>(s.samples.size()) - 1);
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
  EXPECT_GT(s.loop_stats["compute_s"]["p50"].get<double>(), 0.0);
}

TEST(SessionRecorder, AQueuedEndIsNotDoubledAndAWriterErrorIsKeptNotFatal) {
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
  {
    engine::RealtimeLoop loop(engine);
    SessionWriter writer(dir / "error.palpa", default_case_info());
    SessionRecorder recorder(loop, writer);
    loop.start();
    recorder.start();
    Event bad;
    bad.kind = EventKind::Mark;
    bad.mark = 0;  // the writer refuses it: the thread must keep the error, not terminate
    recorder.event(bad);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    loop.stop();
    recorder.finish(0.1);
    EXPECT_NE(recorder.error().find("mark id must be >= 1"), std::string::npos) << recorder.error();
    const auto s = read_session(dir / "error.palpa");
    EXPECT_FALSE(s.complete);  // the End event came after the error and was not written
  }
}

}  // namespace
}  // namespace palpa::session
