#include "sqlite_util.hpp"

#include <array>
#include <charconv>
#include <stdexcept>

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
