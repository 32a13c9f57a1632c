#include "sqlite_util.hpp"

#include <array>
#include <charconv>
#include <stdexcept>
#include <vector>

namespace palpa::session::detail {

Statement::Statement(sqlite3* db, std::string_view sql) {
  if (sqlite3_prepare_v3(db, sql.data(), static_cast<int>(sql.size()), SQLITE_PREPARE_PERSISTENT, &stmt_, nullptr) !=
      SQLITE_OK) {
    sqlite3_finalize(stmt_);
    stmt_ = nullptr;
    throw std::runtime_error(sqlite3_errmsg(db));
  }
  if (stmt_ == nullptr) throw std::runtime_error("empty statement");
}

namespace {

std::string column_text(sqlite3_stmt* stmt, int column) {
  const auto* text = sqlite3_column_text(stmt, column);
  if (text == nullptr) return "NULL";
  return std::string(reinterpret_cast<const char*>(text), static_cast<std::size_t>(sqlite3_column_bytes(stmt, column)));
}

}  // namespace

std::string schema_fingerprint(sqlite3* db) {
  std::string out;
  std::vector<std::string> tables;
  Statement objects(db, "SELECT type, name, tbl_name FROM sqlite_schema ORDER BY type, name");
  int rc = SQLITE_ROW;
  while ((rc = sqlite3_step(objects.get())) == SQLITE_ROW) {
    const std::string type = column_text(objects.get(), 0);
    const std::string name = column_text(objects.get(), 1);
    out += type + ' ' + name + " on " + column_text(objects.get(), 2) + '\n';
    if (type == "table") tables.push_back(name);
  }
  if (rc != SQLITE_DONE) throw std::runtime_error(sqlite3_errmsg(db));
  Statement columns(db, "SELECT name, type, \"notnull\", dflt_value, pk, hidden FROM pragma_table_xinfo(?)");
  for (const auto& table : tables) {
    sqlite3_bind_text(columns.get(), 1, table.c_str(), -1, SQLITE_TRANSIENT);
    while ((rc = sqlite3_step(columns.get())) == SQLITE_ROW) {
      out += "column " + table + '.' + column_text(columns.get(), 0) + ' ' + column_text(columns.get(), 1) +
             " notnull " + column_text(columns.get(), 2) + " default " + column_text(columns.get(), 3) + " pk " +
             column_text(columns.get(), 4) + " hidden " + column_text(columns.get(), 5) + '\n';
    }
    if (rc != SQLITE_DONE) throw std::runtime_error(sqlite3_errmsg(db));
    sqlite3_reset(columns.get());
  }
  return out;
}

std::string schema_of(int version) {
  return std::string(kMetaAndEventsTables) + (version >= 2 ? kSampleBlocksTable : kSamplesTable);
}

namespace {

std::string fingerprint_of_schema(int version) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(":memory:", &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_MEMORY, nullptr) != SQLITE_OK) {
    sqlite3_close_v2(db);
    throw std::runtime_error("cannot open an in-memory database");
  }
  std::string error;
  std::string fingerprint;
  if (exec(db, schema_of(version).c_str(), error) == SQLITE_OK) fingerprint = schema_fingerprint(db);
  sqlite3_close_v2(db);
  if (fingerprint.empty()) throw std::runtime_error("the session schema does not build: " + error);
  return fingerprint;
}

}  // namespace

const std::string& expected_schema_fingerprint(int version) {
  static const std::string v1 = fingerprint_of_schema(1);
  static const std::string v2 = fingerprint_of_schema(2);
  return version >= 2 ? v2 : v1;
}

Statement& Statement::operator=(Statement&& other) noexcept {
  if (this != &other) {
    sqlite3_finalize(stmt_);
    stmt_ = other.stmt_;
    other.stmt_ = nullptr;
  }
  return *this;
}

int exec(sqlite3* db, const char* sql, std::string& error) {
  char* message = nullptr;
  const int rc = sqlite3_exec(db, sql, nullptr, nullptr, &message);
  if (rc != SQLITE_OK) error = message != nullptr ? message : sqlite3_errstr(rc);
  sqlite3_free(message);
  return rc;
}

std::string query_text(sqlite3* db, const char* sql) {
  Statement statement(db, sql);
  const int rc = sqlite3_step(statement.get());
  if (rc != SQLITE_ROW) {
    throw std::runtime_error(rc == SQLITE_DONE ? std::string("no result") : std::string(sqlite3_errmsg(db)));
  }
  const auto* text = sqlite3_column_text(statement.get(), 0);
  return text == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(text));
}

std::string exact_text(double value) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

}  // namespace palpa::session::detail
