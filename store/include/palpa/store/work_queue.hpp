#pragma once
// The work queue of the store's scoring workers (docs/centre.md, "Workers and leases"):
// a worker claims one unscored session with SELECT ... FOR UPDATE SKIP LOCKED and a lease
// (owner, expiry), commits the claim, scores it, then writes the score and ends the claim
// in one transaction only if it still holds the lease. An expired lease may be taken by
// another worker, so a killed worker's session is scored by the next one.
#include <optional>
#include <string>

#include "palpa/store/pg.hpp"

namespace palpa::store {

/// A claimed session: its row as the store holds it and the file's bytes. The worker
/// checks that the file's own metadata agree with the row before scoring it.
struct Claim {
  long long id = 0;         ///< sessions.id
  std::string session_id;   ///< the session file's own id
  std::string file_name;
  std::string file;         ///< the session file's bytes
  std::string station, trainee, mode;
  double started_at_s = 0.0;      ///< Unix time
  long long samples = 0;
  std::string case_document;      ///< the stored case, JSON text
};

/// "session ID from station S (FILE)", escaped for terminals: how errors name a claim.
std::string describe(const Claim& claim);

/// Claims the next unscored session for `owner` for `lease_s` seconds; nothing when no
/// session is free to claim now. Fair across station logins: the session comes from the
/// login whose last claim is oldest (palpa_claim_session), the lowest id within it. A session `owner` holds already is free to it: a worker
/// whose connection broke mid-session (a server restart) takes it up again on reconnecting
/// instead of leaving it until its lease runs out. First retires the sessions claimed max_score_attempts
/// times without a score (their scorers were killed: poison sessions), keeping the reason.
std::optional<Claim> claim_next(Connection& c, const std::string& owner, double lease_s);

/// A claimed row that could not be read (given back with the reason): the worker goes on
/// with the next session.
class ClaimError : public StoreError {
 public:
  explicit ClaimError(const std::string& message) : StoreError(message, false) {}
};

/// Extends the lease of a claim `owner` holds to `lease_s` seconds from now: a worker
/// renews it while its scorer runs, so a lease never runs out under a live worker;
/// false when the lease was lost.
bool renew_claim(Connection& c, const Claim& claim, const std::string& owner, double lease_s);

/// Sessions not scored yet (claimed or not).
long long pending_count(Connection& c);

struct ScoreRow {
  std::string scorer_version, thresholds_sha256, result_json;
  double score = 0.0;
  bool passed = false;
};

/// Writes the score and ends the claim in one transaction if `owner` still holds it;
/// false (nothing written) when another worker took the session over.
bool finish_claim(Connection& c, const Claim& claim, const std::string& owner, const ScoreRow& row);

/// Gives a claimed session back after its scorer was killed or timed out: the next claim
/// may take it at once, and after store_settings.max_score_attempts claims it is retired
/// with this reason (claim_next); false when the lease was lost.
bool release_claim(Connection& c, const Claim& claim, const std::string& owner, const std::string& error);

/// Ends the claim of a session that cannot be scored, keeping the reason in last_error
/// (it is not claimed again); false when the lease was lost.
bool fail_claim(Connection& c, const Claim& claim, const std::string& owner, const std::string& error);

}  // namespace palpa::store
