#include "palpa/session/replay.hpp"

#include <algorithm>
#include <cmath>

namespace palpa::session {

std::size_t sample_at(const std::vector<engine::Sample>& samples, double t) {
  // First sample after t; the one before it is standing at t.
  const auto after = std::upper_bound(samples.begin(), samples.end(), t,
                                      [](double time, const engine::Sample& s) { return time < s.t; });
  if (after == samples.begin()) return 0;
  return static_cast<std::size_t>(after - samples.begin()) - 1;
}

std::vector<std::vector<PathPoint>> contact_path(const std::vector<engine::Sample>& samples, double min_step) {
  std::vector<std::vector<PathPoint>> path;
  const double step2 = min_step * min_step;
  const auto distance2 = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return dx * dx + dy * dy + dz * dz;
  };
  bool in_stretch = false;
  std::size_t last_in_contact = 0;
  const auto close_stretch = [&] {
    // Always keep the stretch's last sample, so the path ends where the finger lifted.
    auto& line = path.back();
    if (line.back().sample != last_in_contact) line.push_back(PathPoint{last_in_contact, samples[last_in_contact].position});
  };
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto& s = samples[i];
    if (s.body < 0) {
      if (in_stretch) close_stretch();
      in_stretch = false;
      continue;
    }
    if (!in_stretch) {
      path.push_back({PathPoint{i, s.position}});
      in_stretch = true;
    } else if (distance2(path.back().back().position, s.position) >= step2) {
      path.back().push_back(PathPoint{i, s.position});
    }
    last_in_contact = i;
  }
  if (in_stretch) close_stretch();
  return path;
}

std::vector<Mark> marks_at(const std::vector<Event>& events, double t) {
  // Events are in time order: those at or before t are a prefix.
  const auto end = std::upper_bound(events.begin(), events.end(), t,
                                    [](double time, const Event& e) { return time < e.t; });
  return standing_marks(std::vector<Event>(events.begin(), end));
}

TimeSpan time_span(const Session& session) {
  TimeSpan span;
  if (!session.samples.empty()) {
    span.start = session.samples.front().t;
    span.end = session.samples.back().t;
  }
  for (const auto& e : session.events) {
    if (e.kind == EventKind::End) span.end = std::max(span.end, e.t);
  }
  if (session.samples.empty() && !session.events.empty()) span.start = session.events.front().t;
  return span;
}

}  // namespace palpa::session
