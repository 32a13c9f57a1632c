#pragma once
// Reads session files (docs/session-format.md) read-only. A session cut short by a crash
// is read up to its last commit (Session::complete is false). Anything unreadable or
// inconsistent throws SessionError naming the file and the place.
#include <cstdint>
#include <filesystem>
#include <string>

#include "palpa/session/session.hpp"

namespace palpa::session {

struct ReadOptions {
  bool samples = true;  ///< false: info, events and stats only (fast listing)
  /// A session with more samples is refused before a row is read: 20 hours at 1 kHz, the
  /// longest Palpa reads (96 bytes each in memory, about 7 GB).
  std::int64_t max_samples = 72'000'000;
};

/// Throws SessionError: not a file, not SQLite, not a Palpa session, a newer format
/// version, a missing table or meta key, a NULL or non-finite value where a number is
/// required, ticks out of order, an invalid case document.
Session read_session(const std::filesystem::path& path, const ReadOptions& options = {});

/// The same for a whole session file held in memory (not one being recorded), named
/// `name` in errors: how a centre worker reads a claimed session without a copy on disk.
Session read_session_bytes(const std::string& bytes, const std::string& name, const ReadOptions& options = {});

}  // namespace palpa::session
