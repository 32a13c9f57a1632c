#pragma once
// Reads session files (docs/session-format.md) read-only. A session cut short by a crash
// is read up to its last commit (Session::complete is false). Anything unreadable or
// inconsistent throws SessionError naming the file and the place.
#include <filesystem>

#include "palpa/session/session.hpp"

namespace palpa::session {

struct ReadOptions {
  bool samples = true;  ///< false: info, events and stats only (fast listing)
};

/// Throws SessionError: not a file, not SQLite, not a Palpa session, a newer format
/// version, a missing table or meta key, a NULL or non-finite value where a number is
/// required, ticks out of order, an invalid case document.
Session read_session(const std::filesystem::path& path, const ReadOptions& options = {});

}  // namespace palpa::session
