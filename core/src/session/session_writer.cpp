#include "palpa/session/session_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <random>
#include <string_view>

#include "palpa/io/case_file.hpp"
#include "sqlite_util.hpp"

namespace palpa::session {
namespace {

std::string now_utc() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  std::array<char, 32> text{};
  const std::size_t n = std::strftime(text.data(), text.size(), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return std::string(text.data(), n);
}

std::string random_id() {
  std::random_device device;
  std::string id;
  static constexpr char kHex[] = "0123456789abcdef";
  for (int k = 0; k < 4; ++k) {
    auto word = device();
    for (int d = 0; d < 8; ++d, word >>= 4) id += kHex[word & 0xF];
  }
  return id;
}

/// The loop statistics as stored in meta loop_stats (docs/session-format.md).
nlohmann::json loop_stats_json(const engine::LoopStats& stats) {
  const auto times = [](double p50, double p99, double p999, double max, double mean) {
    return nlohmann::json{{"p50", p50}, {"p99", p99}, {"p999", p999}, {"max", max}, {"mean", mean}};
  };
  const double mean_period = stats.mean_period();
  return nlohmann::json{
      {"ticks", stats.ticks()},
      {"missed", stats.missed()},
      {"rate_hz", mean_period > 0.0 ? 1.0 / mean_period : 0.0},
      {"period_s", times(stats.period_percentile(0.5), stats.period_percentile(0.99), stats.period_percentile(0.999),
                         stats.max_period(), mean_period)},
      {"compute_s", times(stats.compute_percentile(0.5), stats.compute_percentile(0.99),
                          stats.compute_percentile(0.999), stats.max_compute(), stats.mean_compute())},
  };
}

// Everything a reader will insist on, checked before the file exists: a writer must not
// produce a session that cannot be read back.
void validate(const std::string& file, const SessionInfo& info) {
  if (info.trainee.empty()) throw SessionError(file, "trainee", "must not be empty");
  if (!std::isfinite(info.rate_hz) || info.rate_hz <= 0.0) {
    throw SessionError(file, "rate_hz", "must be a finite number > 0, not " + detail::exact_text(info.rate_hz));
  }
  if (!info.case_document.is_object()) throw SessionError(file, "case", "the case document must be a JSON object");
  try {
    io::parse_case(info.case_document.dump(), file + ": case");
  } catch (const io::CaseError& e) {
    const auto& p = e.problems();
    throw SessionError(file, "case " + (p.empty() ? std::string("/") : p.front().where),
                       p.empty() ? std::string(e.what()) : p.front().reason);
  }
}

// Creates the file itself (O_EXCL), so that an existing session is refused without a race
// and SQLite starts from an empty file.
void create_exclusive(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::error_code ec;
  for (const char* suffix : {"-wal", "-journal"}) {
    // A stale journal beside a new file would be replayed into it.
    auto side = path;
    side += suffix;
    if (std::filesystem::symlink_status(side, ec).type() != std::filesystem::file_type::not_found && !ec) {
      std::string reason = "a leftover ";
      reason += side.filename().string();
      reason += " lies beside it (from an earlier session of that name); move it away first";
      throw SessionError(file, "file", reason);
    }
  }
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int error = errno;
    if (error == EEXIST) {
      throw SessionError(file, "file", "already exists; recorded sessions are never overwritten, choose a new name");
    }
    if (error == ENOENT) {
      std::string reason = "the folder ";
      reason += path.parent_path().empty() ? std::string(".") : path.parent_path().string();
      reason += " does not exist";
      throw SessionError(file, "file", reason);
    }
    std::string reason = "cannot create: ";
    reason += std::strerror(error);
    throw SessionError(file, "file", reason);
  }
  ::close(fd);
}

}  // namespace

SessionWriter::SessionWriter(const std::filesystem::path& path, const SessionInfo& info) : path_(path) {
  const std::string file = path.string();
  validate(file, info);
  create_exclusive(path);
  const auto fail = [&](const std::string& where, const std::string& reason) {
    close();
    // The file is ours and holds nothing yet: leave no half-made session behind.
    std::error_code ec;
    for (const char* suffix : {"", "-wal", "-shm", "-journal"}) {
      auto p = path;
      p += suffix;
      std::filesystem::remove(p, ec);
    }
    throw SessionError(file, where, reason);
  };
  if (sqlite3_open_v2(file.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_NOMUTEX, nullptr) != SQLITE_OK) {
    fail("file", db_ != nullptr ? sqlite3_errmsg(db_) : "cannot open");
  }
  sqlite3_extended_result_codes(db_, 1);
  std::string error;
  try {
    if (detail::query_text(db_, "PRAGMA journal_mode=WAL") != "wal") fail("file", "cannot use write-ahead logging here");
  } catch (const std::runtime_error& e) {
    fail("file", e.what());
  }
  std::string schema = "PRAGMA synchronous=NORMAL; BEGIN; PRAGMA application_id=";
  schema += std::to_string(detail::kApplicationId);
  schema += "; PRAGMA user_version=";
  schema += std::to_string(kFormatVersion);
  schema += ";";
  schema += detail::kSchema;
  if (detail::exec(db_, schema.c_str(), error) != SQLITE_OK) fail("schema", error);

  try {
    detail::Statement meta(db_, "INSERT INTO meta(key, value) VALUES(?, ?)");
    const auto put = [&](const char* key, const std::string& value) {
      sqlite3_bind_text(meta.get(), 1, key, -1, SQLITE_STATIC);
      sqlite3_bind_text(meta.get(), 2, value.data(), static_cast<int>(value.size()), SQLITE_TRANSIENT);
      const int rc = sqlite3_step(meta.get());
      sqlite3_reset(meta.get());
      if (rc != SQLITE_DONE) fail(std::string("meta ") + key, sqlite3_errmsg(db_));
    };
    put("format", std::string(kFormat));
    put("format_version", std::to_string(kFormatVersion));
    put("id", info.id.empty() ? random_id() : info.id);
    put("trainee", info.trainee);
    put("device", info.device);
    put("software_version", info.software_version);
    put("started_at", info.started_at.empty() ? now_utc() : info.started_at);
    put("rate_hz", detail::exact_text(info.rate_hz));
    put("case_source", info.case_source);
    put("case", info.case_document.dump());
    if (info.seed) put("seed", std::to_string(*info.seed));
    put("extra", info.extra.dump());

    detail::Statement sample(db_,
                             "INSERT INTO samples(tick, t, x, y, z, fx, fy, fz, body, u, v, depth, buttons, overrun, "
                             "fault) VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
    detail::Statement event(db_, "INSERT INTO events(t, kind, mark, x, y, z, note) VALUES(?, ?, ?, ?, ?, ?, ?)");
    if (detail::exec(db_, "COMMIT; BEGIN", error) != SQLITE_OK) fail("file", error);
    insert_sample_ = sample.release();  // finalized in close()
    insert_event_ = event.release();
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const SessionError*>(&e) != nullptr) throw;
    fail("file", e.what());
  }
}

SessionWriter::~SessionWriter() {
  if (db_ != nullptr && sqlite3_get_autocommit(db_) == 0) {
    std::string error;
    detail::exec(db_, "COMMIT", error);  // best effort: a destructor cannot report
  }
  close();
}

void SessionWriter::close() noexcept {
  sqlite3_finalize(insert_sample_);
  sqlite3_finalize(insert_event_);
  insert_sample_ = nullptr;
  insert_event_ = nullptr;
  if (db_ != nullptr) sqlite3_close_v2(db_);
  db_ = nullptr;
}

namespace {

void require_open(sqlite3* db, const std::filesystem::path& path, const char* what) {
  if (db == nullptr) throw SessionError(path.string(), what, "the session is finished (or failed to open)");
}

}  // namespace

void SessionWriter::append(const engine::Sample& s) {
  require_open(db_, path_, "samples");
  const auto tick = static_cast<sqlite3_int64>(samples_);
  const std::array<double, 7> values{s.t, s.position[0], s.position[1], s.position[2], s.force[0], s.force[1], s.force[2]};
  static constexpr std::array<const char*, 10> kNames{"t", "x", "y", "z", "fx", "fy", "fz", "u", "v", "depth"};
  const auto not_finite = [&](std::size_t column) {
    std::string where = "samples tick ";
    where += std::to_string(tick);
    where += ": column ";
    where += kNames[column];
    return SessionError(path_.string(), where, "not a finite number");
  };
  sqlite3_stmt* st = insert_sample_;
  sqlite3_bind_int64(st, 1, tick);
  for (std::size_t k = 0; k < values.size(); ++k) {
    // SQLite would store NaN as NULL and fail the NOT NULL constraint with a vaguer message.
    if (!std::isfinite(values[k])) throw not_finite(k);
    sqlite3_bind_double(st, static_cast<int>(k) + 2, values[k]);
  }
  if (s.body >= 0) {
    const std::array<double, 3> contact{s.u, s.v, s.depth};
    for (std::size_t k = 0; k < contact.size(); ++k) {
      if (!std::isfinite(contact[k])) throw not_finite(7 + k);
    }
    sqlite3_bind_int(st, 9, s.body);
    sqlite3_bind_double(st, 10, s.u);
    sqlite3_bind_double(st, 11, s.v);
    sqlite3_bind_double(st, 12, s.depth);
  } else {
    for (int column = 9; column <= 12; ++column) sqlite3_bind_null(st, column);
  }
  sqlite3_bind_int64(st, 13, static_cast<sqlite3_int64>(s.buttons));
  sqlite3_bind_int(st, 14, s.overrun ? 1 : 0);
  sqlite3_bind_int(st, 15, s.fault ? 1 : 0);
  const int rc = sqlite3_step(st);
  sqlite3_reset(st);
  if (rc != SQLITE_DONE) {
    std::string where = "samples tick ";
    where += std::to_string(tick);
    throw SessionError(path_.string(), where, sqlite3_errmsg(db_));
  }
  ++samples_;
}

void SessionWriter::event(const Event& e) {
  require_open(db_, path_, "events");
  std::string where = "events ";
  where += to_string(e.kind);
  where += " at t=";
  where += detail::exact_text(e.t);
  if (!std::isfinite(e.t)) throw SessionError(path_.string(), where, "the time is not a finite number");
  const bool has_mark = e.kind == EventKind::Mark || e.kind == EventKind::Unmark;
  if (has_mark && e.mark < 1) {
    throw SessionError(path_.string(), where, "a mark id must be >= 1, not " + std::to_string(e.mark));
  }
  if (e.kind == EventKind::Mark) {
    for (double x : e.position) {
      if (!std::isfinite(x)) throw SessionError(path_.string(), where, "the mark's position is not finite");
    }
  }
  sqlite3_stmt* st = insert_event_;
  sqlite3_bind_double(st, 1, e.t);
  const auto kind = to_string(e.kind);
  sqlite3_bind_text(st, 2, kind.data(), static_cast<int>(kind.size()), SQLITE_STATIC);
  if (has_mark) {
    sqlite3_bind_int64(st, 3, e.mark);
  } else {
    sqlite3_bind_null(st, 3);
  }
  for (int k = 0; k < 3; ++k) {
    if (e.kind == EventKind::Mark) {
      sqlite3_bind_double(st, 4 + k, e.position[static_cast<std::size_t>(k)]);
    } else {
      sqlite3_bind_null(st, 4 + k);
    }
  }
  sqlite3_bind_text(st, 7, e.note.data(), static_cast<int>(e.note.size()), SQLITE_TRANSIENT);
  const int rc = sqlite3_step(st);
  sqlite3_reset(st);
  if (rc != SQLITE_DONE) throw SessionError(path_.string(), where, sqlite3_errmsg(db_));
}

void SessionWriter::set_loop_stats(const engine::LoopStats& stats) { set_loop_stats(loop_stats_json(stats)); }

void SessionWriter::set_loop_stats(const nlohmann::json& summary) {
  require_open(db_, path_, "meta loop_stats");
  detail::Statement put(db_, "INSERT OR REPLACE INTO meta(key, value) VALUES('loop_stats', ?)");
  const std::string text = summary.dump();
  sqlite3_bind_text(put.get(), 1, text.data(), static_cast<int>(text.size()), SQLITE_TRANSIENT);
  if (sqlite3_step(put.get()) != SQLITE_DONE) throw SessionError(path_.string(), "meta loop_stats", sqlite3_errmsg(db_));
}

void SessionWriter::commit() {
  require_open(db_, path_, "commit");
  std::string error;
  if (sqlite3_get_autocommit(db_) == 0 && detail::exec(db_, "COMMIT", error) != SQLITE_OK) {
    throw SessionError(path_.string(), "commit", error);
  }
  if (detail::exec(db_, "BEGIN", error) != SQLITE_OK) throw SessionError(path_.string(), "commit", error);
}

void SessionWriter::finish() {
  require_open(db_, path_, "finish");
  const std::string file = path_.string();
  {
    detail::Statement put(db_, "INSERT OR REPLACE INTO meta(key, value) VALUES('ended_at', ?)");
    const std::string ended = now_utc();
    sqlite3_bind_text(put.get(), 1, ended.data(), static_cast<int>(ended.size()), SQLITE_TRANSIENT);
    if (sqlite3_step(put.get()) != SQLITE_DONE) throw SessionError(file, "meta ended_at", sqlite3_errmsg(db_));
  }
  std::string error;
  if (sqlite3_get_autocommit(db_) == 0 && detail::exec(db_, "COMMIT", error) != SQLITE_OK) {
    throw SessionError(file, "finish", error);
  }
  sqlite3_finalize(insert_sample_);
  sqlite3_finalize(insert_event_);
  insert_sample_ = nullptr;
  insert_event_ = nullptr;
  // Everything into the main file, then back to a rollback journal: a finished session is
  // one self-contained file that can be copied and opened read-only anywhere.
  if (detail::exec(db_, "PRAGMA wal_checkpoint(TRUNCATE)", error) != SQLITE_OK) {
    throw SessionError(file, "finish", error);
  }
  try {
    if (detail::query_text(db_, "PRAGMA journal_mode=DELETE") != "delete") {
      throw SessionError(file, "finish", "cannot leave write-ahead logging (is another program reading the session?)");
    }
  } catch (const SessionError&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw SessionError(file, "finish", e.what());
  }
  if (sqlite3_close(db_) != SQLITE_OK) throw SessionError(file, "finish", sqlite3_errmsg(db_));
  db_ = nullptr;
}

void write_session(const std::filesystem::path& path, const Session& session) {
  SessionWriter writer(path, session.info);
  for (const auto& sample : session.samples) writer.append(sample);
  for (const auto& event : session.events) writer.event(event);
  if (!session.loop_stats.is_null()) writer.set_loop_stats(session.loop_stats);
  writer.finish();
}

}  // namespace palpa::session
