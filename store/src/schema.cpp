#include "palpa/store/schema.hpp"

#include <fmt/format.h>

#include "migrations.hpp"

namespace palpa::store {
namespace {

// Serializes concurrent inits of one database. Advisory locks are anyone's to take (a
// station could hold this key for ever), so the lock is palpa_schema's own, in a mode that
// conflicts with itself and not with the ACCESS SHARE that reading the table takes: only
// its owner can hold it. The advisory key ("PALL" as an integer) is taken only while no
// palpa_schema exists, before any station login can do anything in this database.
constexpr const char* kFirstLock = "SELECT pg_advisory_xact_lock(1346457676)";
constexpr const char* kLock = "LOCK TABLE palpa_schema IN SHARE ROW EXCLUSIVE MODE";

bool schema_table_exists(Connection& c) {
  return c.exec("read the schema version", "SELECT to_regclass('palpa_schema') IS NOT NULL").text(0, 0) == "t";
}

int current_version(Connection& c) {
  if (!schema_table_exists(c)) return 0;
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
    if (!schema_table_exists(c)) {
      c.exec("lock the schema", kFirstLock);
      c.exec_script("create palpa_schema",
                    "CREATE TABLE IF NOT EXISTS palpa_schema (version integer PRIMARY KEY, "
                    "applied_at timestamptz NOT NULL DEFAULT now())");
    }
    c.exec("lock the schema", kLock);
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
  result.large_objects_open =
      c.exec("check large objects",
             "SELECT bool_or(a.grantee = 0 AND a.privilege_type = 'EXECUTE') FROM pg_proc p, "
             "aclexplode(coalesce(p.proacl, acldefault('f', p.proowner))) a "
             "WHERE p.oid IN ('pg_catalog.lo_create(oid)'::regprocedure, 'pg_catalog.lo_creat(integer)'::regprocedure, "
             "'pg_catalog.lo_from_bytea(oid, bytea)'::regprocedure)")
          .text(0, 0) == "t";
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
