#pragma once
// Where a station sends its xAPI statements: the LRS endpoint and the actor's account
// homePage. From, in this order: the command line (--lrs), the environment (PALPA_LRS,
// PALPA_XAPI_HOME_PAGE), the config file $XDG_CONFIG_HOME/palpa/lrs.json (else
// ~/.config/palpa/lrs.json): {"endpoint": "https://lrs.example/xapi", "home_page":
// "https://sim.example-hospital.org", "outbox": "/var/lib/palpa/xapi-outbox"}.
#include <filesystem>
#include <optional>
#include <string>

namespace palpa::lrs {

/// The homePage Palpa uses when none is configured: statements still validate, and an LRS
/// can tell Palpa's trainee ids from other systems' accounts.
inline constexpr const char* kDefaultHomePage = "urn:palpa";

struct LrsConfig {
  std::string endpoint;                 ///< empty: no LRS configured
  std::string home_page = kDefaultHomePage;
  std::filesystem::path outbox;         ///< the outbox folder (default_outbox_folder())
  std::filesystem::path source;         ///< the config file read, if any (for messages)
};

/// The config file's path (it need not exist).
std::filesystem::path default_config_file();

/// Reads the configuration; `endpoint` (from --lrs) wins when not empty. Throws
/// std::runtime_error "FILE: FIELD: problem" for a config file that exists but is malformed.
LrsConfig load_lrs_config(const std::string& endpoint = {}, const std::filesystem::path& file = default_config_file());

}  // namespace palpa::lrs
