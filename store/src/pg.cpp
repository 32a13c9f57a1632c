#include "palpa/store/pg.hpp"

#include <cstdlib>

#include <fmt/format.h>

namespace palpa::store {

std::string one_line(std::string message) {
  std::string out;
  for (char ch : message) {
    if (ch == '\n' || ch == '\t' || ch == '\r') ch = ' ';
    if (ch == ' ' && (out.empty() || out.back() == ' ')) continue;
    out += ch;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

std::string target_of(const PGconn* conn) {
  auto field = [](const char* v) { return std::string(v && *v ? v : "?"); };
  auto* c = const_cast<PGconn*>(conn);
  std::string host = field(PQhost(c));
  if (!host.empty() && host.front() == '/') host = "[socket " + host + "]";
  return fmt::format("{}:{}/{} as {}", host, field(PQport(c)), field(PQdb(c)), field(PQuser(c)));
}

std::string Result::text(int row, int col) const {
  if (is_null(row, col)) return {};
  return std::string(PQgetvalue(r_.get(), row, col), static_cast<std::size_t>(PQgetlength(r_.get(), row, col)));
}

std::string Result::bytes(int row, int col) const { return text(row, col); }

long long Result::integer(int row, int col) const { return std::strtoll(text(row, col).c_str(), nullptr, 10); }

// A connection string libpq cannot parse is the user's mistake, not a server that is down:
// refused before connecting, so nothing is queued for a store that can never be reached.
void check_conninfo(const std::string& conninfo) {
  char* error = nullptr;
  PQconninfoOption* options = PQconninfoParse(conninfo.c_str(), &error);
  if (options) {
    PQconninfoFree(options);
    return;
  }
  const std::string why = error ? one_line(error) : "out of memory";
  PQfreemem(error);
  throw StoreError(fmt::format("store: bad connection string: {}", why), false);
}

namespace {

// A connection that failed for a reason retrying cannot fix (a bad option value, a service
// that is not defined): the user's mistake, refused without queuing. Everything else
// (refused, timed out, no route, a server starting up, authentication) may pass later.
bool is_configuration_mistake(const std::string& message) {
  static constexpr const char* kMistakes[] = {"invalid sslmode value", "invalid integer value", "invalid port number",
                                              "definition of service", "service file", "invalid value for parameter",
                                              "invalid connection option", "invalid gssencmode value",
                                              "invalid target_session_attrs value", "invalid channel_binding value",
                                              "invalid require_auth", "invalid load_balance_hosts value",
                                              "invalid ssl_min_protocol_version", "invalid ssl_max_protocol_version"};
  for (const char* m : kMistakes) {
    if (message.find(m) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

Connection::Connection(const std::string& conninfo)
    : c_((check_conninfo(conninfo), PQconnectdb(conninfo.c_str())), &PQfinish) {
  if (!c_) throw StoreError("store: cannot connect: out of memory", true);
  if (PQstatus(c_.get()) != CONNECTION_OK) {
    const std::string why = one_line(PQerrorMessage(c_.get()));
    if (is_configuration_mistake(why)) throw StoreError(fmt::format("store: bad connection settings: {}", why), false);
    throw StoreError(fmt::format("store: cannot connect to {}: {}", target_of(c_.get()), why), true);
  }
  // Notices (e.g. "relation already exists, skipping") are not for the user's terminal.
  PQsetNoticeProcessor(c_.get(), [](void*, const char*) {}, nullptr);
}

std::string Connection::target() const { return target_of(c_.get()); }

namespace {

// Errors that pass with time, as a broken connection does: a lock or statement timeout
// (another login held a row), a login's quota, a server short of memory or connections,
// a serialization failure or deadlock. The session waits in the outbox and is sent again.
bool passes_with_time(const PGresult* r) {
  const char* state = r ? PQresultErrorField(r, PG_DIAG_SQLSTATE) : nullptr;
  if (state == nullptr) return false;
  const std::string_view code(state);
  return code == "55P03" || code == "57014" || code == "53400" || code == "53300" || code == "53200" ||
         code == "40001" || code == "40P01" || code == "25P03" || code == "57P01";
}

}  // namespace

void Connection::fail(std::string_view what, const PGresult* r) const {
  const bool broken = PQstatus(c_.get()) != CONNECTION_OK || passes_with_time(r);
  // The server's primary message alone: its CONTEXT lines name functions and statements
  // that are the store's business, not the caller's.
  const char* primary = r ? PQresultErrorField(r, PG_DIAG_MESSAGE_PRIMARY) : nullptr;
  std::string message = primary ? primary : "";
  if (message.empty()) message = PQerrorMessage(c_.get());
  throw StoreError(fmt::format("store: {}: {}", what, one_line(message)), broken);
}

Result Connection::exec(std::string_view what, const char* sql, const std::vector<Param>& params,
                        bool binary_result) {
  std::vector<const char*> values;
  std::vector<int> lengths, formats;
  for (const auto& p : params) {
    values.push_back(p.value ? p.value->data() : nullptr);
    lengths.push_back(p.value ? static_cast<int>(p.value->size()) : 0);
    formats.push_back(p.binary ? 1 : 0);
  }
  Result r(PQexecParams(c_.get(), sql, static_cast<int>(params.size()), nullptr, values.data(), lengths.data(),
                        formats.data(), binary_result ? 1 : 0));
  const auto status = PQresultStatus(r.get());
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) fail(what, r.get());
  return r;
}

void Connection::exec_script(std::string_view what, const char* sql) {
  Result r(PQexec(c_.get(), sql));
  const auto status = PQresultStatus(r.get());
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) fail(what, r.get());
}

Transaction::Transaction(Connection& c) : c_(c) { c_.exec("begin a transaction", "BEGIN"); }

Transaction::~Transaction() {
  if (!done_) PQclear(PQexec(c_.get(), "ROLLBACK"));
}

void Transaction::commit() {
  c_.exec("commit", "COMMIT");
  done_ = true;
}

}  // namespace palpa::store
