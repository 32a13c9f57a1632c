#include "palpa/lrs/lrs_config.hpp"

#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "palpa/lrs/statement_outbox.hpp"

namespace palpa::lrs {
namespace fs = std::filesystem;
namespace {

std::string env(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

// A string field of the config file, or `fallback` when the file does not have it.
std::string text_field(const nlohmann::json& json, const fs::path& file, const char* field, std::string fallback) {
  if (!json.contains(field)) return fallback;
  if (!json[field].is_string() || json[field].get<std::string>().empty())
    throw std::runtime_error(fmt::format("{}: {}: must be a non-empty text", file.string(), field));
  return json[field].get<std::string>();
}

void read_config_file(const fs::path& file, LrsConfig& config) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot read", file.string()));
  const auto json = nlohmann::json::parse(in, nullptr, false);
  if (!json.is_object()) throw std::runtime_error(fmt::format("{}: not a JSON object", file.string()));
  for (const auto& [key, value] : json.items()) {
    if (key != "endpoint" && key != "home_page" && key != "outbox")
      throw std::runtime_error(fmt::format("{}: {}: unknown field (endpoint, home_page, outbox)", file.string(), key));
  }
  config.endpoint = text_field(json, file, "endpoint", config.endpoint);
  config.home_page = text_field(json, file, "home_page", config.home_page);
  config.outbox = text_field(json, file, "outbox", config.outbox.string());
  config.source = file;
}

}  // namespace

fs::path default_config_file() {
  if (const std::string xdg = env("XDG_CONFIG_HOME"); !xdg.empty()) return fs::path(xdg) / "palpa" / "lrs.json";
  const std::string home = env("HOME");
  return fs::path(home.empty() ? "." : home) / ".config" / "palpa" / "lrs.json";
}

LrsConfig load_lrs_config(const std::string& endpoint, const fs::path& file) {
  LrsConfig config;
  config.outbox = default_outbox_folder();
  std::error_code error;
  if (!file.empty() && fs::exists(file, error)) read_config_file(file, config);
  if (const std::string e = env("PALPA_LRS"); !e.empty()) config.endpoint = e;
  if (const std::string h = env("PALPA_XAPI_HOME_PAGE"); !h.empty()) config.home_page = h;
  if (!endpoint.empty()) config.endpoint = endpoint;
  return config;
}

}  // namespace palpa::lrs
