#include "palpa/ui/session_paths.hpp"

#include <cstdlib>
#include <ctime>

#include <fmt/format.h>

namespace palpa::ui {

std::filesystem::path sessions_dir() {
  const char* data = std::getenv("XDG_DATA_HOME");
  const char* home = std::getenv("HOME");
  const std::filesystem::path base = data && *data ? std::filesystem::path(data)
                                     : home && *home ? std::filesystem::path(home) / ".local" / "share"
                                                     : std::filesystem::temp_directory_path();
  return base / "palpa" / "sessions";
}

std::filesystem::path try_it_sessions_dir() { return sessions_dir() / "try-it"; }

std::string utc_stamp() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y%m%dT%H%M%SZ", &utc);
  return text;
}

std::filesystem::path new_session_path(const std::filesystem::path& dir, const std::string& prefix) {
  const std::string stem = prefix + "-" + utc_stamp();
  auto path = dir / (stem + ".palpa");
  for (int k = 2; std::filesystem::exists(path); ++k) path = dir / fmt::format("{}-{}.palpa", stem, k);
  return path;
}

}  // namespace palpa::ui
