#pragma once
// A coordinator's view of a batch: per-case and per-station summaries (sessions, pass rate,
// median score, proficient trainees) and the notes that say which sessions the learning
// curves leave out and the option that brings them in. Works on the headers and the
// scores a batch keeps, so the folder batch and the store's batch summarise alike.
#include <cstddef>
#include <map>
#include <set>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "palpa/report/session_header.hpp"

namespace palpa::report {

/// One scored session as the summaries need it (one row of summary.csv).
struct SessionFacts {
  const SessionHeader* header = nullptr;
  double score = 0.0;  ///< 0..1
  bool passed = false;
  bool abandoned = false;
};

/// (trainee, case_id) pairs whose per-case learning curve is proficient after its last attempt.
using ProficientPairs = std::set<std::pair<std::string, std::string>>;

/// One row of cases.csv or stations.csv.
struct GroupSummary {
  std::string key;                ///< the case_id, or the station (empty: not recorded)
  std::string name;               ///< cases: the case title of the first session; stations: empty
  std::size_t sessions = 0;       ///< rows of summary.csv
  std::size_t scored = 0;         ///< of them not abandoned (an abandoned attempt has no exam)
  std::size_t passed = 0;
  double median_score_100 = 0.0;  ///< over the scored ones; NaN when none
  std::size_t trainees = 0;       ///< distinct trainees with a session here
  std::size_t proficient_trainees = 0;  ///< of them proficient now on a case they did here
};

/// One row per case_id / per station, sorted by key (byte order).
std::vector<GroupSummary> case_summaries(const std::vector<SessionFacts>& sessions, const ProficientPairs& proficient);
std::vector<GroupSummary> station_summaries(const std::vector<SessionFacts>& sessions,
                                            const ProficientPairs& proficient);

/// "case_id,case,sessions,scored,passed,pass_rate,median_score_100,trainees,proficient_trainees"
/// and "station,sessions,...": pass_rate = passed / scored to 0.001 and the median to 0.1
/// (csv_number.hpp), empty when nothing was scored; text as csv_text.
std::string cases_csv(const std::vector<GroupSummary>& cases);
std::string stations_csv(const std::vector<GroupSummary>& stations);

/// Sessions of the batch that its learning curves do not count, and why.
struct LeftOut {
  std::map<std::string, std::size_t> by_mode;  ///< mode -> sessions not "trainee" (without --all-modes)
  std::size_t abandoned = 0;      ///< abandoned attempts otherwise counted (without --include-abandoned)
  std::size_t filtered = 0;       ///< sessions outside the filter: in no output at all
  std::string filter;             ///< SessionFilter::describe()
  std::string filter_options;     ///< the options that made it: "--since, --case"
  /// Store reports: trainee -> the stations that pushed attempts for them without their
  /// enrolment there (flagged, never in a curve: a station may not speak for another's trainee).
  std::map<std::string, std::set<std::string>> unenrolled;
  std::size_t unenrolled_sessions = 0;
  /// Trainees pushed both by the station their first push enrolled them at and by another:
  /// trainee -> every station that pushed for them; none of their attempts is in a curve.
  std::map<std::string, std::set<std::string>> disputed;
};

/// One flag per trainee whose attempts in the curves came from more than one station:
/// "Trainee T: attempts from 2 stations (room-1, room-2) ...". `station_of_attempts` maps
/// each trainee to the stations of their attempts (empty station names are ignored).
std::vector<std::string> several_station_notes(const std::map<std::string, std::set<std::string>>& stations);

/// One sentence per reason, with the option that includes them: "12 scripted sessions are
/// not in the learning curves: only trainee exercises count; give --all-modes to include
/// them." Empty when nothing was left out.
std::vector<std::string> left_out_notes(const LeftOut& left_out);

}  // namespace palpa::report
