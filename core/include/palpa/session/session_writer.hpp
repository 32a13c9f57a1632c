#pragma once
// Writes a session file: SQLite in WAL mode, samples and events inserted in batched
// transactions, so that a writer killed mid-session leaves a file readable up to the last
// commit (commit() at least once a second; the recorder does it every 0.25 s).
// Not for the haptic thread: the writer thread (SessionRecorder) or a headless driver owns it.
#include <filesystem>
#include <memory>

#include "palpa/engine/loop_stats.hpp"
#include "palpa/session/session.hpp"

struct sqlite3;
struct sqlite3_stmt;

namespace palpa::session {

class SessionWriter {
 public:
  /// Creates `path` (which must not exist: recorded data is never overwritten), writes the
  /// schema and `info`, and opens the first transaction. Throws SessionError.
  SessionWriter(const std::filesystem::path& path, const SessionInfo& info);
  /// Commits what is pending and closes (a session without finish() stays incomplete).
  ~SessionWriter();
  SessionWriter(const SessionWriter&) = delete;
  SessionWriter& operator=(const SessionWriter&) = delete;

  /// Adds one tick to the open transaction. Throws SessionError on a write failure.
  void append(const engine::Sample& sample);
  void event(const Event& event);
  /// Stores (replaces) the loop statistics summary.
  void set_loop_stats(const engine::LoopStats& stats);
  /// Stores (replaces) a summary already in the file's JSON form (copying a session).
  void set_loop_stats(const nlohmann::json& summary);
  /// Ends the open transaction (durable against a crash of this process) and opens the next.
  void commit();
  /// Commits, checkpoints the WAL into the main file and closes. Call after the End event.
  void finish();

  std::uint64_t samples_written() const { return samples_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  void close() noexcept;
  std::filesystem::path path_;
  sqlite3* db_ = nullptr;
  sqlite3_stmt* insert_sample_ = nullptr;
  sqlite3_stmt* insert_event_ = nullptr;
  std::uint64_t samples_ = 0;
};

/// Writes a whole session in one go (tests, converters): info, samples, events, stats;
/// complete if the events end with End.
void write_session(const std::filesystem::path& path, const Session& session);

}  // namespace palpa::session
