#include "palpa/session/session_writer.hpp"

#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <memory>
#include <random>
#include <string_view>
#include <thread>
#include <utility>

#include <fmt/format.h>

#include "checks.hpp"
#include "compaction.hpp"
#include "file_claim.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/session/session_id.hpp"
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
// produce a session that cannot be read back (nor one Python's sqlite3 cannot decode).
struct CheckedInfo {
  std::string case_text;
  std::string extra_text;
  std::size_t bodies = 0;
};

CheckedInfo validate(const std::string& file, const SessionInfo& info) {
  if (info.trainee.empty()) throw SessionError(file, "trainee", "must not be empty");
  if (!std::isfinite(info.rate_hz) || info.rate_hz <= 0.0) {
    throw SessionError(file, "rate_hz", "must be a finite number > 0, not " + detail::exact_text(info.rate_hz));
  }
  const std::pair<const char*, const std::string*> texts[] = {
      {"id", &info.id},           {"trainee", &info.trainee},   {"device", &info.device},
      {"software_version", &info.software_version}, {"started_at", &info.started_at},
      {"case_source", &info.case_source}};
  for (const auto& [name, text] : texts) detail::check_utf8(file, name, *text);
  if (!info.case_document.is_object()) throw SessionError(file, "case", "the case document must be a JSON object");
  CheckedInfo checked;
  checked.case_text = detail::dump_json(file, "case", info.case_document);
  checked.extra_text = detail::dump_json(file, "extra", info.extra);
  try {
    checked.bodies = io::parse_case(checked.case_text, file + ": case").bodies.size();
  } catch (const io::CaseError& e) {
    const auto& p = e.problems();
    throw SessionError(file, "case " + (p.empty() ? std::string("/") : p.front().where),
                       p.empty() ? std::string(e.what()) : p.front().reason);
  }
  return checked;
}

}  // namespace

namespace {

struct CloseDb {
  void operator()(sqlite3* db) const { sqlite3_close_v2(db); }
};
using DbOwner = std::unique_ptr<sqlite3, CloseDb>;

DbOwner open_connection(const std::filesystem::path& where, const std::string& file) {
  sqlite3* raw = nullptr;
  const int rc = sqlite3_open_v2(where.c_str(), &raw, SQLITE_OPEN_READWRITE | SQLITE_OPEN_NOMUTEX, nullptr);
  DbOwner db(raw);  // owned even when the open failed (SQLite allocates a handle then)
  if (rc != SQLITE_OK) throw SessionError(file, "file", raw != nullptr ? sqlite3_errmsg(raw) : "cannot open");
  sqlite3_extended_result_codes(raw, 1);
  return db;
}

/// Writes the schema and the meta of `info` into the new, empty file at `building`, which no
/// other program knows of yet, commits them with a rollback journal and closes: the file is
/// a complete (empty) session before it gets its name. Messages name `file`, the final name.
void write_header(const std::filesystem::path& building, const std::string& file, const SessionInfo& info,
                  const CheckedInfo& checked) {
  const DbOwner owner = open_connection(building, file);
  sqlite3* db = owner.get();
  std::string error;
  const std::string schema =
      fmt::format("PRAGMA synchronous=FULL; BEGIN; PRAGMA application_id={}; PRAGMA user_version=1;{}",
                  detail::kApplicationId, detail::schema_of(1));
  if (detail::exec(db, schema.c_str(), error) != SQLITE_OK) throw SessionError(file, "schema", error);

  detail::Statement meta(db, "INSERT INTO meta(key, value) VALUES(?, ?)");
  const auto put = [&](const char* key, const std::string& value) {
    sqlite3_bind_text(meta.get(), 1, key, -1, SQLITE_STATIC);
    sqlite3_bind_text(meta.get(), 2, value.data(), static_cast<int>(value.size()), SQLITE_TRANSIENT);
    const int step = sqlite3_step(meta.get());
    sqlite3_reset(meta.get());
    if (step != SQLITE_DONE) throw SessionError(file, std::string("meta ") + key, sqlite3_errmsg(db));
  };
  put("format", std::string(kFormat));
  put("format_version", "1");  // rows while recording; finish() compacts into format 2
  put("id", info.id.empty() ? new_session_id() : info.id);
  put("trainee", info.trainee);
  put("device", info.device);
  put("software_version", info.software_version);
  put("started_at", info.started_at.empty() ? now_utc() : info.started_at);
  put("rate_hz", detail::exact_text(info.rate_hz));
  put("case_source", info.case_source);
  put("case", checked.case_text);
  if (info.seed) put("seed", fmt::format("{}", *info.seed));
  put("extra", checked.extra_text);
  meta = detail::Statement();  // finalized before the connection closes
  if (detail::exec(db, "COMMIT", error) != SQLITE_OK) throw SessionError(file, "file", error);
  // Into write-ahead logging here, not after the file has its name: the switch rewrites the
  // header through a rollback journal, and a kill during it would leave a hot journal that
  // a read-only reader cannot roll back. Closing this (last) connection removes -wal, -shm.
  if (detail::query_text(db, "PRAGMA journal_mode=WAL") != "wal") {
    throw SessionError(file, "file", "cannot use write-ahead logging here");
  }
}

/// The published session opened for recording: write-ahead logging, the two insert
/// statements, the first transaction open.
struct Opened {
  DbOwner db;
  detail::Statement insert_sample, insert_event;
};

Opened open_for_recording(const std::string& file) {
  Opened out;
  out.db = open_connection(file, file);
  sqlite3* db = out.db.get();
  // Another program reading the live file (a viewer, Python) holds locks only briefly.
  sqlite3_busy_timeout(db, 200);
  if (detail::query_text(db, "PRAGMA journal_mode=WAL") != "wal") {
    throw SessionError(file, "file", "cannot use write-ahead logging here");
  }
  std::string error;
  if (detail::exec(db, "PRAGMA synchronous=NORMAL", error) != SQLITE_OK) throw SessionError(file, "file", error);
  out.insert_sample = detail::Statement(db,
                                        "INSERT INTO samples(tick, t, x, y, z, fx, fy, fz, body, u, v, depth, buttons, "
                                        "overrun, fault) VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  out.insert_event =
      detail::Statement(db, "INSERT INTO events(t, kind, mark, x, y, z, note) VALUES(?, ?, ?, ?, ?, ?, ?)");
  if (detail::exec(db, "BEGIN", error) != SQLITE_OK) throw SessionError(file, "file", error);
  return out;
}

void remove_with_journals(const std::filesystem::path& path) {
  std::error_code ec;
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) {
    auto p = path;
    p += suffix;
    std::filesystem::remove(p, ec);
  }
}

/// Inside a catch block: the exception in flight as a SessionError naming `file`.
[[noreturn]] void rethrow_as_session_error(const std::string& file) {
  try {
    throw;
  } catch (const SessionError&) {
    throw;
  } catch (const std::exception& e) {
    throw SessionError(file, "file", e.what());
  } catch (...) {
    throw SessionError(file, "file", "unknown error while creating the session");
  }
}

/// Everything into the main file, then back to a rollback journal, so that the session is
/// one self-contained file that can be copied and opened read-only anywhere. With another
/// program holding the file open, the checkpoint stops short and the switch needs an
/// exclusive lock it cannot have: false after `attempts` tries, with the reason in `error`.
bool leave_write_ahead_logging(sqlite3* db, int attempts, std::string& error) {
  for (int attempt = 0; attempt < attempts; ++attempt) {
    if (attempt > 0) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (detail::exec(db, "PRAGMA wal_checkpoint(TRUNCATE)", error) != SQLITE_OK) continue;
    try {
      if (detail::query_text(db, "PRAGMA journal_mode=DELETE") == "delete") return true;
    } catch (const std::runtime_error& e) {
      error = e.what();
    }
  }
  return false;
}

}  // namespace

SessionWriter::SessionWriter(const std::filesystem::path& path, const SessionInfo& info, const WriterOptions& options)
    : path_(path), options_(options) {
  if (options.format_version != 1 && options.format_version != 2) {
    throw SessionError(path.string(), "format_version", fmt::format("{} (1 or 2)", options.format_version));
  }
  const std::string file = path.string();
  const CheckedInfo checked = validate(file, info);
  detail::refuse_taken_name(path);
  detail::remove_abandoned_creations(path);
  const std::filesystem::path building = detail::creating_path(path);
  detail::create_exclusive(building);
  try {
    write_header(building, file, info, checked);
    detail::publish(building, path);
  } catch (...) {
    remove_with_journals(building);  // ours alone: nobody else knows its name
    rethrow_as_session_error(file);
  }
  try {
    Opened opened = open_for_recording(file);
    // Statements first: they must be finalized before the connection closes (close()).
    insert_sample_ = opened.insert_sample.release();
    insert_event_ = opened.insert_event.release();
    db_ = opened.db.release();
    bodies_ = checked.bodies;
  } catch (...) {
    // Everything opened is closed by now. The file is ours (published just now) and holds
    // no samples yet: leave no half-made session behind.
    remove_with_journals(path);
    rethrow_as_session_error(file);
  }
}

SessionWriter::~SessionWriter() {
  if (db_ != nullptr && sqlite3_get_autocommit(db_) == 0) {
    std::string error;
    // Best effort: a destructor cannot report. A session cut short this way is still made
    // one self-contained file when no other program has it open.
    if (detail::exec(db_, "COMMIT", error) == SQLITE_OK) leave_write_ahead_logging(db_, 1, error);
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
  const auto where = [&](const char* column) { return fmt::format("samples tick {}: column {}", tick, column); };
  const std::array<double, 7> values{s.t, s.position[0], s.position[1], s.position[2], s.force[0], s.force[1], s.force[2]};
  static constexpr std::array<const char*, 10> kNames{"t", "x", "y", "z", "fx", "fy", "fz", "u", "v", "depth"};
  // SQLite would store NaN as NULL and fail the NOT NULL constraint with a vaguer message.
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (!std::isfinite(values[k])) throw SessionError(path_.string(), where(kNames[k]), "not a finite number");
  }
  if (samples_ > 0 && s.t < last_t_) {
    std::string reason = "time goes backwards (";
    reason += detail::exact_text(s.t);
    reason += " s after ";
    reason += detail::exact_text(last_t_);
    reason += " s)";
    throw SessionError(path_.string(), where("t"), reason);
  }
  if (s.body >= 0) {
    if (static_cast<std::size_t>(s.body) >= bodies_) {
      throw SessionError(path_.string(), where("body"),
                         fmt::format("the case has {} bodies, there is no body {}", bodies_, s.body));
    }
    const std::array<double, 3> contact{s.u, s.v, s.depth};
    for (std::size_t k = 0; k < contact.size(); ++k) {
      if (!std::isfinite(contact[k])) throw SessionError(path_.string(), where(kNames[7 + k]), "not a finite number");
    }
  }
  insert(s);
}

bool SessionWriter::append_repairing(const engine::Sample& sample) {
  require_open(db_, path_, "samples");
  engine::Sample s = sample;
  bool repaired = false;
  const auto zero_if_not_finite = [&](double& x) {
    if (!std::isfinite(x)) {
      x = 0.0;
      repaired = true;
    }
  };
  for (auto& x : s.position) zero_if_not_finite(x);
  for (auto& x : s.force) zero_if_not_finite(x);
  const double t_floor = samples_ > 0 ? last_t_ : 0.0;
  if (!std::isfinite(s.t) || (samples_ > 0 && s.t < last_t_)) {
    s.t = t_floor;
    repaired = true;
  }
  if (s.body >= 0 && (static_cast<std::size_t>(s.body) >= bodies_ || !std::isfinite(s.u) || !std::isfinite(s.v) ||
                      !std::isfinite(s.depth))) {
    s.body = -1;
    s.u = s.v = s.depth = 0.0;
    repaired = true;
  }
  if (repaired) {
    s.fault = true;
    ++repaired_;
  }
  insert(s);
  return !repaired;
}

// Binds and inserts a checked sample as tick samples_.
void SessionWriter::insert(const engine::Sample& s) {
  const auto tick = static_cast<sqlite3_int64>(samples_);
  sqlite3_stmt* st = insert_sample_;
  sqlite3_bind_int64(st, 1, tick);
  const std::array<double, 7> values{s.t, s.position[0], s.position[1], s.position[2], s.force[0], s.force[1], s.force[2]};
  for (std::size_t k = 0; k < values.size(); ++k) sqlite3_bind_double(st, static_cast<int>(k) + 2, values[k]);
  if (s.body >= 0) {
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
    throw SessionError(path_.string(), fmt::format("samples tick {}", tick), sqlite3_errmsg(db_));
  }
  ++samples_;
  last_t_ = s.t;
}

void SessionWriter::event(const Event& e) {
  require_open(db_, path_, "events");
  check_event(path_.string(), e);
  const bool has_mark = e.kind == EventKind::Mark || e.kind == EventKind::Unmark;
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
  if (rc != SQLITE_DONE) {
    std::string where = "events ";
    where += to_string(e.kind);
    where += " at t=";
    where += detail::exact_text(e.t);
    throw SessionError(path_.string(), where, sqlite3_errmsg(db_));
  }
}

void SessionWriter::set_loop_stats(const engine::LoopStats& stats) {
  auto summary = loop_stats_json(stats);
  summary["repaired"] = repaired_;
  set_loop_stats(summary);
}

void SessionWriter::set_loop_stats(const engine::LoopStats& stats, std::uint64_t dropped_samples) {
  auto summary = loop_stats_json(stats);
  summary["dropped"] = dropped_samples;
  summary["repaired"] = repaired_;
  set_loop_stats(summary);
}

void SessionWriter::set_loop_stats(const nlohmann::json& summary) {
  require_open(db_, path_, "meta loop_stats");
  const std::string text = detail::dump_json(path_.string(), "meta loop_stats", summary);
  detail::Statement put(db_, "INSERT OR REPLACE INTO meta(key, value) VALUES('loop_stats', ?)");
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
  if (options_.format_version >= 2) compact();
  // Everything is committed. With a reader open the session stays in WAL mode, complete,
  // which is a warning and not an error.
  if (!leave_write_ahead_logging(db_, 3, error)) {
    if (!warning_.empty()) warning_ += "; ";
    warning_ += file;
    warning_ += ": finish: left in write-ahead-log mode (keep its -wal and -shm beside it): ";
    warning_ += "another program has the session open";
    if (!error.empty()) {
      warning_ += " (";
      warning_ += error;
      warning_ += ")";
    }
  }
  if (sqlite3_close(db_) != SQLITE_OK) throw SessionError(file, "finish", sqlite3_errmsg(db_));
  db_ = nullptr;
}

// Format 2, in its own transaction after everything is committed as rows: a kill during it
// leaves the format-1 file; one that cannot be made is a warning, never a loss.
void SessionWriter::compact() {
  try {
    if (const std::string not_vacuumed = detail::compact_samples(db_); !not_vacuumed.empty()) {
      warning_ = path_.string() + ": finish: format 2, not shrunk (" + not_vacuumed + ")";
    }
  } catch (const std::runtime_error& e) {
    warning_ = path_.string() + ": finish: kept in format 1 (" + e.what() + ")";
  }
}

void write_session(const std::filesystem::path& path, const Session& session, const WriterOptions& options) {
  SessionWriter writer(path, session.info, options);
  for (const auto& sample : session.samples) writer.append(sample);
  for (const auto& event : session.events) writer.event(event);
  if (!session.loop_stats.is_null()) writer.set_loop_stats(session.loop_stats);
  writer.finish();
}

}  // namespace palpa::session
