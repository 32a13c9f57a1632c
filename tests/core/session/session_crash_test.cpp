// A recording process killed with SIGKILL: everything it committed is readable, exactly,
// from the file and the -wal left beside it.
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "palpa/session/session_reader.hpp"
#include "palpa/session/session_writer.hpp"
#include "session_test_support.hpp"

namespace palpa::session {
namespace {

// The child: records as fast as a paced loop would (bursts of 50 ticks), commits about
// every 50 ms and after each commit tells the parent how many samples are committed.
[[noreturn]] void record_until_killed(const std::filesystem::path& path, int report_fd) {
  try {
    SessionWriter writer(path, test::flat_case_info());
    Event start;
    start.kind = EventKind::Start;
    writer.event(start);
    std::uint64_t tick = 0;
    for (;;) {
      const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(50);
      while (std::chrono::steady_clock::now() < until) {
        for (int k = 0; k < 50; ++k) writer.append(test::sample_at(tick++));
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
      writer.commit();
      const std::uint64_t committed = writer.samples_written();
      if (write(report_fd, &committed, sizeof committed) != static_cast<ssize_t>(sizeof committed)) _exit(4);
      // Keep writing into the next (uncommitted) transaction: the kill lands mid-way.
    }
  } catch (...) {
    _exit(3);
  }
}

TEST(SessionCrash, EverythingCommittedBeforeSigkillIsReadBackExactly) {
  test::ScratchDir dir;
  const auto path = dir / "killed.palpa";
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    close(fds[0]);
    record_until_killed(path, fds[1]);
  }
  close(fds[1]);

  std::uint64_t committed = 0;
  int reports = 0;
  while (reports < 4) {
    pollfd p{fds[0], POLLIN, 0};
    ASSERT_EQ(poll(&p, 1, 20000), 1) << "the recording child went silent";
    std::uint64_t value = 0;
    ASSERT_EQ(read(fds[0], &value, sizeof value), static_cast<ssize_t>(sizeof value)) << "the child died early";
    EXPECT_GT(value, committed);
    committed = value;
    ++reports;
  }
  ASSERT_EQ(kill(child, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGKILL);
  close(fds[0]);
  // The crash path: the write-ahead log is still there, the folder is writable.
  EXPECT_TRUE(std::filesystem::exists(dir / "killed.palpa-wal"));

  for (int pass = 0; pass < 2; ++pass) {  // reading changes nothing: the second read agrees
    const Session s = read_session(path);
    EXPECT_FALSE(s.complete);
    EXPECT_TRUE(s.loop_stats.is_null());
    ASSERT_EQ(s.events.size(), 1u);
    EXPECT_EQ(s.events[0].kind, EventKind::Start);
    ASSERT_GE(s.samples.size(), committed) << "pass " << pass;
    for (std::size_t k = 0; k < s.samples.size(); ++k) {
      ASSERT_TRUE(test::same_sample(s.samples[k], test::sample_at(k))) << "tick " << k << ", pass " << pass;
    }
  }
}

}  // namespace
}  // namespace palpa::session
