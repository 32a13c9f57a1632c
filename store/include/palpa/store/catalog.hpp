#pragma once
// What a coordinator reads back from the store: the stored sessions (filtered) and their
// files, for palpa-cli batch --store --out and palpa-cli store status.
#include <optional>
#include <string>
#include <vector>

#include "palpa/store/pg.hpp"

namespace palpa::store {

/// A coarse selection made by the server (the caller applies its exact filter after).
struct SessionFilter {
  std::optional<double> since_s;  ///< started_at >= this, seconds since 1970 UTC
  std::optional<double> until_s;  ///< started_at < this
  std::string trainee;            ///< exact trainee id; empty: every trainee
};

struct StoredSession {
  long long id = 0;
  std::string session_id, station, trainee, file_name, sha256, started_at, mode;
  bool scored = false;          ///< has a score row (any scorer version)
  bool ended_unscored = false;  ///< the workers ended it without a score: refused or retired
  bool pending = false;         ///< in the work queue, not scored yet
  /// The enrolments as they are now (a coordinator may have enrolled the trainee since):
  bool enrolled = true;         ///< the trainee is enrolled at the station that pushed it
  bool provisional = false;     ///< enrolled there by the station's own first push only
  bool trainee_confirmed = false;  ///< a coordinator (or the migration) enrolled the trainee somewhere
  std::string last_error;       ///< why, as the worker wrote it
};

/// The stored sessions matching `filter`, by station then start time.
std::vector<StoredSession> list_sessions(Connection& c, const SessionFilter& filter);

/// The stored bytes of session `id` (sessions.id).
std::string session_file(Connection& c, long long id);

/// The newest score a worker wrote for session `id` (scores.result, JSON text); empty when
/// it has none. Reports take it instead of scoring the session again.
std::string stored_result(Connection& c, long long id);

/// Enrols `trainee` at `station` (or ends the enrolment): from then on that station's
/// pushes for the trainee count in the learning curves (docs/centre.md, "Enrolment").
/// True when it changed anything. Needs palpa_coordinator.
bool enrol(Connection& c, const std::string& trainee, const std::string& station, bool enrolled);

/// Sessions uploaded by the connected login (station_sessions), by station name.
struct StationCount {
  std::string station;
  long long sessions = 0;
};
std::vector<StationCount> my_session_counts(Connection& c);

}  // namespace palpa::store
