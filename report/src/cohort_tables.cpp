#include "palpa/report/cohort_tables.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <fmt/format.h>

#include "palpa/report/csv_number.hpp"
#include "palpa/report/printable.hpp"
#include "palpa/report/summary_csv.hpp"

namespace palpa::report {
namespace {

double median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 == 1 ? values[mid] : (values[mid - 1] + values[mid]) / 2.0;
}

// The sessions of one group summarised; `name` from the first session.
GroupSummary summarise(const std::string& key, const std::vector<const SessionFacts*>& group,
                       const ProficientPairs& proficient) {
  GroupSummary g;
  g.key = key;
  g.sessions = group.size();
  std::vector<double> scores;
  std::set<std::string> trainees, proficient_here;
  for (const SessionFacts* s : group) {
    if (g.name.empty()) g.name = s->header->case_title;
    g.passed += s->passed ? 1 : 0;
    if (!s->abandoned) scores.push_back(100.0 * s->score);
    trainees.insert(s->header->trainee);
    // A trainee counts as proficient here when her curve of a case she did here says so.
    if (proficient.count({s->header->trainee, s->header->case_id}) > 0) proficient_here.insert(s->header->trainee);
  }
  g.scored = scores.size();
  g.median_score_100 = median(std::move(scores));
  g.trainees = trainees.size();
  g.proficient_trainees = proficient_here.size();
  return g;
}

std::vector<GroupSummary> summaries(const std::vector<SessionFacts>& sessions, const ProficientPairs& proficient,
                                    const std::function<std::string(const SessionHeader&)>& key_of) {
  std::map<std::string, std::vector<const SessionFacts*>> groups;
  for (const auto& s : sessions) groups[key_of(*s.header)].push_back(&s);
  std::vector<GroupSummary> rows;
  for (const auto& [key, group] : groups) rows.push_back(summarise(key, group, proficient));
  return rows;
}

// The counts and figures after the key column(s), as a CSV line's tail (with the newline).
std::string figures_csv(const GroupSummary& g) {
  const double rate = g.scored > 0 ? static_cast<double>(g.passed) / static_cast<double>(g.scored)
                                   : std::numeric_limits<double>::quiet_NaN();
  return fmt::format("{},{},{},{},{},{},{}\n", g.sessions, g.scored, g.passed, csv_number(rate, CsvUnit::Fraction),
                     csv_number(g.median_score_100, CsvUnit::Score100), g.trainees, g.proficient_trainees);
}

constexpr const char* kFigures = "sessions,scored,passed,pass_rate,median_score_100,trainees,proficient_trainees";

}  // namespace

std::vector<GroupSummary> case_summaries(const std::vector<SessionFacts>& sessions, const ProficientPairs& proficient) {
  return summaries(sessions, proficient, [](const SessionHeader& h) { return h.case_id; });
}

std::vector<GroupSummary> station_summaries(const std::vector<SessionFacts>& sessions,
                                            const ProficientPairs& proficient) {
  auto rows = summaries(sessions, proficient, [](const SessionHeader& h) { return h.station; });
  for (auto& r : rows) r.name.clear();
  return rows;
}

std::string cases_csv(const std::vector<GroupSummary>& cases) {
  std::string csv = fmt::format("case_id,case,{}\n", kFigures);
  for (const auto& g : cases) csv += csv_text(g.key) + "," + csv_text(g.name) + "," + figures_csv(g);
  return csv;
}

std::string stations_csv(const std::vector<GroupSummary>& stations) {
  std::string csv = fmt::format("station,{}\n", kFigures);
  for (const auto& g : stations) csv += csv_text(g.key) + "," + figures_csv(g);
  return csv;
}

std::vector<std::string> left_out_notes(const LeftOut& l) {
  std::vector<std::string> notes;
  if (!l.by_mode.empty()) {
    std::size_t total = 0;
    std::string modes;  // "12 scripted, 2 replay": the mode is the file's word, shown escaped
    for (const auto& [mode, n] : l.by_mode) {
      total += n;
      modes += fmt::format("{}{} {}", modes.empty() ? "" : ", ", n, printable(mode, 40));
    }
    notes.push_back(fmt::format("{} {} not in the learning curves: only trainee exercises count; give "
                                "--all-modes to include them.",
                                modes, total == 1 ? "session is" : "sessions are"));
  }
  if (l.abandoned > 0)
    notes.push_back(fmt::format("{} abandoned {} not in the learning curves; give --include-abandoned to include "
                                "them.",
                                l.abandoned, l.abandoned == 1 ? "attempt is" : "attempts are"));
  if (l.filtered > 0)
    notes.push_back(fmt::format("{} {} outside the selection ({}) and in no output; run without {} to include them.",
                                l.filtered, l.filtered == 1 ? "session is" : "sessions are", l.filter,
                                l.filter_options));
  for (const auto& [trainee, stations] : l.disputed) {
    std::string names;
    for (const auto& station : stations) names += fmt::format("{}{}", names.empty() ? "" : ", ", printable(station, 64));
    notes.push_back(fmt::format("Flagged: trainee {} was pushed from stations {} and no coordinator enrolled them at "
                                "any: none of their attempts is in the learning curves until a coordinator enrols "
                                "the right station (palpa-cli store enrol).",
                                printable(trainee, 80), names));
  }
  if (l.unenrolled_sessions > 0) {
    std::string who;
    for (const auto& [trainee, stations] : l.unenrolled) {
      for (const auto& station : stations) {
        who += fmt::format("{}trainee {} from station {}", who.empty() ? "" : "; ", printable(trainee, 80),
                           printable(station, 64));
      }
    }
    notes.push_back(fmt::format("Flagged: {} {} pushed by a station the trainee is not enrolled at and {} not in the "
                                "learning curves ({}); a coordinator enrols a trainee at a station with palpa-cli "
                                "store enrol.",
                                l.unenrolled_sessions, l.unenrolled_sessions == 1 ? "session was" : "sessions were",
                                l.unenrolled_sessions == 1 ? "is" : "are", who));
  }
  return notes;
}

std::vector<std::string> several_station_notes(const std::map<std::string, std::set<std::string>>& stations) {
  std::vector<std::string> notes;
  for (const auto& [trainee, seen] : stations) {
    std::string names;
    std::size_t n = 0;
    for (const auto& s : seen) {
      if (s.empty()) continue;
      names += fmt::format("{}{}", names.empty() ? "" : ", ", printable(s, 64));
      ++n;
    }
    if (n < 2) continue;
    notes.push_back(fmt::format("Flagged: trainee {} has attempts from {} stations ({}): check that each attempt is "
                                "theirs (the station of every attempt is in trainees/*.csv).",
                                printable(trainee, 80), n, names));
  }
  return notes;
}

}  // namespace palpa::report
