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
#include <thread>

#include <fmt/format.h>

#include "commands.hpp"
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

struct WorkerTally {
  std::mutex mutex;
  int scored = 0, failed = 0, lost = 0;
  std::string connection_error;
};

// Scores one claimed session and records the outcome (scored, not scorable, or lease lost).
void work_on(store::Connection& c, const store::Claim& claim, const std::string& owner, WorkerTally& tally) {
  std::string error;
  store::ScoreRow row;
  try {
    row = store::score_claim(claim);
  } catch (const std::exception& e) {  // session::SessionError, or no temporary file
    error = e.what();
  }
  const bool held = error.empty() ? store::finish_claim(c, claim, owner, row)
                                  : store::fail_claim(c, claim, owner, error);
  std::lock_guard lock(tally.mutex);
  if (!held) {
    ++tally.lost;
    std::printf("lost the lease: session %s (another worker took it over)\n", claim.session_id.c_str());
  } else if (!error.empty()) {
    ++tally.failed;
    std::fprintf(stderr, "palpa-cli: error: session %s: %s\n", claim.session_id.c_str(), error.c_str());
  } else {
    ++tally.scored;
    std::printf("scored: session %s (%s): %s %s\n", claim.session_id.c_str(), claim.file_name.c_str(),
                fmt::format("{:.1f} / 100", 100.0 * row.score).c_str(), row.passed ? "passed" : "failed");
  }
  std::fflush(stdout);
}

// One worker thread: claims, scores and writes until nothing is left (or forever with --follow).
void worker_loop(const StoreBatchOptions& o, const std::string& owner, WorkerTally& tally) {
  try {
    store::Connection c(o.store);
    store::check_schema(c);
    for (;;) {
      if (auto claim = store::claim_next(c, owner, o.lease_s)) {
        work_on(c, *claim, owner, tally);
        continue;
      }
      // Nothing free: done when nothing is pending, else a lease may expire (a killed worker).
      if (!o.follow && store::pending_count(c) == 0) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(o.follow ? 2000 : 250));
    }
  } catch (const store::StoreError& e) {
    std::lock_guard lock(tally.mutex);
    if (tally.connection_error.empty()) tally.connection_error = e.what();
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
  std::fprintf(stderr, "batch --worker %s: %d scored, %d could not be scored, %d leases lost\n", base.c_str(),
               tally.scored, tally.failed, tally.lost);
  if (!tally.connection_error.empty()) {
    print_error(tally.connection_error);
    return kFailure;
  }
  return tally.failed > 0 ? kBadInput : kOk;
}

// Writes `bytes` to `path` unless a file with the same SHA-256 is there already.
void write_copy(const fs::path& path, const std::string& bytes, const std::string& sha256) {
  std::error_code ec;
  if (fs::exists(path, ec) && store::sha256_hex(store::read_file_bytes(path)) == sha256) return;
  const auto tmp = path.string() + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!f.flush()) throw store::StoreError(fmt::format("{}: cannot be written", tmp), false);
  }
  fs::rename(tmp, path);
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

// Downloads the stored sessions the filter may select into OUT/stored/STATION/SESSION_ID.palpa.
std::vector<std::string> download(store::Connection& c, const fs::path& folder, const report::SessionFilter& filter) {
  std::vector<std::string> files;
  for (const auto& s : store::list_sessions(c, coarse(filter))) {
    std::string station = report::slug(s.station);
    if (station.empty()) station = "station";
    const auto dir = folder / station;
    fs::create_directories(dir);
    const auto path = dir / (s.session_id + ".palpa");
    write_copy(path, store::session_file(c, s.id), s.sha256);
    files.push_back(path.string());
  }
  return files;
}

int run_export(const StoreBatchOptions& o, const std::string& out,
               const std::function<int(const std::vector<std::string>&)>& folder_batch) {
  std::vector<std::string> files;
  try {
    store::Connection c(o.store);
    store::check_schema(c);
    files = download(c, fs::path(out) / "stored", o.filter);
    std::fprintf(stderr, "batch --store %s: %zu sessions in %s\n", c.target().c_str(), files.size(),
                 (fs::path(out) / "stored").c_str());
  } catch (const std::exception& e) {  // StoreError, or a filesystem error
    print_error(e.what());
    return kFailure;
  }
  if (files.empty()) {
    print_error(o.filter.empty() ? "the store holds no session" : "no stored session is " + o.filter.describe());
    return kBadInput;
  }
  return folder_batch(files);
}

}  // namespace

void add_store_batch_options(CLI::App* app, StoreBatchOptions& o) {
  app->add_option("--store", o.store,
                  "batch against the centre store (libpq connection string or URI; docs/centre.md) instead of "
                  "PATHs: with --worker score its unscored sessions, with --out write the outputs from its sessions");
  app->add_flag("--worker", o.worker, "with --store: claim and score unscored sessions (leases), exit when none is left");
  app->add_flag("--follow", o.follow, "with --worker: keep polling for new sessions instead of exiting");
  app->add_option("--lease", o.lease_s, "with --worker: seconds a claimed session is held before another worker may "
                                        "take it over; default 600")
      ->check(options::finite_in(1.0, 86400.0, "s"));
}

int run_store_batch(const StoreBatchOptions& o, const std::string& out,
                    const std::function<int(const std::vector<std::string>&)>& folder_batch) {
  if (o.worker) return run_workers(o);
  if (o.follow) {
    print_error("--follow: needs --worker");
    return kBadInput;
  }
  if (out.empty()) {
    print_error("batch --store: give --worker (score) or --out DIR (reports)");
    return kBadInput;
  }
  return run_export(o, out, folder_batch);
}

}  // namespace palpa::cli
