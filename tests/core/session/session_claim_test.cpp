// Claiming a session's name: a process killed while creating a session never blocks the
// next run with that name; of writers racing for one name exactly one gets it; a writer
// meeting a live recording is told that another process has the file.
#include <cstdio>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "palpa/session/session_reader.hpp"
#include "palpa/session/session_writer.hpp"
#include "session_test_support.hpp"

namespace palpa::session {
namespace {

using test::ScratchDir;

std::vector<std::string> names_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& n : names) text += n + " ";
  return text;
}

// The id of a process that has exited and been reaped: no process runs under it.
pid_t gone_pid() {
  const pid_t child = fork();
  if (child == 0) _exit(0);
  int status = 0;
  waitpid(child, &status, 0);
  return child;
}

void record_one(const std::filesystem::path& path, int samples) {
  SessionWriter writer(path, test::flat_case_info());
  for (int k = 0; k < samples; ++k) writer.append(test::sample_at(static_cast<std::uint64_t>(k)));
  writer.finish();
}

TEST(SessionClaim, WhatAKilledCreationLeftIsRemovedAndDoesNotBlockTheName) {
  ScratchDir dir;
  const auto path = dir / "s.palpa";
  const auto leftover = dir / (".s.palpa." + std::to_string(gone_pid()) + ".creating");
  std::ofstream(leftover) << "half a header";
  std::ofstream(leftover.string() + "-journal") << "its journal";
  // A creation still under way in a live process (pid 1 always runs) is not touched.
  const auto live = dir / ".s.palpa.1.creating";
  std::ofstream(live) << "another creator";

  record_one(path, 10);
  EXPECT_EQ(read_session(path).samples.size(), 10u);
  EXPECT_EQ(joined(names_in(dir.path())), ".s.palpa.1.creating s.palpa ");
}

// A child creating and finishing sessions one after another is killed at a random moment,
// many times. Whatever moment the kill hits, every name is either a readable session or
// free for the next writer, and no hidden creation is left once the next writer has run.
TEST(SessionClaim, AKillAtAnyMomentOfCreationLeavesAReadableSessionOrAFreeName) {
  std::mt19937 random(20261203);
  std::uniform_int_distribution<int> delay_us(0, 30000);
  for (int round = 0; round < 12; ++round) {
    ScratchDir dir;
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      try {
        for (int k = 0;; ++k) record_one(dir / ("s" + std::to_string(k) + ".palpa"), 3);
      } catch (...) {
        _exit(3);
      }
    }
    std::this_thread::sleep_for(std::chrono::microseconds(delay_us(random)));
    ASSERT_EQ(kill(child, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the creating child stopped by itself, status " << status;

    int k = 0;
    for (;; ++k) {
      const auto path = dir / ("s" + std::to_string(k) + ".palpa");
      if (!std::filesystem::exists(path)) break;
      try {
        read_session(path);
      } catch (const SessionError& e) {
        // The one instant that leaves a file: named, not yet committed to. It held nothing.
        EXPECT_NE(std::string(e.what()).find("holds no samples without its -wal"), std::string::npos)
            << "round " << round << ": " << e.what() << " among " << joined(names_in(dir.path()));
      }
    }
    const auto next = dir / ("s" + std::to_string(k) + ".palpa");
    EXPECT_NO_THROW(record_one(next, 5)) << "round " << round << ": the name the kill interrupted is blocked";
    for (const auto& name : names_in(dir.path())) {
      EXPECT_EQ(name.find(".creating"), std::string::npos) << "round " << round << ": left " << name;
    }
  }
}

TEST(SessionClaim, ASecondWriterIsToldAnotherProcessIsRecordingIntoTheFile) {
  ScratchDir dir;
  const auto path = dir / "live.palpa";
  int ready[2];
  ASSERT_EQ(pipe(ready), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    close(ready[0]);
    try {
      SessionWriter writer(path, test::flat_case_info());
      writer.append(test::sample_at(0));
      writer.commit();
      const char one = 1;
      if (write(ready[1], &one, 1) != 1) _exit(4);
      for (;;) pause();  // recording, until killed
    } catch (...) {
      _exit(3);
    }
  }
  close(ready[1]);
  pollfd p{ready[0], POLLIN, 0};
  ASSERT_EQ(poll(&p, 1, 20000), 1) << "the recording child went silent";
  try {
    SessionWriter second(path, test::flat_case_info());
    ADD_FAILURE() << "a second writer opened a live recording";
  } catch (const SessionError& e) {
    const std::string expected = "another process (pid " + std::to_string(child) + ") has it open";
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  close(ready[0]);
  // Once the recorder is gone its name is still taken, now as a session of an earlier run.
  try {
    SessionWriter later(path, test::flat_case_info());
    ADD_FAILURE() << "a recorded session was opened for writing";
  } catch (const SessionError& e) {
    EXPECT_NE(std::string(e.what()).find("already exists; recorded sessions are never overwritten"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(read_session(path).samples.size(), 1u);
}

// Writers started at the same moment on one name: exactly one records, every other one is
// refused with a message that says the name is taken, and nothing else is left behind.
TEST(SessionClaim, OfWritersRacingForOneNameExactlyOneGetsIt) {
  constexpr int kWriters = 6;
  for (int round = 0; round < 5; ++round) {
    ScratchDir dir;
    const auto path = dir / "race.palpa";
    int go[2];
    ASSERT_EQ(pipe(go), 0);
    std::vector<pid_t> children;
    for (int w = 0; w < kWriters; ++w) {
      const pid_t child = fork();
      ASSERT_GE(child, 0);
      if (child == 0) {
        close(go[1]);
        char byte = 0;
        if (read(go[0], &byte, 1) != 0) _exit(5);  // released when the parent closes its end
        try {
          record_one(path, 20);
          _exit(0);
        } catch (const SessionError& e) {
          const std::string what = e.what();
          const bool told = what.find("already exists") != std::string::npos ||
                            what.find("at the same moment") != std::string::npos;
          if (!told) std::fprintf(stderr, "refused: %s\n", what.c_str());
          _exit(told ? 1 : 2);
        } catch (...) {
          _exit(3);
        }
      }
      children.push_back(child);
    }
    close(go[0]);
    close(go[1]);
    int winners = 0;
    for (const pid_t child : children) {
      int status = 0;
      ASSERT_EQ(waitpid(child, &status, 0), child);
      ASSERT_TRUE(WIFEXITED(status));
      EXPECT_LE(WEXITSTATUS(status), 1) << "round " << round << ": a loser was refused without being told why";
      winners += WEXITSTATUS(status) == 0 ? 1 : 0;
    }
    EXPECT_EQ(winners, 1) << "round " << round;
    EXPECT_EQ(read_session(path).samples.size(), 20u);
    EXPECT_EQ(joined(names_in(dir.path())), "race.palpa ") << "round " << round;
  }
}

// A hot journal as a kill during finish()'s switch out of write-ahead logging leaves it:
// page 1 alone, as it was before the switch (format bytes 18 and 19 set to 2, WAL).
void write_header_switch_journal(const std::filesystem::path& session, std::uint32_t page_number) {
  std::ifstream in(session, std::ios::binary);
  std::vector<char> page(4096);
  in.read(page.data(), static_cast<std::streamsize>(page.size()));
  page[18] = page[19] = 2;
  std::vector<char> journal(512, 0);
  const auto put32 = [&](std::size_t at, std::uint32_t v) {
    for (int b = 0; b < 4; ++b) journal[at + static_cast<std::size_t>(b)] = static_cast<char>(v >> (24 - 8 * b));
  };
  const unsigned char magic[8] = {0xd9, 0xd5, 0x05, 0xf9, 0x20, 0xa1, 0x63, 0xd7};
  for (std::size_t b = 0; b < 8; ++b) journal[b] = static_cast<char>(magic[b]);
  put32(8, 1);     // one record
  put32(12, 7);    // checksum nonce
  put32(16, 3);    // pages before the transaction
  put32(20, 512);  // sector size
  put32(24, 4096); // page size
  journal.resize(512 + 4);
  put32(512, page_number);
  journal.insert(journal.end(), page.begin(), page.end());
  journal.resize(journal.size() + 4, 0);  // the record's checksum: not checked by the reader
  std::ofstream(session.string() + "-journal", std::ios::binary).write(journal.data(),
                                                                      static_cast<std::streamsize>(journal.size()));
}

TEST(SessionClaim, AKillDuringTheSwitchOutOfWriteAheadLoggingLeavesAReadableSession) {
  ScratchDir dir;
  const auto path = dir / "switched.palpa";
  record_one(path, 40);
  write_header_switch_journal(path, 1);
  const auto before = std::filesystem::file_size(path.string() + "-journal");
  for (int pass = 0; pass < 2; ++pass) {  // read as it is, and left as it is
    const Session s = read_session(path);
    ASSERT_EQ(s.samples.size(), 40u);
    EXPECT_EQ(s.format_version, 2);  // compacted before the switch
    EXPECT_TRUE(test::near_sample(s.samples[39], test::sample_at(39)));
  }
  EXPECT_EQ(std::filesystem::file_size(path.string() + "-journal"), before);

  // A journal of a data page is an interrupted write the reader cannot undo: refused, named.
  const auto other = dir / "written.palpa";
  record_one(other, 40);
  write_header_switch_journal(other, 2);
  try {
    read_session(other);
    ADD_FAILURE() << "read past a hot journal of a data page";
  } catch (const SessionError& e) {
    EXPECT_NE(std::string(e.what()).find("written.palpa-journal lies beside it"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace palpa::session
