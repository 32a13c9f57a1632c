#pragma once
// Uploading finished sessions to the centre store (docs/centre.md, "Pushing sessions"):
// idempotent by the session's id, verified by the SHA-256 of the file computed here and by
// the server. The GUI and palpa-cli exercise can call push_session after each exercise.
#include <cstdint>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "palpa/store/pg.hpp"

namespace palpa::store {

/// A session file read and checked locally, ready to upload.
struct PreparedSession {
  std::filesystem::path path;
  std::string file_name;  ///< stored with the session: the file's name, or the name it had before the outbox
  std::string bytes;    ///< the file as it is on disk
  std::string sha256;   ///< of `bytes`, hex
  std::string session_id, trainee, started_at, mode, case_title;
  nlohmann::json case_document, events;
  bool complete = false;
  std::uint64_t samples = 0;
};

/// Reads `path` through the session reader. Throws StoreError (not unreachable), one line
/// naming the file, for a file that is no readable session, a session still being recorded
/// (a -wal beside it) or one cut short (no end event): such sessions are not pushed.
PreparedSession prepare_session(const std::filesystem::path& path);

enum class PushStatus { Stored, AlreadyStored };

struct PushResult {
  PushStatus status = PushStatus::Stored;
  std::string session_id;
  std::string sha256;  ///< as confirmed by the server
};

/// Uploads one prepared session from station `station` in one transaction and checks the
/// server's SHA-256 of the stored bytes against the local one (rolled back on a mismatch).
/// A session already stored with the same checksum is AlreadyStored; with another checksum
/// it is an error. Throws StoreError (unreachable when the connection broke).
PushResult push_prepared(Connection& c, const PreparedSession& session, const std::string& station);

/// A path as messages show it: control and bidirectional characters escaped, shortened.
std::string shown(const std::filesystem::path& path);

/// prepare_session + push_prepared.
PushResult push_session(Connection& c, const std::filesystem::path& path, const std::string& station);

}  // namespace palpa::store
