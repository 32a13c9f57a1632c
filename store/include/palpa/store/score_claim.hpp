#pragma once
// Scores a claimed session the way palpa-cli score does, after checking that the file's own
// metadata agree with what the store's row says of it (a station could send a file that
// says one thing and a row that says another). Runs in the worker's scoring child process
// (app/cli/isolated_score.cpp), which reads the bytes from an anonymous memory file and
// the session from memory: no copy on disk.
#include <string>

#include "palpa/store/work_queue.hpp"

namespace palpa::store {

/// The score row of the claimed session whose file is `bytes` (scorer version palpa::kVersion, the
/// SHA-256 of the thresholds' JSON, score::to_json without maps). Throws
/// session::SessionError naming the claim (describe) for a session that
/// cannot be read or scored or whose id, trainee, mode, start, sample count or case
/// differ from the row.
ScoreRow score_claim_bytes(const std::string& bytes, const Claim& claim);

}  // namespace palpa::store
