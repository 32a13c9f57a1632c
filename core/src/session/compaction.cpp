#include "compaction.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "sample_blocks.hpp"
#include "sqlite_util.hpp"

namespace palpa::session::detail {
namespace {

void run(sqlite3* db, const char* sql) {
  std::string error;
  if (exec(db, sql, error) != SQLITE_OK) throw std::runtime_error(error);
}

/// Reads the sample rows in tick order and inserts them as blocks of kBlockTicks ticks.
void write_blocks(sqlite3* db) {
  Statement rows(db, "SELECT tick, t, x, y, z, fx, fy, fz, body, u, v, depth, buttons, overrun, fault FROM samples "
                     "ORDER BY tick");
  Statement insert(db, "INSERT INTO sample_blocks(first_tick, count, data) VALUES(?, ?, ?)");
  BlockTicks block;
  const auto flush = [&] {
    if (block.samples.empty()) return;
    const std::string data = encode_block(block);
    sqlite3_bind_int64(insert.get(), 1, block.ticks.front());
    sqlite3_bind_int64(insert.get(), 2, static_cast<sqlite3_int64>(block.samples.size()));
    sqlite3_bind_blob(insert.get(), 3, data.data(), static_cast<int>(data.size()), SQLITE_STATIC);
    const int rc = sqlite3_step(insert.get());
    sqlite3_reset(insert.get());
    if (rc != SQLITE_DONE) throw std::runtime_error(sqlite3_errmsg(db));
    block.ticks.clear();
    block.samples.clear();
  };
  int rc = SQLITE_ROW;
  sqlite3_stmt* st = rows.get();
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
    engine::Sample s;
    s.t = sqlite3_column_double(st, 1);
    for (int a = 0; a < 3; ++a) {
      s.position[static_cast<std::size_t>(a)] = sqlite3_column_double(st, 2 + a);
      s.force[static_cast<std::size_t>(a)] = sqlite3_column_double(st, 5 + a);
    }
    if (sqlite3_column_type(st, 8) != SQLITE_NULL) {
      s.body = sqlite3_column_int(st, 8);
      s.u = sqlite3_column_double(st, 9);
      s.v = sqlite3_column_double(st, 10);
      s.depth = sqlite3_column_double(st, 11);
    }
    s.buttons = static_cast<std::uint32_t>(sqlite3_column_int64(st, 12));
    s.overrun = sqlite3_column_int(st, 13) != 0;
    s.fault = sqlite3_column_int(st, 14) != 0;
    block.ticks.push_back(sqlite3_column_int64(st, 0));
    block.samples.push_back(s);
    if (static_cast<std::int64_t>(block.samples.size()) == kBlockTicks) flush();
  }
  if (rc != SQLITE_DONE) throw std::runtime_error(sqlite3_errmsg(db));
  flush();
}

}  // namespace

std::string compact_samples(sqlite3* db) {
  run(db, "BEGIN IMMEDIATE");
  try {
    run(db, kSampleBlocksTable);
    write_blocks(db);
    run(db, "DROP TABLE samples");
    run(db, "UPDATE meta SET value = '2' WHERE key = 'format_version'");
    run(db, "PRAGMA user_version = 2");
    run(db, "COMMIT");
  } catch (...) {
    std::string ignored;
    exec(db, "ROLLBACK", ignored);
    throw;
  }
  std::string error;
  if (exec(db, "VACUUM", error) != SQLITE_OK) return "VACUUM: " + error;
  return {};
}

}  // namespace palpa::session::detail
