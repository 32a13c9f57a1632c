#pragma once
// A station's outbox (docs/centre.md, "The outbox"): copies of sessions that could not be
// uploaded, each as ID.palpa with ID.json beside it (source, trainee, started_at, size,
// queued_at, attempts, last_error). The station's own session files are never touched; an
// entry is removed only after the server confirmed its checksum.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "palpa/store/pg.hpp"
#include "palpa/store/push.hpp"

namespace palpa::store {

struct OutboxEntry {
  std::filesystem::path file;  ///< the copy in the outbox (ID.palpa)
  std::string source;          ///< the session file it was copied from
  std::string session_id, trainee, started_at, queued_at, last_error;
  std::uintmax_t size = 0;  ///< bytes
  int attempts = 0;
};

/// The outbox's copy of a session: OUTBOX/SESSION_ID.palpa (with SESSION_ID.json beside it).
std::filesystem::path queued_file(const std::filesystem::path& outbox, const std::string& session_id);

/// True when `s` waits in the outbox already (the same bytes); throws StoreError when the
/// outbox holds another file under its id (or a link), which is never replaced.
bool is_queued(const std::filesystem::path& outbox, const PreparedSession& s);

/// Copies the session into the outbox atomically (a temporary copy renamed into place),
/// creating the folder; when it is queued already, records the new error only. Returns
/// the entry. Throws StoreError naming the outbox when it cannot be written.
OutboxEntry queue_session(const std::filesystem::path& outbox, const PreparedSession& session,
                          const std::string& error);

/// The entries waiting, oldest first (an unreadable ID.json is listed with that error).
std::vector<OutboxEntry> list_outbox(const std::filesystem::path& outbox);

/// Records one more failed attempt with its error.
void record_attempt(const OutboxEntry& entry, const std::string& error);

/// Removes the entry's files (after the server confirmed the checksum).
void remove_entry(const OutboxEntry& entry);

struct FlushResult {
  int sent = 0;     ///< stored or found already stored with the same checksum: removed
  int waiting = 0;  ///< still in the outbox
  std::vector<std::string> errors;  ///< one line per entry that failed
};

/// Pushes every entry over `c` from station `station`; stops at the first broken
/// connection (the rest wait, marked with that error).
FlushResult flush_outbox(Connection& c, const std::filesystem::path& outbox, const std::string& station);

/// Marks every entry with `error` (the server could not be reached).
void mark_unreachable(const std::filesystem::path& outbox, const std::string& error);

}  // namespace palpa::store
