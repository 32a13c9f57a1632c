#pragma once
// palpa-cli batch --store URL: the batch against the centre store (docs/centre.md).
// --worker scores the store's unscored sessions; --out DIR writes the folder batch's outputs
// (summary.csv, learning curves, cohort.html) from the stored sessions.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "isolated_score.hpp"
#include "palpa/report/cohort.hpp"
#include "palpa/report/session_filter.hpp"

namespace palpa::cli {

struct StoreBatchOptions {
  std::string store;      ///< libpq connection string; empty: the folder batch
  bool worker = false;
  bool follow = false;    ///< worker: keep polling when nothing is left
  double lease_s = 120.0;  ///< renewed while a session is scored (batch_store.cpp)
  int jobs = 0;           ///< worker threads (batch's --jobs); 0: all cores
  ScoreLimits limits;     ///< worker: each session is scored in a child process under these
  /// --out: the batch's own filter; the store is asked for a superset of it (a day wider),
  /// the folder batch then applies it exactly, so both batches select alike.
  report::SessionFilter filter;
};

/// The fields of a stored session's row that reports show: a downloaded file whose own
/// metadata say otherwise is not reported (it was forged after the server's checks).
struct StoredRow {
  std::string session_id, trainee, mode;
  bool enrolled = true;  ///< pushed by a station the trainee is enrolled at (else flagged, not in curves)
  /// Enrolled there only by the station's own first push: when another station also pushed
  /// for the trainee, no one can tell whose the trainee is, and neither counts.
  bool provisional = false;
  bool trainee_confirmed = false;  ///< a coordinator enrolled the trainee at some station
};

/// What came down from the store for the folder batch: the files, the station that pushed
/// each (the store's word, not the file's), and the rows that could not be written.
struct StoreDownload {
  std::vector<std::string> files;
  std::map<std::string, std::string> station_of;  ///< file -> the station it was pushed from
  /// file -> what the store's row says of it (checked by the server); the file must agree.
  std::map<std::string, StoredRow> row_of;
  /// file -> the score a worker stored for it (JSON): the report reads it, never scores again.
  std::map<std::string, std::string> result_of;
  std::vector<report::SkippedFile> skipped;
  /// Sessions no worker has scored yet: named in the report as pending, not scored here.
  std::vector<std::string> pending;
};

/// Declares --store, --worker, --follow and --lease on the batch command.
void add_store_batch_options(CLI::App* app, StoreBatchOptions& o);

/// Runs the batch against the store. Without --worker, downloads the stored sessions into
/// OUT/stored/STATION/ and calls `folder_batch` on those files, so the outputs are the
/// folder batch's own.
int run_store_batch(const StoreBatchOptions& o, const std::string& out,
                    const std::function<int(const StoreDownload&)>& folder_batch);

}  // namespace palpa::cli
