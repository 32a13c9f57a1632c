#pragma once
// Scores a claimed session the way palpa-cli score does: the stored bytes written to a
// temporary file, read with session::read_session, scored with score::score_session.
#include <string>

#include "palpa/store/work_queue.hpp"

namespace palpa::store {

/// The score row of the claimed session (scorer version palpa::kVersion, the SHA-256 of
/// the thresholds' JSON, score::to_json without maps). Throws session::SessionError for a
/// session that cannot be read or scored, StoreError when no temporary file can be made.
ScoreRow score_claim(const Claim& claim);

}  // namespace palpa::store
