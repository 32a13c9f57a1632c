#include "palpa/store/schema.hpp"

#include <fmt/format.h>

#include "migrations.hpp"

namespace palpa::store {
namespace {

// Serializes concurrent inits of one database (key: the bytes "PALL" as an integer).
constexpr const char* kLock = "SELECT pg_advisory_xact_lock(1346457676)";

int current_version(Connection& c) {
  const auto exists = c.exec("read the schema version", "SELECT to_regclass('palpa_schema') IS NOT NULL");
  if (exists.text(0, 0) != "t") return 0;
  return static_cast<int>(
      c.exec("read the schema version", "SELECT coalesce(max(version), 0) FROM palpa_schema").integer(0, 0));
}

std::string newer_message(const Connection& c, int found) {
  return fmt::format("store: {} holds schema version {}, newer than this Palpa knows ({}): upgrade Palpa",
                     c.target(), found, known_schema_version());
}

// The store's text rules (lengths in characters, the characters refused) hold only in UTF-8.
void check_encoding(Connection& c) {
  const auto encoding = c.exec("read the encoding", "SELECT current_setting('server_encoding')").text(0, 0);
  if (encoding != "UTF8") {
    throw StoreError(fmt::format("store: {} is encoded in {}; the store needs UTF8: create the database with "
                                 "createdb -E UTF8 -T template0",
                                 c.target(), encoding),
                     false);
  }
}

}  // namespace

int known_schema_version() { return static_cast<int>(migrations().size()); }

InitResult init_schema(Connection& c, int target) {
  if (target <= 0 || target > known_schema_version()) target = known_schema_version();
  check_encoding(c);
  // A lock held elsewhere (a station can hold one on palpa_schema by reading it in an open
  // transaction) makes init fail with a message instead of waiting for ever.
  c.exec("limit lock waits", "SET lock_timeout = '60s'");
  InitResult result;
  {
    Transaction t(c);
    c.exec("lock the schema", kLock);
    c.exec_script("create palpa_schema",
                  "CREATE TABLE IF NOT EXISTS palpa_schema (version integer PRIMARY KEY, "
                  "applied_at timestamptz NOT NULL DEFAULT now())");
    result.from = current_version(c);
    t.commit();
  }
  if (result.from > known_schema_version()) throw NewerSchemaError(newer_message(c, result.from));
  const auto& steps = migrations();
  for (int v = result.from + 1; v <= target; ++v) {
    Transaction t(c);
    c.exec("lock the schema", kLock);
    if (current_version(c) >= v) continue;  // another init applied it meanwhile
    c.exec_script(fmt::format("migration {}", v), steps[static_cast<std::size_t>(v - 1)]);
    c.exec("record the migration", "INSERT INTO palpa_schema(version) VALUES ($1::integer)",
           {Param::text(std::to_string(v))});
    t.commit();
  }
  result.to = current_version(c);
  return result;
}

void check_schema(Connection& c) {
  const int found = current_version(c);
  if (found > known_schema_version()) throw NewerSchemaError(newer_message(c, found));
  if (found < known_schema_version()) {
    throw StoreError(fmt::format("store: {} holds schema version {}, this Palpa needs {}: run palpa-cli store init",
                                 c.target(), found, known_schema_version()),
                     false);
  }
}

}  // namespace palpa::store
