#pragma once
// The centre store's schema (docs/centre.md): versioned migrations, each applied in its
// own transaction and recorded in palpa_schema(version, applied_at).
#include <string>

#include "palpa/store/pg.hpp"

namespace palpa::store {

/// The database holds a schema newer than this Palpa knows: Palpa must be upgraded. A push
/// queues its sessions then; they go out once this station runs the newer Palpa.
class NewerSchemaError : public StoreError {
 public:
  explicit NewerSchemaError(const std::string& message) : StoreError(message, false) {}
};

/// The schema version this Palpa writes and reads (the number of migrations it knows).
int known_schema_version();

struct InitResult {
  int from = 0;  ///< the version found (0: an empty database)
  int to = 0;    ///< the version now
  /// Any login may still create large objects here (they live outside every table and
  /// quota): only a superuser can take that away, which init run by a non-superuser
  /// administrator cannot do (docs/centre.md, section 1).
  bool large_objects_open = false;
};

/// Creates or migrates the schema, the tables, the roles palpa_station, palpa_worker and
/// palpa_coordinator and their grants. Idempotent. Throws StoreError when the database's
/// version is newer than known_schema_version(), or a migration fails (it is rolled back).
/// `target` stops at an older version (tests of the migrations); 0: the newest.
InitResult init_schema(Connection& c, int target = 0);

/// Throws StoreError unless the database holds exactly the version this Palpa knows
/// (older: "run palpa-cli store init"; newer: "upgrade Palpa").
void check_schema(Connection& c);

}  // namespace palpa::store
