#pragma once
// Thin RAII wrappers over libpq: a connection, a result, parameterized statements and a
// transaction. Every value travels as a parameter (PQexecParams), never inside SQL text.
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <libpq-fe.h>

namespace palpa::store {

/// Why a store operation failed. `unreachable` is true when the server could not be
/// reached, the connection broke, or the failure passes with time (a lock or statement
/// timeout, a quota, a server out of memory or connections): a push then queues the
/// session in the outbox. False for a refusal (permissions, a conflict, a bad value).
class StoreError : public std::runtime_error {
 public:
  StoreError(const std::string& message, bool unreachable)
      : std::runtime_error(message), unreachable_(unreachable) {}
  bool unreachable() const { return unreachable_; }

 private:
  bool unreachable_;
};

/// One statement parameter: text (NULL when empty optional) or binary bytes (bytea).
struct Param {
  std::optional<std::string> value;
  bool binary = false;
  static Param text(std::string v) { return {std::move(v), false}; }
  static Param bytes(std::string v) { return {std::move(v), true}; }
  static Param null() { return {std::nullopt, false}; }
};

class Result {
 public:
  explicit Result(PGresult* r) : r_(r, &PQclear) {}
  int rows() const { return PQntuples(r_.get()); }
  bool is_null(int row, int col) const { return PQgetisnull(r_.get(), row, col) == 1; }
  /// The text of a cell ("" for NULL).
  std::string text(int row, int col) const;
  /// The raw bytes of a cell of a binary-format result.
  std::string bytes(int row, int col) const;
  long long integer(int row, int col) const;
  PGresult* get() const { return r_.get(); }

 private:
  std::unique_ptr<PGresult, decltype(&PQclear)> r_;
};

class Connection {
 public:
  /// Connects with `conninfo` passed to libpq as is (key=value, URI, service=, PG* variables,
  /// ~/.pgpass all apply). Throws StoreError (unreachable) with the one line
  /// "store: cannot connect to HOST:PORT/DB as USER: REASON".
  explicit Connection(const std::string& conninfo);
  /// HOST:PORT/DB as USER: the target without the connection string (no password).
  std::string target() const;
  PGconn* get() const { return c_.get(); }
  /// True when the connection itself is gone (not a statement that failed on a live one).
  bool broken() const { return PQstatus(c_.get()) != CONNECTION_OK; }
  /// Runs one statement with its parameters; `binary_result` asks for binary cells (bytea).
  /// Throws StoreError naming the statement's purpose `what` and the server's message.
  Result exec(std::string_view what, const char* sql, const std::vector<Param>& params = {},
              bool binary_result = false);
  /// Runs constant SQL (migrations: several statements, no values). Throws StoreError.
  void exec_script(std::string_view what, const char* sql);

 private:
  [[noreturn]] void fail(std::string_view what, const PGresult* r) const;
  std::unique_ptr<PGconn, decltype(&PQfinish)> c_;
};

/// BEGIN on construction; ROLLBACK on destruction unless commit() was called.
class Transaction {
 public:
  explicit Transaction(Connection& c);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit();

 private:
  Connection& c_;
  bool done_ = false;
};

/// HOST:PORT/DB as USER of a connection (established or failed).
std::string target_of(const PGconn* conn);

/// A libpq message on one line: newlines and tabs folded, trailing space dropped.
std::string one_line(std::string message);

}  // namespace palpa::store
