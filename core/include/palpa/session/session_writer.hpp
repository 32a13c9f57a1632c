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

struct WriterOptions {
  /// The format finish() leaves: 2 compacts the ticks into blocks (quantized to the format's
  /// units, docs/session-format.md), 1 keeps one row per tick, every double exact (tests,
  /// files for readers that know only format 1). While recording, a session is format 1.
  int format_version = kFormatVersion;
};

class SessionWriter {
 public:
  /// Creates `path` (which must not exist: recorded data is never overwritten), writes the
  /// schema and `info`, and opens the first transaction. Throws SessionError.
  SessionWriter(const std::filesystem::path& path, const SessionInfo& info, const WriterOptions& options = {});
  /// Commits what is pending and closes (a session without finish() stays incomplete).
  ~SessionWriter();
  SessionWriter(const SessionWriter&) = delete;
  SessionWriter& operator=(const SessionWriter&) = delete;

  /// Adds one tick to the open transaction. Throws SessionError on a write failure and on
  /// a sample the reader would refuse: a non-finite value, t before the previous tick's, a
  /// body that is not a body of the case.
  void append(const engine::Sample& sample);
  /// Like append(), but a sample the reader would refuse is stored repaired instead of
  /// refused: fault = 1, a non-finite position or force component 0, t before the previous
  /// tick's (or not finite) the previous tick's t, an unusable contact (unknown body,
  /// non-finite u, v or depth) out of contact. Returns false when it repaired the sample
  /// (counted in samples_repaired()). For the recorder: one bad tick must not stop a session.
  /// Throws SessionError only on a write failure.
  bool append_repairing(const engine::Sample& sample);
  /// Throws SessionError on an event the reader would refuse (see check_event()).
  void event(const Event& event);
  /// Stores (replaces) the loop statistics summary.
  void set_loop_stats(const engine::LoopStats& stats);
  /// Same, with the samples the loop dropped because its ring was full
  /// (RealtimeLoop::dropped_samples()), stored as loop_stats.dropped.
  void set_loop_stats(const engine::LoopStats& stats, std::uint64_t dropped_samples);
  /// Stores (replaces) a summary already in the file's JSON form (copying a session).
  void set_loop_stats(const nlohmann::json& summary);
  /// Ends the open transaction (durable against a crash of this process) and opens the next.
  void commit();
  /// Commits, compacts the ticks into format 2 (unless the options say 1), checkpoints the
  /// WAL into the main file and closes. Call after the End event.
  /// When another program has the file open, the switch out of write-ahead logging cannot
  /// be made: the data is committed all the same, the file stays in WAL mode (its -wal and
  /// -shm beside it) and warning() says so; that is not an error. Nor is a session whose
  /// values do not fit format 2's units (an absurd position): it stays format 1, warning()
  /// says why.
  void finish();

  std::uint64_t samples_written() const { return samples_; }
  std::uint64_t samples_repaired() const { return repaired_; }
  const std::filesystem::path& path() const { return path_; }
  /// Empty, or what finish() could not do that is not an error (the file left in WAL mode).
  const std::string& warning() const { return warning_; }

 private:
  void close() noexcept;
  void compact();
  void insert(const engine::Sample& sample);
  void put_loop_stats(const nlohmann::json& summary);
  std::filesystem::path path_;
  sqlite3* db_ = nullptr;
  sqlite3_stmt* insert_sample_ = nullptr;
  sqlite3_stmt* insert_event_ = nullptr;
  std::uint64_t samples_ = 0;
  std::uint64_t repaired_ = 0;
  double last_t_ = 0.0;        ///< t of the last tick written (valid when samples_ > 0)
  std::size_t bodies_ = 0;     ///< in the session's case: a sample's body is below it
  WriterOptions options_;
  std::string warning_;
};

/// Throws SessionError (naming `file`) when the reader would refuse `event`: a non-finite
/// t, a Mark or Unmark without an id >= 1, a Mark without a finite position, a note that is
/// not valid UTF-8. SessionWriter::event and SessionRecorder::event check with it.
void check_event(const std::string& file, const Event& event);

/// Writes a whole session in one go (tests, converters): info, samples, events, stats;
/// complete if the events end with End.
void write_session(const std::filesystem::path& path, const Session& session, const WriterOptions& options = {});

}  // namespace palpa::session
