#pragma once
// Small RAII helpers around the SQLite C API shared by the session writer and reader, and
// the schema both of them agree on (docs/session-format.md). Internal to core/session.
#include <sqlite3.h>

#include <cstdint>
#include <string>
#include <string_view>

namespace palpa::session::detail {

/// PRAGMA application_id of every session file: the bytes 'PALP'.
inline constexpr std::int32_t kApplicationId = 0x50414C50;

/// The tables every format version has.
inline constexpr const char* kMetaAndEventsTables = R"sql(
CREATE TABLE meta(
  key TEXT PRIMARY KEY,
  value TEXT NOT NULL
);
CREATE TABLE events(
  id INTEGER PRIMARY KEY,
  t REAL NOT NULL,
  kind TEXT NOT NULL CHECK(kind IN ('start','mark','unmark','pause','resume','end')),
  mark INTEGER,
  x REAL, y REAL, z REAL,
  note TEXT NOT NULL DEFAULT ''
);
)sql";

/// Format 1 (and a session being recorded): one row per tick.
inline constexpr const char* kSamplesTable = R"sql(
CREATE TABLE samples(
  tick INTEGER PRIMARY KEY,
  t REAL NOT NULL,
  x REAL NOT NULL, y REAL NOT NULL, z REAL NOT NULL,
  fx REAL NOT NULL, fy REAL NOT NULL, fz REAL NOT NULL,
  body INTEGER,
  u REAL, v REAL, depth REAL,
  buttons INTEGER NOT NULL,
  overrun INTEGER NOT NULL,
  fault INTEGER NOT NULL
);
)sql";

/// Format 2: the ticks compacted into blocks (sample_blocks.hpp).
inline constexpr const char* kSampleBlocksTable = R"sql(
CREATE TABLE sample_blocks(
  first_tick INTEGER PRIMARY KEY,
  count INTEGER NOT NULL,
  data BLOB NOT NULL
);
)sql";

/// The tables of format `version` (1 or 2), as created by the writer and checked by the reader.
std::string schema_of(int version);

/// A prepared statement, finalized on destruction.
class Statement {
 public:
  Statement() = default;
  Statement(sqlite3* db, std::string_view sql);  ///< throws std::runtime_error(errmsg)
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  Statement(Statement&& other) noexcept : stmt_(other.stmt_) { other.stmt_ = nullptr; }
  Statement& operator=(Statement&& other) noexcept;
  sqlite3_stmt* get() const { return stmt_; }
  /// Hands the statement over to the caller, who finalizes it.
  sqlite3_stmt* release() {
    auto* stmt = stmt_;
    stmt_ = nullptr;
    return stmt;
  }

 private:
  sqlite3_stmt* stmt_ = nullptr;
};

/// Runs SQL without results; returns SQLITE_OK or the error code, with the message in
/// `error` (sqlite3_errmsg at the time of the failure).
int exec(sqlite3* db, const char* sql, std::string& error);

/// The first column of the first row of a one-value query (a PRAGMA), as text; throws
/// std::runtime_error(errmsg) on failure or when there is no row.
std::string query_text(sqlite3* db, const char* sql);

/// The schema of `db` as one line per object and per column: every object of
/// sqlite_schema (type, name, table; sorted) and every column of each table as
/// PRAGMA table_xinfo gives it (name, declared type, not null, default, primary key and
/// hidden: a generated column is hidden 2 or 3). Reads nothing but the schema. Throws
/// std::runtime_error(errmsg).
std::string schema_fingerprint(sqlite3* db);

/// schema_fingerprint of schema_of(version) itself (built once in memory): what a session of
/// that format version must have.
const std::string& expected_schema_fingerprint(int version);

/// Doubles as text that reads back to the same bits (shortest round-trip form).
std::string exact_text(double value);

}  // namespace palpa::session::detail
