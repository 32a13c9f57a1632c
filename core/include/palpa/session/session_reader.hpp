#pragma once
// Reads session files (docs/session-format.md) read-only. A session cut short by a crash
// is read up to its last commit (Session::complete is false). Anything unreadable or
// inconsistent throws SessionError naming the file and the place.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "palpa/session/session.hpp"

namespace palpa::session {

struct ReadOptions {
  bool samples = true;  ///< false: info, events and stats only (fast listing)
  /// A session with more samples is refused before a row is read: 20 hours at 1 kHz, the
  /// longest Palpa reads. read_session holds them all (96 bytes each: 6.9 GB, 12.6 GB at
  /// the peak while the vector grows); SampleStream one block at a time.
  std::int64_t max_samples = 72'000'000;
};

/// Throws SessionError: not a file, not SQLite, not a Palpa session, a newer format
/// version, a missing table or meta key, a NULL or non-finite value where a number is
/// required, ticks out of order, an invalid case document.
Session read_session(const std::filesystem::path& path, const ReadOptions& options = {});


/// The time of a session's first and last sample (s).
struct SampleTimes {
  double first = 0.0, last = 0.0;
};

/// A session's samples read one block at a time (up to 65536 ticks; 1024 as Palpa writes
/// them, or 1024 rows of format 1): memory bounded by a block whatever the session's length,
/// for whoever needs one pass over them (scoring). The same checks as read_session, with
/// the same messages, made as the samples come. The file stays open in one read transaction
/// (one consistent snapshot) until the last block was read or the stream is destroyed.
class SampleStream {
 public:
  /// Reads everything but the samples and checks their count; throws SessionError as
  /// read_session does.
  explicit SampleStream(const std::filesystem::path& path, std::int64_t max_samples = ReadOptions{}.max_samples);
  /// The same for a whole session file held in memory, named `name` in errors (`bytes`
  /// must outlive the stream).
  SampleStream(const std::string& bytes, const std::string& name,
               std::int64_t max_samples = ReadOptions{}.max_samples);
  ~SampleStream();
  SampleStream(const SampleStream&) = delete;
  SampleStream& operator=(const SampleStream&) = delete;

  /// Info, events, loop statistics, completeness and format; `samples` is empty.
  const Session& head() const;
  /// The next samples in tick order, valid until the next call; empty once all were read.
  /// Throws SessionError where the file is wrong (read_session's message).
  std::span<const engine::Sample> next();
  /// How many samples next() has returned.
  std::uint64_t count() const;
  /// How many samples the file says it holds (rows, or the blocks' counts), known before the
  /// first next(): what next() returns in all for a file it reads to the end without error.
  std::uint64_t declared_count() const;
  /// The first and last sample's time, looked up before reading them in order (a timeline
  /// needs the end before the first sample). Unchecked: nothing when there are no samples
  /// or the first or last cannot be read (next() then throws before the end), and a file
  /// next() refuses may give any value. Call before next().
  std::optional<SampleTimes> sample_times();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace palpa::session
