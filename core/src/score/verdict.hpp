#pragma once
// The verdict on a measured exam (docs/scoring.md, "Gates", "Sub-scores", "Notes"): pass
// or fail by gates, a weighted score, and plain sentences for the trainee.
#include <optional>
#include <vector>

#include "palpa/score/score.hpp"
#include "palpa/session/session.hpp"
#include "timeline.hpp"

namespace palpa::score::detail {

/// The five gates of `score` (whose measures are filled in); `tumour_depth` gives each
/// tumour's depth below the top contour (m), for the message on a missed one.
std::vector<Gate> gates_of(const Score& score, const std::vector<double>& tumour_depth, const Thresholds& thresholds);

/// The sub-scores with their weights normalized to sum 1.
std::vector<SubScore> subscores_of(const Score& score, const Thresholds& thresholds);

/// Appends the notes on the session and its measures to score.notes. `last_t`: the last
/// sample's time, nothing when there were no samples.
void add_notes(Score& score, bool complete, std::optional<double> last_t, const Timeline& timeline,
               std::size_t ignored, const Thresholds& thresholds);

}  // namespace palpa::score::detail
