#pragma once
// One CSV row per scored session. The header is a contract with users' scripts: add
// columns only at the end, never rename or reorder.
#include <string>
#include <string_view>

#include "palpa/report/session_header.hpp"
#include "palpa/score/score.hpp"

namespace palpa::report {

/// "file,session_id,trainee,case,started_at,passed,score,...,complete,samples,outcome,mode,
/// case_file,case_id,score_100" (no newline).
const std::string& csv_header();

/// The row for one session (no newline): passed, safe and complete as 1/0; score 0..1;
/// localization_error_mm the mean over found tumours, empty when none was found; score_100
/// the score out of 100; numbers rounded to their unit (csv_number.hpp); text fields quoted
/// per RFC 4180.
std::string csv_row(const SessionHeader& header, const score::Score& score);

/// A CSV text cell: RFC 4180 quoting and the formula guard of csv_field, after printable()
/// without shortening, so that an ESC, a NUL, a line break or a bidirectional override in a
/// name from a session file is written as \x1b, \u{202e} ... and never reaches a reader's
/// terminal or spreadsheet raw. Plain text is written as csv_field writes it.
std::string csv_text(std::string_view text);

/// "passed", "failed", "abandoned" (the trainee gave it up: no exam) or "incomplete" (cut short).
const char* outcome_of(const score::Score& score);

/// Mean localization error over found tumours (mm); NaN when none was found.
double mean_localization_error_mm(const score::Score& score);

}  // namespace palpa::report
