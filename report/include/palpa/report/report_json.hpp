#pragma once
// The machine-readable report of one session: score::to_json plus a "session" object.
#include <nlohmann/json.hpp>

#include "palpa/report/session_header.hpp"
#include "palpa/score/score.hpp"

namespace palpa::report {

/// score::to_json(score) (without the per-cell maps) with "session": to_json(header).
nlohmann::json report_json(const SessionHeader& header, const score::Score& score);

}  // namespace palpa::report
