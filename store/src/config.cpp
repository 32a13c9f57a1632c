#include "palpa/store/config.hpp"

#include <unistd.h>

#include <cstdlib>
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "palpa/store/pg.hpp"

namespace palpa::store {
namespace {

namespace fs = std::filesystem;

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::string(v) : std::string();
}

fs::path home() { return fs::path(env("HOME")); }

// The config file's settings; an empty object when there is no file.
nlohmann::json read_config(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return nlohmann::json::object();
  std::ifstream in(path);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw StoreError(fmt::format("{}: not valid JSON: {}", path.string(), e.what()), false);
  }
  if (!j.is_object()) throw StoreError(fmt::format("{}: must hold a JSON object", path.string()), false);
  for (const auto& [key, value] : j.items()) {
    if (key != "store" && key != "station" && key != "outbox") {
      throw StoreError(fmt::format("{}: {}: unknown setting (store, station, outbox)", path.string(), key), false);
    }
    if (!value.is_string()) throw StoreError(fmt::format("{}: {}: must be a string", path.string(), key), false);
  }
  return j;
}

std::string host_name() {
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) != 0 || name[0] == '\0') return "station";
  return name;
}

fs::path default_outbox() {
  if (const auto data = env("XDG_DATA_HOME"); !data.empty()) return fs::path(data) / "palpa" / "outbox";
  return home() / ".local" / "share" / "palpa" / "outbox";
}

}  // namespace

fs::path config_path() {
  if (const auto config = env("XDG_CONFIG_HOME"); !config.empty()) return fs::path(config) / "palpa" / "store.json";
  return home() / ".config" / "palpa" / "store.json";
}

StoreSettings resolve_settings(const std::string& store, const std::string& station, const std::string& outbox) {
  const auto file = read_config(config_path());
  auto pick = [&file](const std::string& option, const char* variable, const char* key) {
    if (!option.empty()) return option;
    if (auto v = env(variable); !v.empty()) return v;
    return file.value(key, std::string());
  };
  StoreSettings s;
  s.conninfo = pick(store, "PALPA_STORE", "store");
  s.station = pick(station, "PALPA_STATION", "station");
  if (s.station.empty()) s.station = host_name();
  const auto box = pick(outbox, "PALPA_OUTBOX", "outbox");
  s.outbox = box.empty() ? default_outbox() : fs::path(box);
  return s;
}

}  // namespace palpa::store
