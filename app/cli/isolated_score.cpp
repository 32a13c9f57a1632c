#include "isolated_score.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <new>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "palpa/report/printable.hpp"
#include "palpa/session/session.hpp"
#include "palpa/store/score_claim.hpp"

namespace palpa::cli {
namespace {

constexpr int kSessionFd = 3;  // where the child finds the session's bytes
constexpr int kClaimFd = 4;    // and the claim's row, as JSON
constexpr int kExitRefused = 2;
constexpr int kExitOutOfMemory = 4;
constexpr std::size_t kMaxOutput = std::size_t{64} << 20;  // bytes kept of the child's stdout

// RLIMIT_AS cannot apply under AddressSanitizer: its shadow memory alone reserves terabytes.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSpaceLimit = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSpaceLimit = false;
#else
constexpr bool kAddressSpaceLimit = true;
#endif
#else
constexpr bool kAddressSpaceLimit = true;
#endif

class Fd {
 public:
  explicit Fd(int fd = -1) : fd_(fd) {}
  ~Fd() { reset(); }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }
  void reset(int fd = -1) {
    if (fd_ >= 0) close(fd_);
    fd_ = fd;
  }

 private:
  int fd_;
};

void write_all(int fd, const std::string& bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const auto n = write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw store::StoreError(fmt::format("worker: cannot fill a memory file: {}", std::strerror(errno)), false);
    done += static_cast<std::size_t>(n);
  }
}

// An anonymous file in memory holding `bytes`: gone with the last process that has it open.
int memory_file(const char* name, const std::string& bytes) {
  const int fd = memfd_create(name, MFD_CLOEXEC);
  if (fd < 0) throw store::StoreError(fmt::format("worker: cannot create a memory file: {}", std::strerror(errno)), false);
  try {
    write_all(fd, bytes);
  } catch (...) {
    close(fd);
    throw;
  }
  lseek(fd, 0, SEEK_SET);
  return fd;
}

nlohmann::json claim_json(const store::Claim& c) {
  return {{"id", c.id},           {"session_id", c.session_id}, {"file_name", c.file_name},
          {"station", c.station}, {"trainee", c.trainee},       {"mode", c.mode},
          {"started_at_s", c.started_at_s}, {"samples", c.samples}, {"case_document", c.case_document}};
}

store::Claim claim_from_json(const nlohmann::json& j) {
  store::Claim c;
  c.id = j.at("id").get<long long>();
  c.session_id = j.at("session_id").get<std::string>();
  c.file_name = j.at("file_name").get<std::string>();
  c.station = j.at("station").get<std::string>();
  c.trainee = j.at("trainee").get<std::string>();
  c.mode = j.at("mode").get<std::string>();
  c.started_at_s = j.at("started_at_s").get<double>();
  c.samples = j.at("samples").get<long long>();
  c.case_document = j.at("case_document").get<std::string>();
  return c;
}

std::string read_fd(int fd) {
  std::string all;
  char buffer[65536];
  for (;;) {
    const auto n = read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return all;
    all.append(buffer, static_cast<std::size_t>(n));
  }
}

struct Pipe {
  Fd read_end, write_end;
  Pipe() {
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0) throw store::StoreError("worker: cannot create a pipe", false);
    read_end.reset(fds[0]);
    write_end.reset(fds[1]);
  }
};

// Everything the child needs, made before fork: after it only async-signal-safe calls.
struct ChildPlan {
  int session_fd = -1, claim_fd = -1, out_fd = -1, err_fd = -1;
  rlimit memory{}, cpu{};
  pid_t parent = getpid();
  std::vector<char*> argv;
};

[[noreturn]] void become_scorer(const ChildPlan& p) {
  prctl(PR_SET_PDEATHSIG, SIGKILL);  // the worker's death ends its scorer too
  if (getppid() != p.parent) _exit(127);
  const int session = fcntl(p.session_fd, F_DUPFD, 10);
  const int claim = fcntl(p.claim_fd, F_DUPFD, 10);
  if (session < 0 || claim < 0 || dup2(session, kSessionFd) < 0 || dup2(claim, kClaimFd) < 0 ||
      dup2(p.out_fd, STDOUT_FILENO) < 0 || dup2(p.err_fd, STDERR_FILENO) < 0) {
    _exit(127);
  }
  if (kAddressSpaceLimit) setrlimit(RLIMIT_AS, &p.memory);
  setrlimit(RLIMIT_CPU, &p.cpu);
  execv("/proc/self/exe", p.argv.data());
  _exit(127);
}

struct ChildOutput {
  std::string out, err;
  bool timed_out = false;
  int status = 0;
};

// Collects the child's stdout and stderr until both close or the deadline passes (then
// the child is killed), and reaps it.
ChildOutput wait_for(pid_t pid, int out_fd, int err_fd, std::chrono::seconds limit,
                     const std::function<void()>& while_waiting) {
  ChildOutput r;
  const auto deadline = std::chrono::steady_clock::now() + limit;
  pollfd fds[2] = {{out_fd, POLLIN, 0}, {err_fd, POLLIN, 0}};
  int open_fds = 2;
  char buffer[65536];
  while (open_fds > 0) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      r.timed_out = true;
      kill(pid, SIGKILL);
      break;
    }
    if (while_waiting) {
      try {
        while_waiting();
      } catch (...) {  // the caller cannot go on (its server went away): the child goes too
        kill(pid, SIGKILL);
        while (waitpid(pid, &r.status, 0) < 0 && errno == EINTR) {
        }
        throw;
      }
    }
    // At least four wakes a second: while_waiting (the lease's renewal) runs on each.
    if (poll(fds, 2, static_cast<int>(std::min<long long>(left.count(), 250))) < 0 && errno != EINTR) break;
    for (int k = 0; k < 2; ++k) {
      if (fds[k].fd < 0 || fds[k].revents == 0) continue;
      const auto n = read(fds[k].fd, buffer, sizeof buffer);
      if (n > 0) {
        auto& into = k == 0 ? r.out : r.err;
        if (into.size() < (k == 0 ? kMaxOutput : 65536)) into.append(buffer, static_cast<std::size_t>(n));
      } else if (n == 0 || errno != EINTR) {
        fds[k].fd = -1;
        --open_fds;
      }
    }
  }
  while (waitpid(pid, &r.status, 0) < 0 && errno == EINTR) {
  }
  return r;
}

std::string first_line(const std::string& text) {
  auto line = text.substr(0, text.find('\n'));
  const std::string prefix = "palpa-cli: error: ";
  if (line.rfind(prefix, 0) == 0) line.erase(0, prefix.size());
  return line;
}

IsolatedScore outcome_of(const ChildOutput& r, const store::Claim& claim, const ScoreLimits& limits) {
  IsolatedScore s;
  const auto who = store::describe(claim);
  if (r.timed_out) {
    s.error = fmt::format("{}: scoring took longer than {} s; the scorer was stopped", who, 2 * limits.cpu_s + 10);
  } else if (WIFSIGNALED(r.status)) {
    const int sig = WTERMSIG(r.status);
    s.error = sig == SIGXCPU || sig == SIGKILL
                  ? fmt::format("{}: scoring used more than its {} s of CPU time or was killed (signal {})", who,
                                limits.cpu_s, sig)
                  : fmt::format("{}: the scorer crashed (signal {})", who, sig);
  } else if (WEXITSTATUS(r.status) == kExitOutOfMemory) {
    s.error = fmt::format("{}: scoring needed more than its {} MB of memory", who, limits.memory_mb);
  } else if (WEXITSTATUS(r.status) == kExitRefused) {
    s.outcome = ScoreOutcome::Refused;
    s.error = first_line(r.err);
  } else if (WEXITSTATUS(r.status) != 0) {
    s.error = fmt::format("{}: the scorer failed (exit {}): {}", who, WEXITSTATUS(r.status), first_line(r.err));
  } else {
    const auto j = nlohmann::json::parse(r.out, nullptr, false);
    if (j.is_discarded() || !j.is_object()) {
      s.error = fmt::format("{}: the scorer's answer could not be read", who);
      return s;
    }
    s.outcome = ScoreOutcome::Scored;
    s.row.scorer_version = j.value("scorer_version", "");
    s.row.thresholds_sha256 = j.value("thresholds_sha256", "");
    s.row.result_json = j.value("result", "");
    s.row.score = j.value("score", 0.0);
    s.row.passed = j.value("passed", false);
  }
  return s;
}

}  // namespace

IsolatedScore score_in_child(const store::Claim& claim, const ScoreLimits& limits,
                             const std::function<void()>& while_waiting) {
  const Fd session(memory_file("palpa-session", claim.file));
  const Fd row(memory_file("palpa-claim", claim_json(claim).dump()));
  Pipe out, err;
  static char kArg0[] = "palpa-cli", kArg1[] = "store", kArg2[] = "score-claim";
  ChildPlan plan;
  plan.session_fd = session.get();
  plan.claim_fd = row.get();
  plan.out_fd = out.write_end.get();
  plan.err_fd = err.write_end.get();
  const auto bytes = static_cast<rlim_t>(limits.memory_mb) << 20;
  plan.memory = {bytes, bytes};
  plan.cpu = {static_cast<rlim_t>(limits.cpu_s), static_cast<rlim_t>(limits.cpu_s + 5)};
  plan.argv = {kArg0, kArg1, kArg2, nullptr};
  const pid_t pid = fork();
  if (pid < 0) throw store::StoreError(fmt::format("worker: cannot start a scorer: {}", std::strerror(errno)), false);
  if (pid == 0) become_scorer(plan);
  out.write_end.reset();
  err.write_end.reset();
  const auto r = wait_for(pid, out.read_end.get(), err.read_end.get(), std::chrono::seconds(2 * limits.cpu_s + 10),
                          while_waiting);
  return outcome_of(r, claim, limits);
}

int run_score_child() {
  try {
    const auto claim = claim_from_json(nlohmann::json::parse(read_fd(kClaimFd)));
    const auto row = store::score_claim_bytes(read_fd(kSessionFd), claim);
    const nlohmann::json j{{"scorer_version", row.scorer_version}, {"thresholds_sha256", row.thresholds_sha256},
                           {"result", row.result_json}, {"score", row.score}, {"passed", row.passed}};
    std::fputs(j.dump().c_str(), stdout);
    return std::fflush(stdout) == 0 ? 0 : 1;
  } catch (const std::bad_alloc&) {
    std::fputs("out of memory\n", stderr);
    return kExitOutOfMemory;
  } catch (const session::SessionError& e) {
    std::fprintf(stderr, "%s\n", report::printable(e.what(), 2000).c_str());
    return kExitRefused;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", report::printable(e.what(), 2000).c_str());
    return 1;
  }
}

}  // namespace palpa::cli
