#pragma once
// Scoring a store's session in a child process under limits (docs/security.md, "Poison
// sessions"): a session file is untrusted, and one that makes the scorer use all memory or
// run for ever must cost its worker nothing but that child. The bytes go to the child in an
// anonymous memory file (memfd), so no copy outlives the worker, whatever kills it.
#include <functional>
#include <string>

#include "palpa/store/work_queue.hpp"

namespace palpa::cli {

struct ScoreLimits {
  long memory_mb = 2048;  ///< the child's address space (RLIMIT_AS); not applied under ASan
  long cpu_s = 600;       ///< the child's CPU time (RLIMIT_CPU); the wall-clock limit is twice it + 10 s
};

enum class ScoreOutcome {
  Scored,   ///< `row` holds the score
  Refused,  ///< the file is no session, or it disagrees with its row: `error`; never retried
  Killed,   ///< the child died (memory, time, crash): `error`; retried until retired
};

struct IsolatedScore {
  ScoreOutcome outcome = ScoreOutcome::Killed;
  store::ScoreRow row;
  std::string error;
};

/// Scores `claim` in a child process (this executable, `store score-claim`) under `limits`.
/// `while_waiting` runs about four times a second while the child works (the worker renews its
/// lease there); an exception from it propagates after the child is killed.
IsolatedScore score_in_child(const store::Claim& claim, const ScoreLimits& limits,
                             const std::function<void()>& while_waiting = {});

/// The child's side: reads the claim's row (JSON) from fd 4 and the session from fd 3,
/// prints the score row as JSON on stdout. Exit 0 scored, 2 refused, 4 out of memory.
int run_score_child();

}  // namespace palpa::cli
