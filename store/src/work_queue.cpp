#include "palpa/store/work_queue.hpp"

#include <cstdlib>

#include <fmt/format.h>

#include "palpa/report/printable.hpp"

namespace palpa::store {
namespace {

// Ends the claim if `owner` holds it; true when it did. Inside the caller's transaction.
bool end_claim(Connection& c, const Claim& claim, const std::string& owner, const std::string& error) {
  const auto r = c.exec("end the claim",
                        "UPDATE work_queue SET done = true, lease_owner = NULL, lease_expires = NULL, last_error = $3 "
                        "WHERE session_id = $1::bigint AND lease_owner = $2 AND NOT done RETURNING session_id",
                        {Param::text(std::to_string(claim.id)), Param::text(owner),
                         error.empty() ? Param::null() : Param::text(error)});
  return r.rows() == 1;
}

// Ends, with their last error, the sessions that were claimed max_score_attempts times and
// never scored: each claim killed its scorer, or its worker (a lease that ran out).
void retire_poison(Connection& c) {
  c.exec("retire sessions that kill their scorer",
         "UPDATE work_queue w SET done = true, lease_owner = NULL, lease_expires = NULL, "
         "last_error = 'retired after ' || w.attempts || ' attempts: ' || "
         "coalesce(w.last_error, 'each claim ended without a score: its worker stopped or lost the server "
         "while scoring (the lease ran out)') "
         "WHERE NOT w.done AND w.attempts >= (SELECT max_score_attempts FROM store_settings) "
         "AND (w.lease_expires IS NULL OR w.lease_expires < now())");
}

// Gives the row back with `error` if `owner` holds it; true when it did.
bool give_back(Connection& c, long long id, const std::string& owner, const std::string& error) {
  const auto r = c.exec("give the claim back",
                        "UPDATE work_queue SET lease_owner = NULL, lease_expires = NULL, last_error = $3 "
                        "WHERE session_id = $1::bigint AND lease_owner = $2 AND NOT done RETURNING session_id",
                        {Param::text(std::to_string(id)), Param::text(owner), Param::text(error)});
  return r.rows() == 1;
}

Claim read_claim(Connection& c, long long id) {
  const auto r = c.exec("read the claimed session",
                        "SELECT s.session_id, s.file_name, s.file, s.station, t.name, s.mode, "
                        "extract(epoch FROM s.started_at)::text, s.samples::text, c.document::text "
                        "FROM sessions s JOIN trainees t ON t.id = s.trainee_id JOIN cases c ON c.id = s.case_id "
                        "WHERE s.id = $1::bigint",
                        {Param::text(std::to_string(id))}, true);
  if (r.rows() != 1) throw StoreError(fmt::format("store: session row {} is gone", id), false);
  Claim claim;
  claim.id = id;
  claim.session_id = r.text(0, 0);
  claim.file_name = r.text(0, 1);
  claim.file = r.bytes(0, 2);
  claim.station = r.text(0, 3);
  claim.trainee = r.text(0, 4);
  claim.mode = r.text(0, 5);
  // A binary result: numbers asked for as text, so they read the same on every platform.
  claim.started_at_s = std::strtod(r.text(0, 6).c_str(), nullptr);
  claim.samples = std::strtoll(r.text(0, 7).c_str(), nullptr, 10);
  claim.case_document = r.text(0, 8);
  return claim;
}

}  // namespace

std::string describe(const Claim& claim) {
  return report::printable(fmt::format("session {} from station {} ({})", claim.session_id, claim.station,
                                       claim.file_name),
                           300);
}

std::optional<Claim> claim_next(Connection& c, const std::string& owner, double lease_s) {
  retire_poison(c);
  const auto claimed = c.exec("claim a session", "SELECT public.palpa_claim_session($1, $2::double precision)",
                              {Param::text(owner), Param::text(fmt::format("{}", lease_s))});
  if (claimed.is_null(0, 0)) return std::nullopt;
  const long long id = claimed.integer(0, 0);
  try {
    return read_claim(c, id);
  } catch (const StoreError& e) {
    if (c.broken()) throw;
    // A row this worker cannot read (the server ran out of memory making its text, a
    // timeout): given back with the reason, so that it is retired after
    // max_score_attempts claims, whatever the error's class.
    give_back(c, id, owner, e.what());
    throw ClaimError(fmt::format("store: session row {}: {}", id, e.what()));
  }
}

bool renew_claim(Connection& c, const Claim& claim, const std::string& owner, double lease_s) {
  const auto r = c.exec("renew the lease",
                        "UPDATE work_queue SET lease_expires = now() + make_interval(secs => $3::double precision) "
                        "WHERE session_id = $1::bigint AND lease_owner = $2 AND NOT done RETURNING session_id",
                        {Param::text(std::to_string(claim.id)), Param::text(owner),
                         Param::text(fmt::format("{}", lease_s))});
  return r.rows() == 1;
}

long long pending_count(Connection& c) {
  return c.exec("count unscored sessions", "SELECT count(*) FROM work_queue WHERE NOT done").integer(0, 0);
}

bool finish_claim(Connection& c, const Claim& claim, const std::string& owner, const ScoreRow& row) {
  Transaction t(c);
  if (!end_claim(c, claim, owner, {})) return false;
  c.exec("write the score",
         "INSERT INTO scores(session_id, scorer_version, thresholds_sha256, score, passed, result, worker) "
         "VALUES ($1::bigint, $2, $3, $4::double precision, $5::boolean, $6::jsonb, $7) "
         "ON CONFLICT (session_id, scorer_version, thresholds_sha256) DO NOTHING",
         {Param::text(std::to_string(claim.id)), Param::text(row.scorer_version), Param::text(row.thresholds_sha256),
          Param::text(fmt::format("{}", row.score)), Param::text(row.passed ? "true" : "false"),
          Param::text(row.result_json), Param::text(owner)});
  t.commit();
  return true;
}

bool release_claim(Connection& c, const Claim& claim, const std::string& owner, const std::string& error) {
  return give_back(c, claim.id, owner, error);
}

bool fail_claim(Connection& c, const Claim& claim, const std::string& owner, const std::string& error) {
  Transaction t(c);
  if (!end_claim(c, claim, owner, error)) return false;
  t.commit();
  return true;
}

}  // namespace palpa::store
