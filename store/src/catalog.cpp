#include "palpa/store/catalog.hpp"

#include <fmt/format.h>

namespace palpa::store {
namespace {

Param optional_text(const std::string& v) { return v.empty() ? Param::null() : Param::text(v); }
Param optional_seconds(const std::optional<double>& v) { return v ? Param::text(fmt::format("{}", *v)) : Param::null(); }

}  // namespace

std::vector<StoredSession> list_sessions(Connection& c, const SessionFilter& f) {
  const auto r = c.exec(
      "list the stored sessions",
      "SELECT s.id, s.session_id, s.station, t.name, s.file_name, s.sha256, "
      "to_char(s.started_at AT TIME ZONE 'UTC', 'YYYY-MM-DD\"T\"HH24:MI:SS\"Z\"'), "
      "EXISTS (SELECT 1 FROM scores sc WHERE sc.session_id = s.id), s.mode, "
      "coalesce(w.done, false), coalesce(w.last_error, ''), "
      "coalesce((SELECT e.enrolled_by FROM enrolments e WHERE e.trainee_id = s.trainee_id AND e.station = s.station), "
      "''), EXISTS (SELECT 1 FROM enrolments e WHERE e.trainee_id = s.trainee_id AND e.enrolled_by <> 'first push') "
      "FROM sessions s JOIN trainees t ON t.id = s.trainee_id LEFT JOIN work_queue w ON w.session_id = s.id "
      "WHERE ($1::double precision IS NULL OR s.started_at >= to_timestamp($1::double precision)) "
      "AND ($2::double precision IS NULL OR s.started_at < to_timestamp($2::double precision)) "
      "AND ($3::text IS NULL OR t.name = $3::text) "
      "ORDER BY s.station, s.started_at, s.session_id",
      {optional_seconds(f.since_s), optional_seconds(f.until_s), optional_text(f.trainee)});
  std::vector<StoredSession> all;
  for (int i = 0; i < r.rows(); ++i) {
    StoredSession s;
    s.id = r.integer(i, 0);
    s.session_id = r.text(i, 1);
    s.station = r.text(i, 2);
    s.trainee = r.text(i, 3);
    s.file_name = r.text(i, 4);
    s.sha256 = r.text(i, 5);
    s.started_at = r.text(i, 6);
    s.mode = r.text(i, 8);
    s.scored = r.text(i, 7) == "t";
    s.ended_unscored = r.text(i, 9) == "t" && !s.scored;
    s.last_error = r.text(i, 10);
    s.pending = !s.scored && r.text(i, 9) == "f";
    s.enrolled = !r.text(i, 11).empty();
    s.provisional = r.text(i, 11) == "first push";
    s.trainee_confirmed = r.text(i, 12) == "t";
    all.push_back(std::move(s));
  }
  return all;
}

std::string session_file(Connection& c, long long id) {
  const auto r = c.exec("read a stored session", "SELECT file FROM sessions WHERE id = $1::bigint",
                        {Param::text(std::to_string(id))}, true);
  if (r.rows() != 1) throw StoreError("store: session " + std::to_string(id) + " is gone", false);
  return r.bytes(0, 0);
}

std::string stored_result(Connection& c, long long id) {
  const auto r = c.exec("read a stored score",
                        "SELECT result::text FROM scores WHERE session_id = $1::bigint ORDER BY scored_at DESC, id DESC "
                        "LIMIT 1",
                        {Param::text(std::to_string(id))});
  return r.rows() == 1 ? r.text(0, 0) : std::string();
}

bool enrol(Connection& c, const std::string& trainee, const std::string& station, bool enrolled) {
  const auto r = c.exec("enrol a trainee", "SELECT public.palpa_enrol($1, $2, $3::boolean)",
                        {Param::text(trainee), Param::text(station), Param::text(enrolled ? "true" : "false")});
  return r.text(0, 0) == "t";
}

std::vector<StationCount> my_session_counts(Connection& c) {
  const auto r = c.exec("count this login's sessions",
                        "SELECT station, count(*) FROM station_sessions GROUP BY station ORDER BY station");
  std::vector<StationCount> counts;
  for (int i = 0; i < r.rows(); ++i) counts.push_back({r.text(i, 0), r.integer(i, 1)});
  return counts;
}

}  // namespace palpa::store
