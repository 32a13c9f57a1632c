#include "timeline.hpp"

#include <algorithm>

namespace palpa::score::detail {
namespace {

void find_start_and_end(const std::optional<session::SampleTimes>& samples, const std::vector<session::Event>& events,
                        Timeline& tl) {
  bool have_start = false, have_end = false;
  for (const auto& e : events) {
    if (e.kind == session::EventKind::Start && !have_start) {
      tl.start = e.t;
      have_start = true;
    }
    if (e.kind == session::EventKind::End && !have_end) {
      tl.end = e.t;
      have_end = true;
    }
  }
  if (!have_start) tl.start = samples ? samples->first : 0.0;
  if (!have_end) tl.end = samples ? samples->last : tl.start;
  tl.end = std::max(tl.end, tl.start);
}

void find_pauses(const std::vector<session::Event>& events, Timeline& tl) {
  bool paused = false;
  double since = 0.0;
  auto add = [&](double a, double b) {
    a = std::max(a, tl.start);
    b = std::min(b, tl.end);
    if (b > a) tl.pauses.emplace_back(a, b);
  };
  for (const auto& e : events) {
    if (e.kind == session::EventKind::Pause && !paused) {
      paused = true;
      since = e.t;
    } else if (e.kind == session::EventKind::Resume && paused) {
      paused = false;
      add(since, e.t);
    }
  }
  if (paused) add(since, tl.end);
}

}  // namespace

Timeline timeline_of(const std::vector<session::Event>& session_events,
                     const std::optional<session::SampleTimes>& samples) {
  Timeline tl;
  std::vector<session::Event> events = session_events;
  std::stable_sort(events.begin(), events.end(), [](const auto& a, const auto& b) { return a.t < b.t; });
  find_start_and_end(samples, events, tl);
  find_pauses(events, tl);
  tl.active = tl.end - tl.start;
  for (const auto& [a, b] : tl.pauses) tl.active -= b - a;
  tl.active = std::max(0.0, tl.active);
  return tl;
}

}  // namespace palpa::score::detail
