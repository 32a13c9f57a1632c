#pragma once
// Where a station's store is, its name and its outbox (docs/centre.md, "Station
// configuration"). Each setting is taken from, in order: the command-line option, the
// environment (PALPA_STORE, PALPA_STATION, PALPA_OUTBOX), the config file
// $XDG_CONFIG_HOME/palpa/store.json (~/.config/palpa/store.json), a default.
#include <filesystem>
#include <string>

namespace palpa::store {

struct StoreSettings {
  std::string conninfo;           ///< libpq connection string; empty when none is configured
  std::string station;            ///< default: the host name
  std::filesystem::path outbox;   ///< default: $XDG_DATA_HOME/palpa/outbox (~/.local/share/palpa/outbox)
};

/// The config file's path (whether or not it exists).
std::filesystem::path config_path();

/// Resolves the settings; an empty option means "not given". Throws StoreError (not
/// unreachable) naming the config file and field when the file is not valid.
StoreSettings resolve_settings(const std::string& store, const std::string& station, const std::string& outbox);

}  // namespace palpa::store
