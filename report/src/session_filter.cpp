#include "palpa/report/session_filter.hpp"

#include <cctype>
#include <filesystem>
#include <vector>

#include <fmt/format.h>

namespace palpa::report {
namespace {

constexpr double kDay = 86400.0;

/// Days from 1970-01-01 to a civil date (proleptic Gregorian; H. Hinnant's algorithm).
long long days_from_civil(long long y, unsigned m, unsigned d) {
  y -= m <= 2 ? 1 : 0;
  const long long era = (y >= 0 ? y : y - 399) / 400;
  const auto yoe = static_cast<unsigned>(y - era * 400);
  const unsigned month_from_march = m > 2 ? m - 3 : m + 9;
  const unsigned doy = (153 * month_from_march + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<long long>(doe) - 719468;
}

unsigned days_in_month(long long y, unsigned m) {
  static constexpr unsigned kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  const bool leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
  return m == 2 && leap ? 29 : kDays[m - 1];
}

/// Reads `n` digits at `at` (advancing it); -1 when they are not all digits.
int digits(const std::string& s, std::size_t& at, std::size_t n) {
  if (at + n > s.size()) return -1;
  int v = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const char c = s[at + k];
    if (!std::isdigit(static_cast<unsigned char>(c))) return -1;
    v = v * 10 + (c - '0');
  }
  at += n;
  return v;
}

bool expect(const std::string& s, std::size_t& at, char c) {
  if (at >= s.size() || s[at] != c) return false;
  ++at;
  return true;
}

/// The time of day after 'T' (seconds), and the zone; nullopt when malformed.
std::optional<double> time_of_day(const std::string& s, std::size_t at) {
  const int hh = digits(s, at, 2);
  if (hh < 0 || hh > 23 || !expect(s, at, ':')) return std::nullopt;
  const int mm = digits(s, at, 2);
  if (mm < 0 || mm > 59) return std::nullopt;
  double seconds = hh * 3600.0 + mm * 60.0;
  if (at < s.size() && s[at] == ':') {
    ++at;
    const int ss = digits(s, at, 2);
    if (ss < 0 || ss > 60) return std::nullopt;
    seconds += ss;
    if (at < s.size() && s[at] == '.') {
      double scale = 0.1;
      std::size_t start = ++at;
      for (; at < s.size() && std::isdigit(static_cast<unsigned char>(s[at])); ++at, scale /= 10) seconds += (s[at] - '0') * scale;
      if (at == start) return std::nullopt;
    }
  }
  if (at == s.size()) return seconds;  // no zone: UTC, as started_at is written
  if (s[at] == 'Z' || s[at] == 'z') return at + 1 == s.size() ? std::optional<double>(seconds) : std::nullopt;
  if (s[at] != '+' && s[at] != '-') return std::nullopt;
  const double sign = s[at++] == '+' ? 1.0 : -1.0;
  const int oh = digits(s, at, 2);
  if (oh < 0 || oh > 23 || !expect(s, at, ':')) return std::nullopt;
  const int om = digits(s, at, 2);
  if (om < 0 || om > 59 || at != s.size()) return std::nullopt;
  return seconds - sign * (oh * 3600.0 + om * 60.0);
}

}  // namespace

std::optional<double> parse_iso8601(const std::string& s, bool* date_only) {
  std::size_t at = 0;
  const int y = digits(s, at, 4);
  if (y < 0 || !expect(s, at, '-')) return std::nullopt;
  const int m = digits(s, at, 2);
  if (m < 1 || m > 12 || !expect(s, at, '-')) return std::nullopt;
  const int d = digits(s, at, 2);
  if (d < 1 || static_cast<unsigned>(d) > days_in_month(y, static_cast<unsigned>(m))) return std::nullopt;
  const double midnight = static_cast<double>(days_from_civil(y, static_cast<unsigned>(m), static_cast<unsigned>(d))) * kDay;
  if (date_only) *date_only = at == s.size();
  if (at == s.size()) return midnight;
  if (s[at] != 'T' && s[at] != 't' && s[at] != ' ') return std::nullopt;
  const auto t = time_of_day(s, at + 1);
  if (!t) return std::nullopt;
  return midnight + *t;
}

void SessionFilter::validate() const {
  auto check = [](const std::string& option, const std::string& value) {
    if (!value.empty() && !parse_iso8601(value))
      throw FilterError(fmt::format("{}: \"{}\" is not a date: give YYYY-MM-DD or a time such as "
                                    "2026-11-01T08:00:00Z",
                                    option, value));
  };
  check("--since", since);
  check("--until", until);
  if (!since.empty() && !until.empty() && *parse_iso8601(since) > *parse_iso8601(until))
    throw FilterError(fmt::format("--since: {} is after --until {}: no session could match", since, until));
}

bool SessionFilter::matches(const SessionHeader& h) const {
  if (!trainee.empty() && h.trainee != trainee) return false;
  if (!case_key.empty()) {
    constexpr std::string_view kPrefix = "urn:palpa:case:";
    const bool by_id = h.case_id == case_key ||
                       (h.case_id.rfind(kPrefix, 0) == 0 && h.case_id.substr(kPrefix.size()) == case_key);
    const bool by_file = !h.case_file.empty() &&
                         (h.case_file == case_key || std::filesystem::path(h.case_file).stem().string() == case_key);
    if (!by_id && !by_file) return false;
  }
  if (since.empty() && until.empty()) return true;
  const auto started = parse_iso8601(h.started_at);
  if (!started) return false;
  if (!since.empty() && *started < *parse_iso8601(since)) return false;
  if (!until.empty()) {
    bool date_only = false;
    const double end = *parse_iso8601(until, &date_only);
    if (date_only ? *started >= end + kDay : *started > end) return false;  // a date covers its whole day
  }
  return true;
}

std::string SessionFilter::describe() const {
  if (empty()) return {};
  std::string dates;
  if (!since.empty() && !until.empty()) {
    dates = fmt::format("from {} to {}", since, until);
  } else if (!since.empty()) {
    dates = fmt::format("from {} on", since);
  } else if (!until.empty()) {
    dates = fmt::format("up to {}", until);
  }
  std::vector<std::string> of;
  if (!case_key.empty()) of.push_back("case " + case_key);
  if (!trainee.empty()) of.push_back("trainee " + trainee);
  std::string text = "sessions";
  if (!dates.empty()) text += " " + dates;
  for (std::size_t k = 0; k < of.size(); ++k) text += (k == 0 && dates.empty() ? " of " : ", ") + of[k];
  return text;
}

}  // namespace palpa::report
