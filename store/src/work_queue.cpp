#include "palpa/store/work_queue.hpp"

#include <fmt/format.h>

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

}  // namespace

std::optional<Claim> claim_next(Connection& c, const std::string& owner, double lease_s) {
  Transaction t(c);
  const auto claimed = c.exec(
      "claim a session",
      "UPDATE work_queue w SET lease_owner = $1, lease_expires = now() + make_interval(secs => $2::double precision), "
      "attempts = w.attempts + 1 "
      "WHERE w.session_id = (SELECT q.session_id FROM work_queue q WHERE NOT q.done "
      "AND (q.lease_expires IS NULL OR q.lease_expires < now()) ORDER BY q.session_id "
      "LIMIT 1 FOR UPDATE SKIP LOCKED) RETURNING w.session_id",
      {Param::text(owner), Param::text(fmt::format("{}", lease_s))});
  if (claimed.rows() == 0) return std::nullopt;
  t.commit();
  Claim claim;
  claim.id = claimed.integer(0, 0);
  const auto r = c.exec("read the claimed session", "SELECT session_id, file_name, file FROM sessions WHERE id = $1::bigint",
                        {Param::text(std::to_string(claim.id))}, true);
  claim.session_id = r.text(0, 0);
  claim.file_name = r.text(0, 1);
  claim.file = r.bytes(0, 2);
  return claim;
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

bool fail_claim(Connection& c, const Claim& claim, const std::string& owner, const std::string& error) {
  Transaction t(c);
  if (!end_claim(c, claim, owner, error)) return false;
  t.commit();
  return true;
}

}  // namespace palpa::store
