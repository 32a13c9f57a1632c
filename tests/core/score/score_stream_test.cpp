// score_stream: the same score as score_session on the whole session, read block by block
// (format 2) or a thousand rows at a time (format 1), for sessions complete or cut short.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include <sqlite3.h>

#include "palpa/score/score.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/session/session_upgrade.hpp"

namespace palpa::score {
namespace {

namespace fs = std::filesystem;

class ScoreStream : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "palpa-score-stream-XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  // A copy of a sample session, with `sql` run on it (empty: as it is).
  fs::path copy(const std::string& name, const std::string& sql = {}) {
    const fs::path to = dir_ / (name + "-" + std::to_string(copies_++) + ".palpa");
    fs::copy_file(fs::path(PALPA_SOURCE_DIR) / "data/sessions" / (name + ".palpa"), to);
    if (!sql.empty()) {
      sqlite3* db = nullptr;
      EXPECT_EQ(sqlite3_open(to.c_str(), &db), SQLITE_OK);
      EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
      sqlite3_close(db);
    }
    return to;
  }
  fs::path compacted(const fs::path& from) {
    const fs::path to = dir_ / (from.stem().string() + "-blocks.palpa");
    session::write_compacted_copy(from, to);
    return to;
  }
  fs::path dir_;
  int copies_ = 0;
};

void expect_same_score(const fs::path& path) {
  const Score whole = score_session(session::read_session(path), path.string());
  session::SampleStream stream(path);
  const Score streamed = score_stream(stream, path.string());
  EXPECT_EQ(to_json(streamed, true).dump(), to_json(whole, true).dump()) << path;
  EXPECT_GT(streamed.samples, 1024u) << "more than one piece";
}

TEST_F(ScoreStream, SameScoreAsTheWholeSessionInBothFormats) {
  for (const char* name : {"expert", "sloppy", "light"}) {
    const fs::path rows = copy(name);
    expect_same_score(rows);
    expect_same_score(compacted(rows));
  }
}

// Without start and end events the timeline runs from the first to the last sample,
// which the stream looks up before it reads them; a pause left open runs to that end.
TEST_F(ScoreStream, SameScoreWithoutStartOrEndEvents) {
  const fs::path cut = copy("sloppy", "DELETE FROM events WHERE kind IN ('start', 'end');"
                                      "INSERT INTO events(t, kind, note) VALUES (20.0, 'pause', '');");
  expect_same_score(cut);
  expect_same_score(compacted(cut));
  session::SampleStream stream(cut);
  EXPECT_FALSE(score_stream(stream, cut.string()).complete);
}

}  // namespace
}  // namespace palpa::score
