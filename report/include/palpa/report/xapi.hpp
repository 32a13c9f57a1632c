#pragma once
// An xAPI 1.0.3 statement for a scored session, for learning record stores: the trainee
// (actor, an account on the centre's homePage) passed or failed (verb) the case (activity), with the
// score, success, completion, duration and the palpation metrics as result extensions.
#include <string>

#include <nlohmann/json.hpp>

#include "palpa/report/session_header.hpp"
#include "palpa/score/score.hpp"

namespace palpa::report {

/// ISO 8601 duration in seconds rounded to 0.01 s (xAPI's recommended precision), without
/// trailing zeros: 183.25 -> "PT183.25S", 60 -> "PT60S". Negative or non-finite: "PT0S".
std::string iso8601_duration(double seconds);

/// The statement: id = uuid_v5(kPalpaNamespace, session id), so re-scoring a session gives
/// the same id (an LRS then treats it as the same statement); timestamp = started_at;
/// result.score.scaled = score (0..1), raw = 100 * score in [min 0, max 100];
/// extensions under "urn:palpa:xapi:..." (localization_error_mm null when nothing was found).
/// The actor is the account `header.trainee` on `home_page` (the centre's configured homePage,
/// docs/centre.md; "urn:palpa" when none is configured).
nlohmann::json xapi_statement(const SessionHeader& header, const score::Score& score,
                              const std::string& home_page = "urn:palpa");

}  // namespace palpa::report
