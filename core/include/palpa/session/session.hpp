#pragma once
// A recorded exercise (docs/session-format.md): who palpated which case on which device,
// every haptic tick, the events (start, marks, pauses, end) and the loop statistics. The
// case is kept with its tumour ground truth as placed for this session, so a session can
// be replayed and re-scored without the case file.
#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "palpa/engine/engine.hpp"

namespace palpa::session {

/// Format identity stored in every session file (meta keys `format` and `format_version`).
/// Version 1 holds one row per tick (every session while it is recorded); version 2, what a
/// finished session becomes, holds the ticks compacted into blocks (docs/session-format.md).
/// The reader reads both; kFormatVersion is the newest it reads.
inline constexpr std::string_view kFormat = "palpa-session";
inline constexpr int kFormatVersion = 2;

enum class EventKind : std::uint8_t { Start, Mark, Unmark, Pause, Resume, End };

/// "start", "mark", "unmark", "pause", "resume", "end": the names stored in the file.
std::string_view to_string(EventKind kind);
std::optional<EventKind> event_kind_from_string(std::string_view name);

struct Event {
  double t = 0.0;  ///< s, on the samples' clock
  EventKind kind = EventKind::Start;
  /// Mark and Unmark: the mark's id (unique within the session, from 1); -1 otherwise.
  std::int64_t mark = -1;
  /// Mark: where the trainee placed it (m, scene coordinates: the probe position).
  std::array<double, 3> position{};
  std::string note;  ///< free text (e.g. why the session ended); may be empty
};

/// Everything about a session except its samples and events.
struct SessionInfo {
  std::string id;                ///< unique id (random hex) of this session
  std::string trainee;           ///< trainee id as given (--trainee); non-empty
  std::string device;            ///< device name (DeviceCapabilities::name)
  std::string software_version;  ///< palpa::kVersion of the recorder
  std::string started_at;        ///< ISO 8601 UTC, e.g. 2026-11-22T16:40:00Z
  double rate_hz = 1000.0;       ///< haptic rate
  std::string case_source;       ///< the case file as named when the session started
  /// The case as palpated: a valid case document (docs/case-format.md) whose tumours are
  /// at the positions placed for this session (the ground truth).
  nlohmann::json case_document = nlohmann::json::object();
  std::optional<std::uint64_t> seed;  ///< seed used to place randomized tumours, if any
  /// Free metadata (exercise style, GUI mode, ...): written and read back unchanged.
  nlohmann::json extra = nlohmann::json::object();
};

/// A mark still standing at the end of the session (placed and not removed).
struct Mark {
  std::int64_t id = -1;
  double t = 0.0;
  std::array<double, 3> position{};
};

struct Session {
  SessionInfo info;
  std::vector<engine::Sample> samples;  ///< in tick order
  std::vector<Event> events;            ///< in time order
  /// Loop statistics summary as recorded (docs/session-format.md); null when the session
  /// ended without them (a crash).
  nlohmann::json loop_stats;
  /// True when the session has an End event: false for a session cut short (crash, kill).
  bool complete = false;
  /// The file's format version (meta format_version): 1 (rows) or 2 (compact blocks).
  int format_version = kFormatVersion;
};

/// Marks placed and not removed, in placement order.
std::vector<Mark> standing_marks(const std::vector<Event>& events);

/// An attempt the trainee gave up (closed the window and chose to abandon it) ends with an
/// End event whose note starts with this word, followed by ": " and the reason. Such a
/// session is complete but no exam: reports call it abandoned, learning curves leave it out.
inline constexpr std::string_view kAbandonedNote = "abandoned";
bool is_abandoned(const Session& session);

/// What produced a session (docs/session-format.md, "Modes"): "trainee" (a trainee's
/// exercise in the window), "instructor-try" (an instructor's Try it), "scripted" (palpa-cli
/// exercise), "replay" (exercise --device replay:...), "simulated" (palpa-cli simulate),
/// "bench". The meta's extra "mode"; for sessions recorded before it was written, inferred
/// from the other extra keys ("unknown" when nothing tells).
std::string session_mode(const SessionInfo& info);

/// A session file that cannot be read, or a session that is inconsistent. what() is one
/// line "FILE: WHERE: REASON", WHERE naming the table, meta key or row (e.g.
/// "samples row 1234: column t").
class SessionError : public std::runtime_error {
 public:
  SessionError(std::string file, std::string where, std::string reason);
  const std::string& file() const { return file_; }
  const std::string& where() const { return where_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string file_, where_, reason_;
};

}  // namespace palpa::session
