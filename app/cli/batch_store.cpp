// palpa-cli batch --store URL --worker | --out DIR (docs/centre.md, "Workers and leases",
// "Reports from the store").
#include "batch_store.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <thread>

#include <fmt/format.h>

#include "commands.hpp"
#include "isolated_score.hpp"
#include "palpa/report/printable.hpp"
#include "palpa/options/number_checks.hpp"
#include "palpa/report/session_header.hpp"
#include "palpa/session/session.hpp"
#include "palpa/store/catalog.hpp"
#include "palpa/store/schema.hpp"
#include "palpa/store/score_claim.hpp"
#include "palpa/store/sha256.hpp"
#include "palpa/store/work_queue.hpp"

namespace palpa::cli {
namespace {

namespace fs = std::filesystem;

std::string host_name() {
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) != 0 || name[0] == '\0') return "host";
  return name;
}

// Thrown from the lease's renewal when another worker holds the session now.
struct LeaseLost {};

struct WorkerTally {
  std::mutex mutex;
  int scored = 0, failed = 0, killed = 0, lost = 0;
  std::string connection_error;
};

// Scores one claimed session in a child process and records the outcome: scored, not
// scorable (ended with the reason), scorer killed (given back; retired after
// store_settings.max_score_attempts claims), or lease lost.
void work_on(store::Connection& c, const store::Claim& claim, const std::string& owner, const StoreBatchOptions& o,
             WorkerTally& tally) {
  IsolatedScore scored;
  // The lease is renewed at a third of its length while the scorer runs: however long the
  // scoring (up to the child's wall limit), no other worker takes the session over.
  auto renewed = std::chrono::steady_clock::now();
  const auto every = std::chrono::duration<double>(o.lease_s / 3.0);
  auto renew = [&] {
    if (std::chrono::steady_clock::now() - renewed < every) return;
    if (!store::renew_claim(c, claim, owner, o.lease_s)) throw LeaseLost{};  // stops the child: its work is lost
    renewed = std::chrono::steady_clock::now();
  };
  const auto& limits = o.limits;
  try {
    scored = score_in_child(claim, limits, renew);
  } catch (const LeaseLost&) {
    std::lock_guard lock(tally.mutex);
    ++tally.lost;
    std::printf("lost the lease: %s (another worker took it over; its scorer was stopped)\n",
                store::describe(claim).c_str());
    std::fflush(stdout);
    return;
  } catch (const store::StoreError& e) {  // no memory file, pipe or process: this machine's trouble, retried
    if (e.unreachable()) throw;                // the server went away while renewing: reconnect
    scored.error = store::describe(claim) + ": " + e.what();
  } catch (const std::exception& e) {  // a row the scorer cannot be handed (text that is not UTF-8)
    scored.outcome = ScoreOutcome::Refused;
    scored.error = store::describe(claim) + ": " + e.what();
  }
  bool held = false;
  switch (scored.outcome) {
    case ScoreOutcome::Scored: held = store::finish_claim(c, claim, owner, scored.row); break;
    case ScoreOutcome::Refused: held = store::fail_claim(c, claim, owner, scored.error); break;
    case ScoreOutcome::Killed: held = store::release_claim(c, claim, owner, scored.error); break;
  }
  std::lock_guard lock(tally.mutex);
  if (!held) {
    ++tally.lost;
    std::printf("lost the lease: %s (another worker took it over)\n", store::describe(claim).c_str());
  } else if (scored.outcome == ScoreOutcome::Refused) {
    ++tally.failed;
    print_error(scored.error);
  } else if (scored.outcome == ScoreOutcome::Killed) {
    ++tally.killed;
    print_error(scored.error + " (given back to the queue)");
  } else {
    ++tally.scored;
    std::printf("scored: %s: %s %s\n", store::describe(claim).c_str(),
                fmt::format("{:.1f} / 100", 100.0 * scored.row.score).c_str(),
                scored.row.passed ? "passed" : "failed");
  }
  std::fflush(stdout);
}

// Claims, scores and writes over `c` until nothing is left (or for ever with --follow).
void serve(store::Connection& c, const StoreBatchOptions& o, const std::string& owner, WorkerTally& tally) {
  for (;;) {
    std::optional<store::Claim> claim;
    try {
      claim = store::claim_next(c, owner, o.lease_s);
    } catch (const store::ClaimError& e) {  // one row's trouble, given back: go on with the next
      print_error(e.what());
      continue;
    }
    if (claim) {
      work_on(c, *claim, owner, o, tally);
      continue;
    }
    // Nothing free: done when nothing is pending, else a lease may expire (a killed worker).
    if (!o.follow && store::pending_count(c) == 0) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(o.follow ? 2000 : 250));
  }
}

// One worker thread. With --follow a lost server is waited for: reconnects with a backoff
// of 1, 2, 4 ... 30 s (a restart, a network outage); without it the worker reports and ends.
void worker_loop(const StoreBatchOptions& o, const std::string& owner, WorkerTally& tally) {
  int backoff_s = 1;
  for (;;) {
    try {
      store::Connection c(o.store);
      store::check_schema(c);
      backoff_s = 1;
      serve(c, o, owner, tally);
      return;
    } catch (const store::StoreError& e) {
      if (!o.follow || !e.unreachable()) {
        std::lock_guard lock(tally.mutex);
        if (tally.connection_error.empty()) tally.connection_error = e.what();
        return;
      }
      std::fprintf(stderr, "batch --worker %s: %s; trying again in %d s\n", owner.c_str(),
                   report::printable(e.what(), 400).c_str(), backoff_s);
      std::this_thread::sleep_for(std::chrono::seconds(backoff_s));
      backoff_s = std::min(2 * backoff_s, 30);
    }
  }
}

int run_workers(const StoreBatchOptions& o) {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const auto jobs = o.jobs > 0 ? static_cast<unsigned>(o.jobs) : cores;
  const std::string base = fmt::format("{}:{}", host_name(), getpid());
  WorkerTally tally;
  {
    std::vector<std::jthread> pool;
    for (unsigned k = 0; k < jobs; ++k) {
      pool.emplace_back([&o, &tally, owner = fmt::format("{}:{}", base, k)] { worker_loop(o, owner, tally); });
    }
  }
  std::fprintf(stderr,
               "batch --worker %s: %d scored, %d could not be scored, %d scorers killed (given back), %d leases lost\n",
               base.c_str(), tally.scored, tally.failed, tally.killed, tally.lost);
  if (!tally.connection_error.empty()) {
    print_error(tally.connection_error);
    return kFailure;
  }
  return tally.failed > 0 ? kBadInput : kOk;
}

// Writes `bytes` to `path` unless a file with the same SHA-256 is there already; the
// temporary file is removed on every failure.
void write_copy(const fs::path& path, const std::string& bytes, const std::string& sha256) {
  std::error_code ec;
  if (fs::exists(path, ec) && store::sha256_hex(store::read_file_bytes(path)) == sha256) return;
  const auto tmp = path.string() + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    f.close();
    if (!f) {
      fs::remove(tmp, ec);
      throw store::StoreError(fmt::format("{}: cannot be written", tmp), false);
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw store::StoreError(fmt::format("{}: cannot be written: {}", path.string(), ec.message()), false);
  }
}

// What to ask the store for: the filter's trainee, its dates a day wider each side (a
// date's day, zones); the folder batch applies the exact filter to what comes down.
store::SessionFilter coarse(const report::SessionFilter& f) {
  constexpr double kDay = 86400.0;
  store::SessionFilter c;
  c.trainee = f.trainee;
  if (auto since = report::parse_iso8601(f.since); !f.since.empty() && since) c.since_s = *since - kDay;
  if (auto until = report::parse_iso8601(f.until); !f.until.empty() && until) c.until_s = *until + 2 * kDay;
  return c;
}

// A station's folder: its slug and 8 hex digits of its name's SHA-256, so that two names
// with one slug ("Room 1", "room-1") or none ("<script>") never share a folder.
std::string station_folder(const std::string& station) {
  auto slug = report::slug(station);
  if (slug.empty()) slug = "station";
  return slug + "-" + store::sha256_hex(station).substr(0, 8);
}

// OUT/stored/STATION-HASH/ROW.palpa: named from the server's row key and a slug, never
// from text a station chose, and checked to stay inside `folder` all the same.
fs::path download_path(const fs::path& folder, const store::StoredSession& s) {
  const auto path = folder / station_folder(s.station) / fmt::format("{}.palpa", s.id);
  const auto inside = fs::weakly_canonical(folder);
  const auto target = fs::weakly_canonical(path);
  if (std::mismatch(inside.begin(), inside.end(), target.begin(), target.end()).first != inside.end()) {
    throw store::StoreError(fmt::format("{}: outside {}", path.string(), folder.string()), false);
  }
  return path;
}

// Downloads the stored sessions the filter may select. A row that cannot be written is
// listed with its reason and the rest still come down.
StoreDownload download(store::Connection& c, const fs::path& folder, const report::SessionFilter& filter) {
  StoreDownload d;
  for (const auto& s : store::list_sessions(c, coarse(filter))) {
    const auto name = report::printable(fmt::format("store session {} from station {}", s.session_id, s.station), 300);
    if (s.ended_unscored) {  // a file the workers refused (forged, not a session) or retired
      d.skipped.push_back({name, report::printable("not scored by the workers: " + s.last_error, 400)});
      continue;
    }
    if (!s.scored) {  // scored only by a worker, under its limits: this process never scores a stored file
      d.pending.push_back(name);
      continue;
    }
    try {
      const auto path = download_path(folder, s);
      fs::create_directories(path.parent_path());
      write_copy(path, store::session_file(c, s.id), s.sha256);
      d.files.push_back(path.string());
      d.station_of[path.string()] = s.station;
      d.row_of[path.string()] = {s.session_id, s.trainee, s.mode, s.enrolled, s.provisional, s.trainee_confirmed};
      d.result_of[path.string()] = store::stored_result(c, s.id);
    } catch (const store::StoreError& e) {
      if (e.unreachable()) throw;
      d.skipped.push_back({name, report::printable(e.what(), 400)});
    } catch (const fs::filesystem_error& e) {
      d.skipped.push_back({name, report::printable(e.what(), 400)});
    }
  }
  return d;
}

int run_export(const StoreBatchOptions& o, const std::string& out,
               const std::function<int(const StoreDownload&)>& folder_batch) {
  StoreDownload d;
  try {
    store::Connection c(o.store);
    store::check_schema(c);
    d = download(c, fs::path(out) / "stored", o.filter);
    std::fprintf(stderr, "batch --store %s: %zu scored sessions in %s%s%s\n", c.target().c_str(), d.files.size(),
                 (fs::path(out) / "stored").c_str(),
                 d.skipped.empty() ? "" : fmt::format(", {} not scorable or not written", d.skipped.size()).c_str(),
                 d.pending.empty() ? "" : fmt::format(", {} pending (not scored by a worker yet)", d.pending.size()).c_str());
  } catch (const std::exception& e) {  // StoreError, or a filesystem error
    print_error(e.what());
    return kFailure;
  }
  return folder_batch(d);
}

}  // namespace

void add_store_batch_options(CLI::App* app, StoreBatchOptions& o) {
  app->add_option("--store", o.store,
                  "batch against the centre store (libpq connection string or URI; docs/centre.md) instead of "
                  "PATHs: with --worker score its unscored sessions, with --out write the outputs from its sessions");
  app->add_flag("--worker", o.worker, "with --store: claim and score unscored sessions (leases), exit when none is left");
  app->add_flag("--follow", o.follow, "with --worker: keep polling for new sessions instead of exiting");
  app->add_option("--lease", o.lease_s, "with --worker: seconds a claimed session is held before another worker may "
                                        "take it over; renewed every third of it while the session is scored, so it "
                                        "only runs out when its worker is gone; default 120")
      ->check(options::finite_in(1.0, 86400.0, "s"));
  app->add_option("--score-memory", o.limits.memory_mb,
                  "with --worker: MB of memory each session's scorer may use (a child process); default 2048")
      ->check(CLI::Range(64L, 1048576L));
  app->add_option("--score-seconds", o.limits.cpu_s,
                  "with --worker: CPU seconds each session's scorer may use; default 600")
      ->check(CLI::Range(1L, 86400L));
}

int run_store_batch(const StoreBatchOptions& o, const std::string& out,
                    const std::function<int(const StoreDownload&)>& folder_batch) {
  if (o.worker) return run_workers(o);
  if (o.follow) {
    print_error("--follow: needs --worker");
    return kBadInput;
  }
  if (out.empty()) {
    print_error("batch --store: give --worker (score) or --out DIR (reports)");
    return kBadInput;
  }
  try {
    o.filter.validate();  // before anything comes down
  } catch (const report::FilterError& e) {
    print_error(e.what());
    return kBadInput;
  }
  return run_export(o, out, folder_batch);
}

}  // namespace palpa::cli
