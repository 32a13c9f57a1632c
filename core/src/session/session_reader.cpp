#include "palpa/session/session_reader.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <string_view>

#include <fmt/format.h>

#include "palpa/io/case_file.hpp"
#include "palpa/io/json_text.hpp"
#include "hot_journal.hpp"
#include "sample_blocks.hpp"
#include "sqlite_util.hpp"

namespace palpa::session {
namespace {

std::string hex32(std::uint32_t value) { return fmt::format("0x{:08X}", value); }

/// Reads one session file; every failure is a SessionError naming the file and the place.
/// read_head() reads everything but the samples, then read_more() hands them over a block
/// at a time (SampleStream), or all of them into one vector (read_session).
class Reader {
 public:
  Reader(const std::filesystem::path& path) : file_(path.string()) {}
  /// A whole session file held in memory, named `name` in errors.
  Reader(const std::string& name, const std::string& bytes) : file_(name), bytes_(&bytes) {}
  ~Reader() {
    samples_query_.reset();  // finalized before the connection closes
    if (db_ != nullptr) sqlite3_close_v2(db_);
  }
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  /// Opens the file and reads meta and events in a read transaction. With
  /// options.samples, checks the sample count and leaves the transaction open for
  /// read_more(); without, ends it.
  Session read_head(const std::filesystem::path& path, const ReadOptions& options);
  /// Appends the next samples to `out`: one block (format 2) or up to kRowsPerRead rows
  /// (format 1), every check made. False, with nothing appended, once all were read (the
  /// transaction then ends).
  bool read_more(std::vector<engine::Sample>& out);
  /// The file's sample count, capped for a reservation (count_samples).
  std::int64_t reserve_hint() const { return reserve_hint_; }
  /// The file's sample count as its tables declare it (checked against the limit).
  std::int64_t declared_count() const { return declared_; }
  std::optional<SampleTimes> sample_times();

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& reason) const {
    throw SessionError(file_, where, reason);
  }
  [[noreturn]] void fail_sqlite(const std::string& where, int rc) const;
  void check_file(const std::filesystem::path& path);
  void check_bytes();
  void open_in_memory();
  void configure();
  [[noreturn]] void fail_wal_missing() const;
  bool wal_files_missing() const;
  void refuse_empty_without_wal(const Session& session);
  void open();
  void check_identity();
  void read_format_version();
  void check_tables();
  void check_schema();
  bool has_table(const char* name);
  void read_meta(Session& session);
  void read_events(Session& session);
  void start_samples(std::int64_t max_samples);
  bool read_rows(std::vector<engine::Sample>& out, bool& at_end);
  bool read_block(std::vector<engine::Sample>& out);
  void end_transaction();
  std::int64_t count_samples(const char* sql, std::int64_t max_samples);
  std::optional<double> peek_time(bool last);
  template <typename Where>
  void check_contact(engine::Sample& s, const Where& where) const;
  template <typename Where>
  void check_time(double t, double previous_t, const Where& where) const;

  detail::Statement prepare(const std::string& where, const char* sql) {
    try {
      return detail::Statement(db_, sql);
    } catch (const std::runtime_error&) {
      fail_sqlite(where, sqlite3_extended_errcode(db_));
    }
  }
  /// Steps a query: true for a row, false at the end; throws on anything else.
  bool step(const detail::Statement& statement, const std::string& where) const {
    const int rc = sqlite3_step(statement.get());
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    fail_sqlite(where, rc);
  }

  std::string file_;
  const std::string* bytes_ = nullptr;  // the file's bytes when read from memory (SampleStream from bytes)
  bool wal_header_ = false;  // the file header says WAL mode: it needs its -wal and -shm
  bool wal_absent_ = false;  // ... and before opening, its -wal was missing or empty
  detail::JournalBeside journal_ = detail::JournalBeside::None;
  sqlite3* db_ = nullptr;
  int version_ = 1;  // meta format_version: 1 (samples rows) or 2 (sample_blocks)
  std::size_t bodies_ = 0;  // in the session's case: a sample's body index must be below it
  std::vector<double> thickness_;  // m, per body: 2 x its largest radius, the deepest press it has
  // Where read_more() has got to: the samples' query (reset at the end), the last tick and
  // time read (the next must follow them), how many were read.
  std::optional<detail::Statement> samples_query_;
  std::int64_t max_samples_ = 0, reserve_hint_ = 0, declared_ = 0, read_ = 0, previous_tick_ = -1;
  double previous_t_ = -std::numeric_limits<double>::infinity();
  std::vector<std::int64_t> ticks_;  // the ticks of the block being read
};

void Reader::fail_wal_missing() const {
  fail("file", "recorded in WAL mode: its -wal/-shm files are missing or the folder is not writable");
}

// A session left in WAL mode (cut short, or finished while another program had it open)
// keeps part of its data in FILE-wal; without it (or without FILE-shm where none can be
// made) SQLite sees an empty or unopenable database.
bool Reader::wal_files_missing() const { return wal_header_ && wal_absent_; }

// The header and case of a session are in its main file from the start; its samples are in
// the -wal until a checkpoint. So a session in WAL mode that was missing its -wal and has
// no End and no samples is a copy made without its -wal (or a recording stopped before its
// first commit): say so rather than read it as a session in which nothing happened.
void Reader::refuse_empty_without_wal(const Session& session) {
  if (!wal_files_missing() || session.complete) return;
  auto any = prepare("samples", version_ >= 2 ? "SELECT EXISTS(SELECT 1 FROM sample_blocks)"
                                              : "SELECT EXISTS(SELECT 1 FROM samples)");
  if (step(any, "samples") && sqlite3_column_int(any.get(), 0) != 0) return;
  fail("file",
       "recorded in WAL mode and holds no samples without its -wal: keep its -wal and -shm beside it "
       "when copying (or the recording stopped before its first commit)");
}

void Reader::fail_sqlite(const std::string& where, int rc) const {
  const std::string message = db_ != nullptr ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
  if (wal_header_ && ((rc & 0xFF) == SQLITE_CANTOPEN || (rc & 0xFF) == SQLITE_READONLY)) fail_wal_missing();
  switch (rc & 0xFF) {
    case SQLITE_NOTADB: fail("file", "not a Palpa session (not an SQLite database)");
    case SQLITE_CORRUPT: fail(where, "damaged file (" + message + "): it was cut short or overwritten");
    case SQLITE_CANTOPEN: fail("file", "cannot open (" + message + ")");
    case SQLITE_NOMEM: fail(where, "out of memory");
    default: fail(where, message);
  }
}

void Reader::check_file(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found) fail("file", "no such file");
  if (ec) fail("file", ec.message());
  if (status.type() == std::filesystem::file_type::directory) fail("file", "is a folder, not a session file");
  if (status.type() != std::filesystem::file_type::regular) fail("file", "not a regular file");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) fail("file", ec.message());
  if (size == 0) fail("file", "not a Palpa session (empty file)");
  // SQLite takes any file to be a database until it reads it; say plainly what is not.
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("file", "cannot open for reading");
  std::array<char, 20> header{};
  in.read(header.data(), static_cast<std::streamsize>(header.size()));
  if (in.gcount() < 16 || std::string_view(header.data(), 16) != std::string_view("SQLite format 3\0", 16)) {
    fail("file", "not a Palpa session (not an SQLite database)");
  }
  // Bytes 18 and 19: the file format's write and read versions, 2 in WAL mode.
  wal_header_ = in.gcount() == 20 && header[18] == 2 && header[19] == 2;
  // Looked at before opening: SQLite creates an empty -wal (and -shm) where it can.
  std::error_code wal_ec;
  const auto wal_size = std::filesystem::file_size(file_ + "-wal", wal_ec);
  wal_absent_ = wal_ec || wal_size == 0;
  journal_ = detail::journal_beside(path);
  if (journal_ == detail::JournalBeside::Transaction) {
    fail("file", "a write was interrupted and its " + path.filename().string() +
                     "-journal lies beside it; Palpa reads sessions without changing them and cannot roll it back "
                     "(opening the file once with the sqlite3 tool does)");
  }
}

void Reader::check_bytes() {
  if (bytes_->empty()) fail("file", "not a Palpa session (empty file)");
  if (bytes_->size() < 16 || std::string_view(bytes_->data(), 16) != std::string_view("SQLite format 3\0", 16)) {
    fail("file", "not a Palpa session (not an SQLite database)");
  }
}

// The bytes deserialized into an in-memory database (SQLite's memdb), read-only. A file
// whose header says WAL mode is read as a rollback-journal file: memory has no -wal.
void Reader::open_in_memory() {
  int rc = sqlite3_open_v2(":memory:", &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_NOMUTEX, nullptr);
  if (rc != SQLITE_OK) fail_sqlite("file", rc);
  const auto size = static_cast<sqlite3_uint64>(bytes_->size());
  auto* copy = static_cast<unsigned char*>(sqlite3_malloc64(size));
  if (copy == nullptr) fail("file", "out of memory");
  std::memcpy(copy, bytes_->data(), bytes_->size());
  if (size >= 20 && copy[18] == 2 && copy[19] == 2) copy[18] = copy[19] = 1;
  rc = sqlite3_deserialize(db_, "main", copy, static_cast<sqlite3_int64>(size), static_cast<sqlite3_int64>(size),
                           SQLITE_DESERIALIZE_FREEONCLOSE | SQLITE_DESERIALIZE_READONLY);
  if (rc != SQLITE_OK) fail_sqlite("file", rc);
  configure();
}

void Reader::open() {
  // Read-only: a session is evidence and is never changed by reading it. A session cut
  // short still has its -wal (and -shm) beside it; SQLite reads the committed part of it.
  // After a kill while finish() switched out of write-ahead logging, every page is whole in
  // the main file and the journal holds page 1 alone (hot_journal.hpp): read it as it is.
  const bool as_is = journal_ == detail::JournalBeside::HeaderSwitchOnly;
  const std::string name = as_is ? detail::sqlite_uri(file_, "immutable=1") : file_;
  const int flags = SQLITE_OPEN_READONLY | SQLITE_OPEN_NOMUTEX | (as_is ? SQLITE_OPEN_URI : 0);
  const int rc = sqlite3_open_v2(name.c_str(), &db_, flags, nullptr);
  if (rc != SQLITE_OK) fail_sqlite("file", rc);
  configure();
}

void Reader::configure() {
  sqlite3_extended_result_codes(db_, 1);
  sqlite3_busy_timeout(db_, 2000);  // a writer mid-commit: wait briefly, never hang
  // A hostile file may carry views or triggers: run nothing it defines.
  sqlite3_db_config(db_, SQLITE_DBCONFIG_DEFENSIVE, 1, nullptr);
  sqlite3_db_config(db_, SQLITE_DBCONFIG_TRUSTED_SCHEMA, 0, nullptr);
  std::string error;
  if (const int pragma = detail::exec(db_, "PRAGMA cell_size_check=ON", error); pragma != SQLITE_OK) {
    fail_sqlite("file", pragma);
  }
}

bool Reader::has_table(const char* name) {
  auto query = prepare("file", "SELECT 1 FROM sqlite_schema WHERE type = 'table' AND name = ?");
  sqlite3_bind_text(query.get(), 1, name, -1, SQLITE_STATIC);
  return step(query, "file");
}

void Reader::check_identity() {
  auto query = prepare("file", "PRAGMA application_id");
  if (!step(query, "file")) fail("file", "not a Palpa session (no application_id)");
  const auto id = static_cast<std::uint32_t>(sqlite3_column_int(query.get(), 0));
  if (id != static_cast<std::uint32_t>(detail::kApplicationId)) {
    if (!has_table("meta")) {
      if (wal_files_missing()) fail_wal_missing();
      fail("file", "not a Palpa session (an SQLite database without Palpa's tables)");
    }
    fail("application_id", "not a Palpa session (application_id is " + hex32(id) + ", a session has " +
                               hex32(static_cast<std::uint32_t>(detail::kApplicationId)) + " 'PALP')");
  }
  for (const char* table : {"meta", "events"}) {
    if (!has_table(table)) fail(table, "table is missing");
  }
  // Palpa writes no views or triggers; one in a session is a hand-made or hostile file.
  auto extra = prepare("file", "SELECT type, name FROM sqlite_schema WHERE type IN ('view', 'trigger') LIMIT 1");
  if (step(extra, "file")) {
    std::string reason = "not a Palpa session (holds a ";
    reason += reinterpret_cast<const char*>(sqlite3_column_text(extra.get(), 0));
    reason += " '";
    const auto* name = sqlite3_column_text(extra.get(), 1);
    reason += name != nullptr ? reinterpret_cast<const char*>(name) : "";
    reason += "'; sessions have none)";
    fail("file", reason);
  }
}

// The format version decides which tables the file must have, so it is read first (after
// the meta table is known to exist): a newer format is refused before anything else.
void Reader::read_format_version() {
  auto query = prepare("meta", "SELECT key, value FROM meta WHERE key IN ('format', 'format_version')");
  std::string format, version_text;
  bool has_format = false, has_version = false;
  while (step(query, "meta")) {
    const auto* key = sqlite3_column_text(query.get(), 0);
    const auto* value = sqlite3_column_text(query.get(), 1);
    if (key == nullptr) continue;
    if (value == nullptr) fail(std::string("meta ") + reinterpret_cast<const char*>(key), "no value (NULL)");
    const bool is_format = std::string_view(reinterpret_cast<const char*>(key)) == "format";
    (is_format ? has_format : has_version) = true;
    (is_format ? format : version_text) = reinterpret_cast<const char*>(value);
  }
  if (!has_format) fail("meta format", "missing");
  if (format != kFormat) fail("meta format", "not a Palpa session (format is '" + format + "')");
  if (!has_version) fail("meta format_version", "missing");
  const char* end = version_text.data() + version_text.size();
  const auto parsed = std::from_chars(version_text.data(), end, version_);
  if (parsed.ec != std::errc() || parsed.ptr != end || version_text.empty()) {
    fail("meta format_version", "not an integer: '" + version_text + "'");
  }
  if (version_ > kFormatVersion) {
    fail("meta format_version",
         fmt::format("format version {} is newer than this Palpa reads ({})", version_, kFormatVersion));
  }
  if (version_ < 1) fail("meta format_version", fmt::format("format version {} does not exist", version_));
}

void Reader::check_tables() {
  const char* samples = version_ >= 2 ? "sample_blocks" : "samples";
  if (!has_table(samples)) fail(samples, "table is missing");
}

// Exactly the documented schema, compared before a row is read: an extra table, index,
// view or trigger, a changed column or a generated one (which SQLite would evaluate on
// reading it, at whatever cost the file's author chose) is refused, naming the first
// difference.
void Reader::check_schema() {
  std::string found;
  try {
    found = detail::schema_fingerprint(db_);
  } catch (const std::runtime_error&) {
    fail_sqlite("file", sqlite3_extended_errcode(db_));
  }
  const std::string& expected = detail::expected_schema_fingerprint(version_);
  if (found == expected) return;
  const auto lines = [](const std::string& text) {
    std::vector<std::string> out;
    for (std::size_t at = 0, end; at < text.size(); at = end + 1) {
      end = text.find('\n', at);
      out.push_back(text.substr(at, end - at));
    }
    return out;
  };
  const auto have = lines(found);
  const auto want = lines(expected);
  for (const auto& line : have) {
    if (std::find(want.begin(), want.end(), line) == want.end()) {
      fail("file", "not a Palpa session (its schema has " + line + ", which a session does not; docs/session-format.md)");
    }
  }
  for (const auto& line : want) {
    if (std::find(have.begin(), have.end(), line) == have.end()) {
      fail("file", "not a Palpa session (its schema lacks " + line + "; docs/session-format.md)");
    }
  }
  fail("file", "not a Palpa session (its schema differs from docs/session-format.md)");
}

template <typename T>
bool parse_number(const std::string& text, T& out) {
  const char* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, out);
  return result.ec == std::errc() && result.ptr == end && !text.empty();
}

void Reader::read_meta(Session& session) {
  std::map<std::string, std::string> meta;
  auto query = prepare("meta", "SELECT key, value FROM meta");
  while (step(query, "meta")) {
    if (sqlite3_column_type(query.get(), 0) == SQLITE_NULL) continue;
    const std::string key(reinterpret_cast<const char*>(sqlite3_column_text(query.get(), 0)));
    if (sqlite3_column_type(query.get(), 1) == SQLITE_NULL) fail("meta " + key, "no value (NULL)");
    const auto* value = reinterpret_cast<const char*>(sqlite3_column_text(query.get(), 1));
    meta[key] = std::string(value, static_cast<std::size_t>(sqlite3_column_bytes(query.get(), 1)));
  }
  const auto get = [&](const char* key) -> const std::string& {
    const auto it = meta.find(key);
    if (it == meta.end()) fail(std::string("meta ") + key, "missing");
    return it->second;
  };

  session.format_version = version_;  // checked by read_format_version()
  auto& info = session.info;
  info.id = get("id");
  info.trainee = get("trainee");
  info.device = get("device");
  info.software_version = get("software_version");
  info.started_at = get("started_at");
  info.case_source = get("case_source");
  if (!parse_number(get("rate_hz"), info.rate_hz) || !std::isfinite(info.rate_hz) || info.rate_hz <= 0.0) {
    fail("meta rate_hz", "not a finite number > 0: '" + get("rate_hz") + "'");
  }
  if (const auto it = meta.find("seed"); it != meta.end()) {
    std::uint64_t seed = 0;
    if (!parse_number(it->second, seed)) fail("meta seed", "not an unsigned 64-bit integer: '" + it->second + "'");
    info.seed = seed;
  }

  const std::string& case_text = get("case");
  if (case_text.size() > io::CaseLimits::kMaxFileBytes) fail("meta case", "too large for a case");
  try {
    auto parsed = io::parse_case(case_text, file_ + ": meta case");
    bodies_ = parsed.bodies.size();
    for (const auto& body : parsed.bodies) {
      double largest = 0.0;
      for (const double r : body.radius) largest = std::max(largest, r);
      thickness_.push_back(2.0 * largest);
    }
    info.case_document = std::move(parsed.document);
  } catch (const io::CaseError& e) {
    const auto& problems = e.problems();
    if (problems.empty()) fail("meta case", e.what());
    fail("meta case " + problems.front().where, problems.front().reason);
  }

  const auto json = [&](const char* key, const std::string& text) {
    nlohmann::json out;
    if (const auto problem = io::parse_json_text(text, io::CaseLimits::kMaxDepth, io::CaseLimits::kMaxValues, out)) {
      fail(std::string("meta ") + key, problem->where + ": " + problem->reason);
    }
    return out;
  };
  info.extra = json("extra", get("extra"));
  if (const auto it = meta.find("loop_stats"); it != meta.end()) session.loop_stats = json("loop_stats", it->second);
}

// Column checks shared by events and samples: `where` is only built when something is wrong.
struct Row {
  const std::string& file;
  sqlite3_stmt* stmt;
  const char* table;     // "samples" or "events"
  const char* key_name;  // "tick" or "id"
  std::int64_t key = 0;

  std::string where(const char* column) const {
    if (column == nullptr) return fmt::format("{} {} {}", table, key_name, key);
    return fmt::format("{} {} {}: column {}", table, key_name, key, column);
  }
  bool is_null(int column) const { return sqlite3_column_type(stmt, column) == SQLITE_NULL; }
  double real(int column, const char* name) const {
    const int type = sqlite3_column_type(stmt, column);
    if (type != SQLITE_FLOAT && type != SQLITE_INTEGER) {
      throw SessionError(file, where(name), type == SQLITE_NULL ? "missing (NULL)" : "not a number");
    }
    const double value = sqlite3_column_double(stmt, column);
    if (!std::isfinite(value)) throw SessionError(file, where(name), "not a finite number");
    return value;
  }
  std::int64_t integer(int column, const char* name, std::int64_t lo, std::int64_t hi) const {
    const int type = sqlite3_column_type(stmt, column);
    if (type != SQLITE_INTEGER) {
      throw SessionError(file, where(name), type == SQLITE_NULL ? "missing (NULL)" : "not an integer");
    }
    const std::int64_t value = sqlite3_column_int64(stmt, column);
    if (value < lo || value > hi) {
      const std::string reason = hi == std::numeric_limits<std::int64_t>::max()
                                     ? fmt::format("must be >= {}, not {}", lo, value)
                                     : fmt::format("must be in {}..{}, not {}", lo, hi, value);
      throw SessionError(file, where(name), reason);
    }
    return value;
  }
};

constexpr std::int64_t kInt64Max = std::numeric_limits<std::int64_t>::max();

void Reader::read_events(Session& session) {
  auto query = prepare("events", "SELECT id, t, kind, mark, x, y, z, note FROM events ORDER BY t, id");
  Row row{file_, query.get(), "events", "id"};
  while (step(query, "events")) {
    row.key = sqlite3_column_int64(query.get(), 0);
    Event e;
    e.t = row.real(1, "t");
    const auto* kind_text = sqlite3_column_text(query.get(), 2);
    const std::string kind = kind_text == nullptr ? std::string() : reinterpret_cast<const char*>(kind_text);
    const auto kind_value = event_kind_from_string(kind);
    if (!kind_value) throw SessionError(file_, row.where("kind"), "unknown event kind '" + kind + "'");
    e.kind = *kind_value;
    if (e.kind == EventKind::Mark || e.kind == EventKind::Unmark) e.mark = row.integer(3, "mark", 1, kInt64Max);
    if (e.kind == EventKind::Mark) {
      e.position = {row.real(4, "x"), row.real(5, "y"), row.real(6, "z")};
    }
    if (const auto* note = sqlite3_column_text(query.get(), 7)) {
      e.note.assign(reinterpret_cast<const char*>(note), static_cast<std::size_t>(sqlite3_column_bytes(query.get(), 7)));
    }
    if (e.kind == EventKind::End) session.complete = true;
    session.events.push_back(std::move(e));
  }
}

// Round-off a writer may leave beyond the ranges (a foot point's parameters, a depth of
// -1e-18): accepted, and clamped for u and v.
constexpr double kParameterSlack = 1e-9;
constexpr double kDepthSlack = 1e-6;  // m

// The sample count as the file declares it, refused beyond `max_samples` before a value
// is read. Capped for the reservation (about 4 million ticks, 70 minutes at 1 kHz): a
// hostile count must not make the reservation itself fail; a longer session grows the
// vector as it reads.
std::int64_t Reader::count_samples(const char* sql, std::int64_t max_samples) {
  auto count = prepare("samples", sql);
  if (!step(count, "samples")) return 0;
  const auto rows = std::max<sqlite3_int64>(0, sqlite3_column_int64(count.get(), 0));
  if (rows > max_samples) {
    fail("samples", fmt::format("{} rows: more than a session may hold ({}; 72000000 is 20 hours at 1 kHz)", rows,
                                max_samples));
  }
  declared_ = rows;
  return std::min<sqlite3_int64>(rows, sqlite3_int64{1} << 22);
}

template <typename Where>
void Reader::check_time(double t, double previous_t, const Where& where) const {
  if (t < previous_t) {
    throw SessionError(file_, where("t"),
                       "time goes backwards (" + detail::exact_text(t) + " s after " + detail::exact_text(previous_t) +
                           " s)");
  }
}

// In the format's ranges (docs/session-format.md): parameters in [0, 1], a press no deeper
// than the body is thick (a hostile value would send scoring out of bounds).
template <typename Where>
void Reader::check_contact(engine::Sample& s, const Where& where) const {
  for (const auto& [value, name] : {std::pair{s.u, "u"}, std::pair{s.v, "v"}}) {
    if (!(value >= -kParameterSlack && value <= 1.0 + kParameterSlack)) {
      throw SessionError(file_, where(name), "outside [0, 1]: " + detail::exact_text(value));
    }
  }
  s.u = std::clamp(s.u, 0.0, 1.0);
  s.v = std::clamp(s.v, 0.0, 1.0);
  const double thickness = thickness_[static_cast<std::size_t>(s.body)];
  const double deepest = thickness * (1.0 + 1e-6) + kDepthSlack;
  if (!(s.depth >= -kDepthSlack && s.depth <= deepest)) {
    throw SessionError(file_, where("depth"),
                       "outside [0, " + detail::exact_text(thickness) + "] m, the body's thickness: " +
                           detail::exact_text(s.depth));
  }
}

// Format 1 reads this many rows a call: about what a format-2 block holds.
constexpr int kRowsPerRead = 1024;

void Reader::start_samples(std::int64_t max_samples) {
  static constexpr const char* kColumns =
      "SELECT tick, t, x, y, z, fx, fy, fz, body, u, v, depth, buttons, overrun, fault FROM samples ORDER BY tick";
  max_samples_ = max_samples;
  if (version_ >= 2) {
    reserve_hint_ = count_samples("SELECT total(count) FROM sample_blocks", max_samples);
    samples_query_.emplace(
        prepare("sample_blocks", "SELECT first_tick, count, data FROM sample_blocks ORDER BY first_tick"));
  } else {
    reserve_hint_ = count_samples("SELECT count(*) FROM samples", max_samples);
    samples_query_.emplace(prepare("samples", kColumns));
  }
}

bool Reader::read_more(std::vector<engine::Sample>& out) {
  if (!samples_query_) return false;
  bool at_end = false;
  const bool more = version_ >= 2 ? read_block(out) : read_rows(out, at_end);
  // Ended at once: stepping a finished query again would start it over.
  if (!more || at_end) end_transaction();
  return more;
}

// The samples were all read: the snapshot is no longer needed.
void Reader::end_transaction() {
  samples_query_.reset();
  std::string error;
  if (const int rc = detail::exec(db_, "COMMIT", error); rc != SQLITE_OK) fail_sqlite("file", rc);
}

// Format 1: rows in tick order, every column checked; `at_end` when the last was read.
bool Reader::read_rows(std::vector<engine::Sample>& out, bool& at_end) {
  sqlite3_stmt* query = samples_query_->get();
  Row row{file_, query, "samples", "tick"};
  const auto where_in_row = [&row](const char* column) { return row.where(column); };
  const auto max_body = static_cast<std::int64_t>(bodies_) - 1;
  int rows = 0;
  for (; rows < kRowsPerRead; ++rows) {
    const int rc = sqlite3_step(query);
    if (rc == SQLITE_DONE) {
      at_end = true;
      break;
    }
    if (rc != SQLITE_ROW) {
      fail_sqlite(previous_tick_ >= 0 ? fmt::format("samples after tick {}", previous_tick_) : "samples", rc);
    }
    row.key = sqlite3_column_int64(query, 0);
    row.integer(0, "tick", previous_tick_ + 1, kInt64Max);
    engine::Sample s;
    s.t = row.real(1, "t");
    check_time(s.t, previous_t_, where_in_row);
    s.position = {row.real(2, "x"), row.real(3, "y"), row.real(4, "z")};
    s.force = {row.real(5, "fx"), row.real(6, "fy"), row.real(7, "fz")};
    if (!row.is_null(8)) {
      if (max_body < 0) throw SessionError(file_, row.where("body"), "the case has no bodies");
      s.body = static_cast<std::int32_t>(row.integer(8, "body", 0, max_body));
      s.u = row.real(9, "u");
      s.v = row.real(10, "v");
      s.depth = row.real(11, "depth");
      check_contact(s, where_in_row);
    }
    s.buttons = static_cast<std::uint32_t>(row.integer(12, "buttons", 0, std::numeric_limits<std::uint32_t>::max()));
    s.overrun = row.integer(13, "overrun", 0, 1) != 0;
    s.fault = row.integer(14, "fault", 0, 1) != 0;
    previous_tick_ = row.key;
    previous_t_ = s.t;
    out.push_back(s);
  }
  read_ += rows;
  return rows > 0;
}

// Format 2: blocks in tick order, each decoded (sample_blocks.hpp) and its ticks checked
// like format 1's rows. A block's messages name it: "sample_blocks first_tick 2048: ...".
bool Reader::read_block(std::vector<engine::Sample>& out) {
  if (!step(*samples_query_, "sample_blocks")) return false;
  sqlite3_stmt* query = samples_query_->get();
  Row row{file_, query, "sample_blocks", "first_tick"};
  std::int64_t tick = 0;
  const auto where_in_block = [&](const char* column) {
    return fmt::format("sample_blocks first_tick {}: tick {}: column {}", row.key, tick, column);
  };
  row.key = sqlite3_column_int64(query, 0);
  const std::int64_t count = row.integer(1, "count", 1, detail::kMaxBlockTicks);
  if (read_ + count > max_samples_) {
    fail("sample_blocks", fmt::format("more samples than a session may hold ({})", max_samples_));
  }
  if (sqlite3_column_type(query, 2) != SQLITE_BLOB) fail(row.where("data"), "not a blob");
  const std::size_t first = out.size();
  ticks_.clear();
  try {
    detail::decode_block(sqlite3_column_blob(query, 2), static_cast<std::size_t>(sqlite3_column_bytes(query, 2)),
                         count, ticks_, out);
  } catch (const std::runtime_error& e) {
    fail(row.where(nullptr), e.what());
  }
  if (ticks_.front() != row.key) fail(row.where(nullptr), fmt::format("its first tick is {}", ticks_.front()));
  for (std::size_t k = 0; k < ticks_.size(); ++k) {
    tick = ticks_[k];
    auto& s = out[first + k];
    if (tick <= previous_tick_) fail(where_in_block("tick"), fmt::format("not after tick {}", previous_tick_));
    check_time(s.t, previous_t_, where_in_block);
    if (s.body >= 0) {
      if (static_cast<std::size_t>(s.body) >= bodies_) {
        fail(where_in_block("body"), fmt::format("the case has {} bodies, there is no body {}", bodies_, s.body));
      }
      check_contact(s, where_in_block);
    }
    previous_tick_ = tick;
    previous_t_ = s.t;
  }
  read_ += count;
  return true;
}

// The time of the first (or last) sample, read out of order and unchecked: nothing when it
// cannot be read. The checked reading in order (read_more) reports what is wrong; where it
// succeeds, the sample it ends with (or starts with) is this one, for ticks strictly increase.
std::optional<double> Reader::peek_time(bool last) {
  const char* order = last ? " DESC LIMIT 1" : " LIMIT 1";
  if (version_ < 2) {
    auto query = prepare("samples", (std::string("SELECT t FROM samples ORDER BY tick") + order).c_str());
    if (sqlite3_step(query.get()) != SQLITE_ROW) return std::nullopt;
    const int type = sqlite3_column_type(query.get(), 0);
    if (type != SQLITE_FLOAT && type != SQLITE_INTEGER) return std::nullopt;
    return sqlite3_column_double(query.get(), 0);
  }
  auto query = prepare("sample_blocks",
                       (std::string("SELECT count, data FROM sample_blocks ORDER BY first_tick") + order).c_str());
  if (sqlite3_step(query.get()) != SQLITE_ROW || sqlite3_column_type(query.get(), 1) != SQLITE_BLOB) return std::nullopt;
  std::vector<std::int64_t> ticks;
  std::vector<engine::Sample> samples;
  try {
    detail::decode_block(sqlite3_column_blob(query.get(), 1), static_cast<std::size_t>(sqlite3_column_bytes(query.get(), 1)),
                         sqlite3_column_int64(query.get(), 0), ticks, samples);
  } catch (const std::runtime_error&) {
    return std::nullopt;
  }
  return last ? samples.back().t : samples.front().t;
}

std::optional<SampleTimes> Reader::sample_times() {
  const auto first = peek_time(false);
  const auto last = peek_time(true);
  if (!first || !last) return std::nullopt;
  return SampleTimes{*first, *last};
}

Session Reader::read_head(const std::filesystem::path& path, const ReadOptions& options) {
  if (bytes_ != nullptr) {
    check_bytes();
    open_in_memory();
  } else {
    check_file(path);
    open();
  }
  // One read transaction for everything: a live session being written meanwhile is read
  // as one consistent snapshot (meta, events and samples of the same commit).
  std::string error;
  if (const int rc = detail::exec(db_, "BEGIN", error); rc != SQLITE_OK) fail_sqlite("file", rc);
  check_identity();
  read_format_version();
  check_tables();
  check_schema();
  Session session;
  read_meta(session);
  read_events(session);
  refuse_empty_without_wal(session);
  if (options.samples) {
    start_samples(options.max_samples);
  } else {
    end_transaction();  // without the samples: their table's columns were checked with the schema
  }
  return session;
}

}  // namespace

Session read_session(const std::filesystem::path& path, const ReadOptions& options) {
  Reader reader(path);
  Session session = reader.read_head(path, options);
  session.samples.reserve(static_cast<std::size_t>(reader.reserve_hint()));
  while (reader.read_more(session.samples)) {
  }
  return session;
}

struct SampleStream::Impl {
  explicit Impl(const std::filesystem::path& path) : reader(path) {}
  Impl(const std::string& bytes, const std::string& name) : reader(name, bytes) {}
  Reader reader;
  Session head;
  std::vector<engine::Sample> block;
  std::uint64_t count = 0;
};

SampleStream::SampleStream(const std::filesystem::path& path, std::int64_t max_samples)
    : impl_(std::make_unique<Impl>(path)) {
  ReadOptions options;
  options.max_samples = max_samples;
  impl_->head = impl_->reader.read_head(path, options);
}

SampleStream::SampleStream(const std::string& bytes, const std::string& name, std::int64_t max_samples)
    : impl_(std::make_unique<Impl>(bytes, name)) {
  ReadOptions options;
  options.max_samples = max_samples;
  impl_->head = impl_->reader.read_head(name, options);
}

SampleStream::~SampleStream() = default;

const Session& SampleStream::head() const { return impl_->head; }

std::span<const engine::Sample> SampleStream::next() {
  impl_->block.clear();  // capacity kept: one block's worth
  impl_->reader.read_more(impl_->block);
  impl_->count += impl_->block.size();
  return impl_->block;
}

std::uint64_t SampleStream::count() const { return impl_->count; }

std::uint64_t SampleStream::declared_count() const {
  return static_cast<std::uint64_t>(impl_->reader.declared_count());
}

std::optional<SampleTimes> SampleStream::sample_times() { return impl_->reader.sample_times(); }

}  // namespace palpa::session
