#pragma once
// The active part of a session: start to end minus pauses (docs/scoring.md, "Duration").
#include <optional>
#include <utility>
#include <vector>

#include "palpa/session/session.hpp"
#include "palpa/session/session_reader.hpp"

namespace palpa::score::detail {

struct Timeline {
  double start = 0.0, end = 0.0;
  std::vector<std::pair<double, double>> pauses;  ///< clipped to [start, end], in order
  double active = 0.0;                            ///< end - start - pauses, >= 0
};

/// From the first Start and End events (the first and last sample when one is missing)
/// and the Pause/Resume pairs between them; a pause left open runs to the end. `samples`:
/// the first and last sample's time, nothing when there are none.
Timeline timeline_of(const std::vector<session::Event>& events, const std::optional<session::SampleTimes>& samples);

}  // namespace palpa::score::detail
