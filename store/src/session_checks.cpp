#include "palpa/store/session_checks.hpp"

#include <algorithm>
#include <array>

#include <fmt/format.h>

#include "palpa/report/printable.hpp"
#include "palpa/report/session_filter.hpp"
#include "palpa/session/session_id.hpp"

namespace palpa::store {
namespace {

std::size_t code_points(std::string_view s) {
  return static_cast<std::size_t>(std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

// Each of the server's date checks: finite, from 2000 on, not after tomorrow.
std::string date_problem(const std::string& started_at) {
  const auto t = report::parse_iso8601(started_at);
  if (!t) return "field started_at: not an ISO 8601 date";
  constexpr double k2000 = 946684800.0;
  const double tomorrow = static_cast<double>(std::time(nullptr)) + 86400.0;
  if (*t < k2000 || *t > tomorrow) return "field started_at: not a date between 2000-01-01 and tomorrow";
  return {};
}

}  // namespace

bool is_known_mode(std::string_view mode) {
  static constexpr std::array<std::string_view, 7> kModes{"trainee", "instructor-try", "scripted", "replay",
                                                          "simulated", "bench", "unknown"};
  return std::find(kModes.begin(), kModes.end(), mode) != kModes.end();
}

std::string text_problem(std::string_view field, std::string_view value, std::size_t max_chars) {
  if (value.empty()) return fmt::format("field {}: empty", field);
  if (!report::is_printable(value)) {
    return fmt::format("field {}: holds a NUL, control or bidirectional-override character, or invalid UTF-8", field);
  }
  if (code_points(value) > max_chars) return fmt::format("field {}: longer than {} characters", field, max_chars);
  return {};
}

namespace {

// The first field the store would refuse, or "".
std::string first_problem(const PreparedSession& s) {
  if (!session::is_session_id(s.session_id)) return "field id: not a session id (32 lowercase hex digits)";
  if (auto p = text_problem("trainee", s.trainee, kMaxTraineeChars); !p.empty()) return p;
  if (auto p = text_problem("file name", s.file_name, kMaxFileNameChars); !p.empty()) return p;
  if (s.file_name.find('/') != std::string::npos) return "field file name: holds a /";
  if (!s.case_title.empty()) {
    if (auto p = text_problem("case title", s.case_title, kMaxCaseTitleChars); !p.empty()) return p;
  }
  if (!is_known_mode(s.mode)) {
    return "field mode: not one of trainee, instructor-try, scripted, replay, simulated, bench, unknown";
  }
  if (auto p = date_problem(s.started_at); !p.empty()) return p;
  if (s.samples > 72000000) return "field samples: more than 72000000";
  return {};
}

}  // namespace

void check_pushable(const PreparedSession& s) {
  const auto problem = first_problem(s);
  if (problem.empty()) return;
  throw StoreError(fmt::format("{}: {}; not pushed", report::printable(s.path.string(), 200), problem), false);
}

// Station names are administrative: plain ASCII, so that no two look alike.
void check_station_name(const std::string& station) {
  auto problem = text_problem("station", station, kMaxStationChars);
  const auto alnum = [](char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9'); };
  const auto plain = [&alnum](char c) { return alnum(c) || c == ' ' || c == '.' || c == '_' || c == '-'; };
  const bool plain_name =
      !station.empty() && alnum(station.front()) && std::all_of(station.begin(), station.end(), plain);
  if (problem.empty() && !plain_name) {
    problem = "field station: only letters A-Z, digits, space, dot, underscore and dash, from a letter or digit";
  }
  if (!problem.empty()) {
    throw StoreError(fmt::format("station name: {}", problem.substr(std::string_view("field station: ").size())),
                     false);
  }
}

}  // namespace palpa::store
