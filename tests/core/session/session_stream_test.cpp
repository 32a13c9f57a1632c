// SampleStream: the samples of a session a block at a time, the same values as read_session
// holds, the same refusals with the same messages, in both formats.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "palpa/session/session_reader.hpp"
#include "palpa/session/session_writer.hpp"
#include "session_test_support.hpp"

namespace palpa::session {
namespace {

using test::ScratchDir;

void record(const std::filesystem::path& path, std::uint64_t n, const WriterOptions& options = {}) {
  SessionWriter writer(path, test::flat_case_info(), options);
  writer.event(Event{});
  for (std::uint64_t k = 0; k < n; ++k) writer.append(test::sample_at(k));
  Event end;
  end.t = static_cast<double>(n) / 1000.0;
  end.kind = EventKind::End;
  writer.event(end);
  writer.finish();
}

// Every sample of the stream, checking that no piece is larger than `largest`.
std::vector<engine::Sample> drain(SampleStream& stream, std::size_t largest) {
  std::vector<engine::Sample> out;
  for (auto piece = stream.next(); !piece.empty(); piece = stream.next()) {
    EXPECT_LE(piece.size(), largest);
    out.insert(out.end(), piece.begin(), piece.end());
  }
  EXPECT_TRUE(stream.next().empty()) << "a finished stream stays finished";
  return out;
}

// The message of the SessionError `read` throws, empty when it throws none.
template <class Read>
std::string refusal(Read&& read) {
  try {
    read();
  } catch (const SessionError& e) {
    return e.what();
  }
  return {};
}

void expect_stream_reads_as_read_session(const std::filesystem::path& path, std::size_t n) {
  const Session whole = read_session(path);
  SampleStream stream(path);
  EXPECT_EQ(stream.head().info.id, whole.info.id);
  EXPECT_EQ(stream.head().events.size(), whole.events.size());
  EXPECT_EQ(stream.head().complete, whole.complete);
  EXPECT_EQ(stream.head().format_version, whole.format_version);
  EXPECT_TRUE(stream.head().samples.empty());
  const std::optional<SampleTimes> times = stream.sample_times();
  ASSERT_TRUE(times);
  const auto samples = drain(stream, 1024);
  ASSERT_EQ(samples.size(), n);
  ASSERT_EQ(whole.samples.size(), n);
  EXPECT_EQ(stream.count(), n);
  for (std::size_t k = 0; k < n; ++k) ASSERT_TRUE(test::same_sample(samples[k], whole.samples[k])) << "sample " << k;
  EXPECT_EQ(times->first, whole.samples.front().t);
  EXPECT_EQ(times->last, whole.samples.back().t);
}

TEST(SampleStream, ReadsEverySampleAsReadSessionInBothFormats) {
  ScratchDir dir;
  // 2500: a last block part full; 2048: the rows end exactly at the end of a piece.
  for (const std::size_t n : {std::size_t{2500}, std::size_t{2048}}) {
    const auto rows = dir / ("rows" + std::to_string(n) + ".palpa");
    record(rows, n, test::kRows);
    expect_stream_reads_as_read_session(rows, n);
    const auto blocks = dir / ("blocks" + std::to_string(n) + ".palpa");
    record(blocks, n);
    expect_stream_reads_as_read_session(blocks, n);
  }
}

TEST(SampleStream, ASessionWithoutSamplesHasNoTimes) {
  ScratchDir dir;
  const auto path = dir / "empty.palpa";
  record(path, 0);
  SampleStream stream(path);
  EXPECT_FALSE(stream.sample_times());
  EXPECT_TRUE(stream.next().empty());
  EXPECT_EQ(stream.count(), 0u);
}

// A fault in the middle of the samples is found when the stream gets there, with
// read_session's message; the samples before it come out first.
TEST(SampleStream, RefusesWhatReadSessionRefusesWithTheSameMessage) {
  ScratchDir dir;
  struct Damage {
    const char* name;
    const WriterOptions* options;
    const char* sql;
  };
  const WriterOptions blocks{};
  const Damage damages[] = {
      {"backwards.palpa", &test::kRows, "UPDATE samples SET t = 0.5 WHERE tick = 1500;"},
      {"nobody.palpa", &test::kRows, "UPDATE samples SET body = 3 WHERE tick = 1501;"},
      {"noise.palpa", &blocks, "UPDATE sample_blocks SET data = randomblob(300) WHERE first_tick = 1024;"},
      {"moved.palpa", &blocks,
       "DELETE FROM sample_blocks WHERE first_tick = 1024; "
       "UPDATE sample_blocks SET first_tick = 1024 WHERE first_tick = 2048;"},
  };
  for (const auto& damage : damages) {
    const auto path = dir / damage.name;
    record(path, 2500, *damage.options);
    test::sql(path, damage.sql);
    const std::string expected = refusal([&] { read_session(path); });
    ASSERT_FALSE(expected.empty()) << damage.name << " was read";
    SampleStream stream(path);
    std::size_t before = 0;
    const std::string got = refusal([&] {
      for (auto piece = stream.next(); !piece.empty(); piece = stream.next()) before += piece.size();
    });
    EXPECT_EQ(got, expected) << damage.name;
    EXPECT_GE(before, 1024u) << damage.name << ": the first block is whole";
  }
}

TEST(SampleStream, ASessionOverTheLimitIsRefusedBeforeASampleIsRead) {
  ScratchDir dir;
  const auto path = dir / "long.palpa";
  record(path, 3000);
  const std::string expected = refusal([&] {
    ReadOptions options;
    options.max_samples = 2000;
    read_session(path, options);
  });
  EXPECT_NE(expected.find("more than a session may hold (2000"), std::string::npos) << expected;
  EXPECT_EQ(refusal([&] { SampleStream stream(path, 2000); }), expected);
}

}  // namespace
}  // namespace palpa::session
