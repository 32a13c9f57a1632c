#pragma once
// Replaying a recorded session (review mode): the sample standing at a time t, the probe
// path thinned for drawing, and the marks standing at t. Headless; the review window
// turns these into VTK actors.
#include <array>
#include <cstddef>
#include <vector>

#include "palpa/session/session.hpp"

namespace palpa::session {

/// Index of the sample standing at time t: the last sample with sample.t <= t (binary
/// search; the samples are in tick order). t before the first sample gives 0; an empty
/// list gives 0 too (callers check for samples first).
std::size_t sample_at(const std::vector<engine::Sample>& samples, double t);

/// A point of the drawn probe path.
struct PathPoint {
  std::size_t sample = 0;  ///< index of the sample it came from
  std::array<double, 3> position{};  ///< m
};

/// The probe path as polylines of in-contact samples (body >= 0), one polyline per contact
/// stretch, thinned so that consecutive kept points are at least `min_step` (m) apart; the
/// first and last sample of each stretch are always kept.
std::vector<std::vector<PathPoint>> contact_path(const std::vector<engine::Sample>& samples, double min_step);

/// Marks standing at time t: placed at or before t and not removed at or before t, in
/// placement order (standing_marks over the events up to t).
std::vector<Mark> marks_at(const std::vector<Event>& events, double t);

/// The replay's time span: first sample to the end (End event or last sample), s.
struct TimeSpan {
  double start = 0.0, end = 0.0;
};
TimeSpan time_span(const Session& session);

}  // namespace palpa::session
