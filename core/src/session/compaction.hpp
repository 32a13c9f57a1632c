#pragma once
// Turning a format-1 session (one row per tick) into format 2 (sample_blocks), in place, in
// one transaction: a crash at any moment leaves the file readable as one or the other.
// Used by SessionWriter::finish() and by the upgrade of old files. Internal to core/session.
#include <sqlite3.h>

#include <string>

namespace palpa::session::detail {

/// In one transaction of `db` (a format-1 session open read-write, no transaction open):
/// the samples into sample_blocks, the samples table dropped, meta format_version and
/// user_version 2. Then VACUUM, so that the file shrinks (in WAL mode the checkpoint that
/// follows truncates it). Throws std::runtime_error with the reason (a value that does not
/// fit its unit, a write error); the transaction is rolled back then and the file is as it
/// was. A VACUUM that fails (another program reading) leaves a correct, larger file and
/// returns its reason; empty on success.
std::string compact_samples(sqlite3* db);

}  // namespace palpa::session::detail
