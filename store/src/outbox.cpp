#include "palpa/store/outbox.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <ctime>
#include <fstream>
#include <tuple>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "palpa/report/printable.hpp"
#include "palpa/session/session_id.hpp"
#include "palpa/store/session_checks.hpp"
#include "palpa/store/sha256.hpp"

namespace palpa::store {
namespace {

namespace fs = std::filesystem;

std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

fs::path meta_path(const fs::path& file) {
  auto p = file;
  p.replace_extension(".json");
  return p;
}

// Writes all of `text` to a new file `tmp` (O_EXCL | O_NOFOLLOW: never through a link or
// over a file someone put there); false on any failure, with nothing left behind.
bool write_new_file(const fs::path& tmp, const std::string& text) {
  const int fd = open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) return false;
  std::size_t done = 0;
  while (done < text.size()) {
    const auto n = write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  const bool whole = done == text.size() && fsync(fd) == 0;
  if (close(fd) != 0 || !whole) {
    std::error_code ec;
    fs::remove(tmp, ec);  // a partial copy would keep a full disk full
    return false;
  }
  return true;
}

// Writes `text` to `path` through a temporary file renamed into place.
void write_atomically(const fs::path& path, const std::string& text) {
  const auto tmp = path.parent_path() / fmt::format(".{}.{}.tmp", path.filename().string(), getpid());
  std::error_code ec;
  if (fs::is_symlink(tmp, ec)) fs::remove(tmp, ec);  // a leftover link is removed, never followed
  if (!write_new_file(tmp, text)) {
    throw StoreError(fmt::format("{}: outbox: cannot write (disk full, or a file in the way)", path.string()), false);
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw StoreError(fmt::format("{}: outbox: cannot write: {}", path.string(), ec.message()), false);
  }
}

void write_meta(const OutboxEntry& e) {
  const nlohmann::json j{{"source", e.source},         {"session_id", e.session_id}, {"trainee", e.trainee},
                         {"started_at", e.started_at}, {"size", e.size},             {"queued_at", e.queued_at},
                         {"attempts", e.attempts},     {"last_error", e.last_error}};
  write_atomically(meta_path(e.file), j.dump(2) + "\n");
}

OutboxEntry read_entry(const fs::path& file) {
  OutboxEntry e;
  e.file = file;
  std::error_code ec;
  e.size = fs::file_size(file, ec);
  try {
    std::ifstream in(meta_path(file));
    const auto j = nlohmann::json::parse(in);
    e.source = j.value("source", "");
    e.session_id = j.value("session_id", "");
    e.trainee = j.value("trainee", "");
    e.started_at = j.value("started_at", "");
    e.queued_at = j.value("queued_at", "");
    e.attempts = j.value("attempts", 0);
    e.last_error = j.value("last_error", "");
  } catch (const nlohmann::json::exception& x) {
    e.last_error = fmt::format("{}: unreadable: {}", meta_path(file).string(), x.what());
  }
  return e;
}

}  // namespace

fs::path queued_file(const fs::path& outbox, const std::string& session_id) {
  if (!session::is_session_id(session_id)) {
    throw StoreError(fmt::format("outbox: \"{}\" is no session id: not queued", report::printable(session_id, 40)),
                     false);
  }
  return outbox / (session_id + ".palpa");
}

bool is_queued(const fs::path& outbox, const PreparedSession& s) {
  const auto file = queued_file(outbox, s.session_id);
  std::error_code ec;
  if (!fs::exists(file, ec) && !fs::is_symlink(file, ec)) return false;
  if (fs::is_symlink(file, ec) || sha256_hex(read_file_bytes(file)) != s.sha256) {
    throw StoreError(fmt::format("{}: outbox: {} already holds another session with this id; not queued",
                                 report::printable(s.path.string(), 200), file.string()),
                     false);
  }
  return true;
}

OutboxEntry queue_session(const fs::path& outbox, const PreparedSession& s, const std::string& error) {
  check_pushable(s);  // its id becomes the file name: only a session the store would take
  std::error_code ec;
  fs::create_directories(outbox, ec);
  if (ec) throw StoreError(fmt::format("{}: outbox: cannot create: {}", outbox.string(), ec.message()), false);
  const auto file = queued_file(outbox, s.session_id);
  if (is_queued(outbox, s)) {
    auto e = read_entry(file);
    record_attempt(e, error);
    return read_entry(file);
  }
  write_atomically(file, s.bytes);  // the bytes already checksummed, not a new read
  OutboxEntry e{file, fs::absolute(s.path, ec).string(), s.session_id, s.trainee, s.started_at, now_utc(), error,
                s.bytes.size(), 1};
  try {
    write_meta(e);
  } catch (const StoreError&) {
    fs::remove(file, ec);  // not queued after all: no copy without its record
    throw;
  }
  return e;
}

std::vector<OutboxEntry> list_outbox(const fs::path& outbox) {
  std::vector<OutboxEntry> entries;
  std::error_code ec;
  for (fs::directory_iterator it(outbox, ec), end; !ec && it != end; it.increment(ec)) {
    const auto& p = it->path();
    if (p.extension() == ".palpa" && p.filename().string().front() != '.') entries.push_back(read_entry(p));
  }
  std::sort(entries.begin(), entries.end(), [](const OutboxEntry& a, const OutboxEntry& b) {
    return std::tie(a.queued_at, a.file) < std::tie(b.queued_at, b.file);
  });
  return entries;
}

void record_attempt(const OutboxEntry& entry, const std::string& error) {
  auto e = entry;
  e.attempts += 1;
  e.last_error = error;
  write_meta(e);
}

void remove_entry(const OutboxEntry& entry) {
  std::error_code ec;
  fs::remove(meta_path(entry.file), ec);
  fs::remove(entry.file, ec);
}

void mark_unreachable(const fs::path& outbox, const std::string& error) {
  for (const auto& e : list_outbox(outbox)) record_attempt(e, error);
}

FlushResult flush_outbox(Connection& c, const fs::path& outbox, const std::string& station) {
  FlushResult r;
  bool broken = false;
  for (const auto& e : list_outbox(outbox)) {
    if (broken) {
      ++r.waiting;
      continue;
    }
    try {
      auto session = prepare_session(e.file);
      if (!e.source.empty()) session.file_name = fs::path(e.source).filename().string();
      push_prepared(c, session, station);
      remove_entry(e);
      ++r.sent;
    } catch (const StoreError& x) {
      record_attempt(e, x.what());
      r.errors.push_back(fmt::format("{} (from {}): {}", e.file.string(), e.source, x.what()));
      ++r.waiting;
      broken = x.unreachable();
    }
  }
  return r;
}

}  // namespace palpa::store
