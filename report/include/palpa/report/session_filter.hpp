#pragma once
// Which sessions a batch's outputs cover: a start-time range, a case, a trainee. Works on
// the SessionHeader alone, so the folder batch and a database-backed one select alike.
#include <optional>
#include <stdexcept>
#include <string>

#include "palpa/report/session_header.hpp"

namespace palpa::report {

/// A bad option value; what() is one line naming the option ("--since: ...").
class FilterError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// An instant as seconds since 1970-01-01T00:00:00Z, from an ISO 8601 text: a date
/// "YYYY-MM-DD" or a time "YYYY-MM-DDTHH:MM[:SS[.fff]]" with "Z" or "+HH:MM"/"-HH:MM"
/// (UTC without a zone, as started_at is written). nullopt when it is neither or a field
/// is out of range (month 13, 31 April, hour 24). `date_only` says whether it was a date.
std::optional<double> parse_iso8601(const std::string& text, bool* date_only = nullptr);

struct SessionFilter {
  std::string since, until;  ///< as given; a date covers its whole day (until: to its end)
  std::string case_key;      ///< matches case_id, case_file, case_id without "urn:palpa:case:", or case_file's stem
  std::string trainee;       ///< matches the trainee id exactly

  /// Checks the values; throws FilterError for a bad date or since after until.
  void validate() const;
  /// Every condition holds; a session whose started_at cannot be read never passes a date bound.
  bool matches(const SessionHeader& header) const;
  bool empty() const { return since.empty() && until.empty() && case_key.empty() && trainee.empty(); }
  /// "sessions from 2026-11-01 to 2026-11-30, case default", "sessions of trainee alice";
  /// empty when the filter is empty.
  std::string describe() const;
};

}  // namespace palpa::report
