#include "palpa/scripted/exercise.hpp"

#include <chrono>
#include <random>

#include <fmt/format.h>

#include "palpa/session/session_id.hpp"
#include "palpa/version.hpp"

namespace palpa::scripted {

std::string iso8601_utc(std::int64_t unix_seconds) {
  // Civil date from days since 1970-01-01 (H. Hinnant's days_from_civil, inverted):
  // no gmtime, whose buffer is shared between threads.
  std::int64_t days = unix_seconds / 86400;
  std::int64_t rem = unix_seconds % 86400;
  if (rem < 0) {
    rem += 86400;
    --days;
  }
  const std::int64_t z = days + 719468;
  const std::int64_t era = (z >= 0 ? z : z - 146096) / 146097;
  const std::int64_t doe = z - era * 146097;
  const std::int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const std::int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const std::int64_t mp = (5 * doy + 2) / 153;
  const std::int64_t day = doy - (153 * mp + 2) / 5 + 1;
  const std::int64_t month = mp < 10 ? mp + 3 : mp - 9;
  const std::int64_t year = yoe + era * 400 + (month <= 2 ? 1 : 0);
  return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}Z", year, month, day, rem / 3600, rem % 3600 / 60, rem % 60);
}

std::string iso8601_utc_now() {
  const auto now = std::chrono::system_clock::now();
  return iso8601_utc(std::chrono::duration_cast<std::chrono::seconds>(now.time_since_epoch()).count());
}

session::SessionInfo exercise_session_info(const io::CaseFile& placed, const std::string& case_source,
                                           std::optional<std::uint64_t> seed, Style style,
                                           const std::string& trainee, const std::string& device_name,
                                           const std::string& started_at, double rate_hz) {
  session::SessionInfo info;
  info.id = session::new_session_id();
  info.trainee = trainee;
  info.device = device_name;
  info.software_version = palpa::kVersion;
  info.started_at = started_at;
  info.rate_hz = rate_hz;
  info.case_source = case_source;
  info.case_document = io::to_json(placed);
  info.seed = seed;
  info.extra = nlohmann::json::object();
  info.extra["exercise_style"] = std::string(to_string(style));
  info.extra["mode"] = "scripted";
  return info;
}

}  // namespace palpa::scripted
