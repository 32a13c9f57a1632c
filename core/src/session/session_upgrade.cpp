#include "palpa/session/session_upgrade.hpp"

#include <memory>
#include <stdexcept>
#include <string>

#include "compaction.hpp"
#include "file_claim.hpp"
#include "palpa/session/session.hpp"
#include "sqlite_util.hpp"

namespace palpa::session {
namespace {

struct CloseDb {
  void operator()(sqlite3* db) const { sqlite3_close_v2(db); }
};
using DbOwner = std::unique_ptr<sqlite3, CloseDb>;

DbOwner open_db(const std::filesystem::path& path, int flags, const std::string& file) {
  sqlite3* raw = nullptr;
  const int rc = sqlite3_open_v2(path.c_str(), &raw, flags | SQLITE_OPEN_NOMUTEX, nullptr);
  DbOwner db(raw);
  if (rc != SQLITE_OK) throw SessionError(file, "file", raw != nullptr ? sqlite3_errmsg(raw) : "cannot open");
  sqlite3_busy_timeout(raw, 2000);
  return db;
}

// Every page of `from` (one read snapshot, with its -wal if it has one) into the empty `to`,
// which then uses a rollback journal whatever `from` used.
void copy_pages(sqlite3* from, sqlite3* to, const std::string& to_file) {
  sqlite3_backup* backup = sqlite3_backup_init(to, "main", from, "main");
  if (backup == nullptr) throw SessionError(to_file, "file", sqlite3_errmsg(to));
  const int rc = sqlite3_backup_step(backup, -1);
  sqlite3_backup_finish(backup);
  if (rc != SQLITE_DONE) throw SessionError(to_file, "file", sqlite3_errstr(rc));
  if (detail::query_text(to, "PRAGMA journal_mode=DELETE") != "delete") {
    throw SessionError(to_file, "file", "cannot leave write-ahead logging");
  }
}

void remove_with_journals(const std::filesystem::path& path) {
  std::error_code ec;
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) {
    auto p = path;
    p += suffix;
    std::filesystem::remove(p, ec);
  }
}

}  // namespace

std::optional<long> process_holding(const std::filesystem::path& path) {
  auto shm = path;
  shm += "-shm";
  return detail::other_process_locking(shm);
}

void write_compacted_copy(const std::filesystem::path& from, const std::filesystem::path& to) {
  const std::string from_file = from.string();
  const std::string to_file = to.string();
  const DbOwner source = open_db(from, SQLITE_OPEN_READONLY, from_file);
  std::string version;
  try {
    version = detail::query_text(source.get(), "SELECT value FROM meta WHERE key = 'format_version'");
  } catch (const std::runtime_error& e) {
    throw SessionError(from_file, "meta format_version", e.what());
  }
  if (version != "1") throw SessionError(from_file, "meta format_version", "format " + version + ", not 1");
  detail::create_exclusive(to);
  try {
    const DbOwner target = open_db(to, SQLITE_OPEN_READWRITE, to_file);
    copy_pages(source.get(), target.get(), to_file);
    try {
      detail::compact_samples(target.get());  // a VACUUM that fails leaves a larger, correct file
    } catch (const std::runtime_error& e) {
      throw SessionError(from_file, "samples", e.what());
    }
  } catch (...) {
    remove_with_journals(to);
    throw;
  }
}

}  // namespace palpa::session
