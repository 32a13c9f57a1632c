#include "palpa/session/session.hpp"

#include <algorithm>
#include <utility>

namespace palpa::session {

std::string_view to_string(EventKind kind) {
  switch (kind) {
    case EventKind::Start: return "start";
    case EventKind::Mark: return "mark";
    case EventKind::Unmark: return "unmark";
    case EventKind::Pause: return "pause";
    case EventKind::Resume: return "resume";
    case EventKind::End: return "end";
  }
  return "unknown";
}

std::optional<EventKind> event_kind_from_string(std::string_view name) {
  for (auto kind : {EventKind::Start, EventKind::Mark, EventKind::Unmark, EventKind::Pause, EventKind::Resume,
                    EventKind::End}) {
    if (to_string(kind) == name) return kind;
  }
  return std::nullopt;
}

std::vector<Mark> standing_marks(const std::vector<Event>& events) {
  std::vector<Mark> marks;
  const auto find = [&](std::int64_t id) {
    return std::find_if(marks.begin(), marks.end(), [id](const Mark& m) { return m.id == id; });
  };
  for (const auto& event : events) {
    if (event.kind == EventKind::Mark) {
      // Ids are unique by contract; should one be placed again, the mark moves (the newer
      // placement is the one standing).
      if (auto it = find(event.mark); it != marks.end()) marks.erase(it);
      marks.push_back(Mark{event.mark, event.t, event.position});
    } else if (event.kind == EventKind::Unmark) {
      if (auto it = find(event.mark); it != marks.end()) marks.erase(it);  // unknown ids: ignored
    }
  }
  return marks;
}

namespace {
// what() is one line even when a reason (an SQLite message, a file name) holds a newline.
std::string one_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}
}  // namespace

SessionError::SessionError(std::string file, std::string where, std::string reason)
    : std::runtime_error(one_line(file + ": " + where + ": " + reason)),
      file_(std::move(file)),
      where_(std::move(where)),
      reason_(std::move(reason)) {}

bool is_abandoned(const Session& session) {
  for (const auto& e : session.events) {
    if (e.kind == EventKind::End) return e.note.rfind(kAbandonedNote, 0) == 0;
  }
  return false;
}

std::string session_mode(const SessionInfo& info) {
  const auto& x = info.extra;
  if (!x.is_object()) return "unknown";
  if (const auto m = x.find("mode"); m != x.end() && m->is_string() && !m->get_ref<const std::string&>().empty())
    return m->get<std::string>();
  if (x.contains("replayed_from")) return "replay";
  if (x.contains("exercise_style")) return "scripted";
  if (x.contains("trajectory")) return "simulated";
  return "unknown";
}

}  // namespace palpa::session
