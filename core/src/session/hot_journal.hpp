#pragma once
// A rollback journal left beside a session. Palpa writes rollback-journal transactions into
// a named session only when finish() switches it out of write-ahead logging: after a full
// checkpoint, that transaction rewrites page 1 alone (its format bytes). A process killed
// during the switch leaves a hot journal holding just page 1; every data page is already
// whole in the main file. A read-only reader cannot roll the journal back (SQLite refuses
// with SQLITE_READONLY), but it can read the main file as it is.
// Journal layout: https://www.sqlite.org/fileformat2.html#the_rollback_journal
#include <filesystem>

namespace palpa::session::detail {

enum class JournalBeside {
  None,              ///< no journal, or one SQLite would not roll back (empty, zeroed header)
  HeaderSwitchOnly,  ///< a hot journal of page 1 alone: the interrupted switch described above
  Transaction,       ///< a hot journal of other pages: an interrupted write of data
};

/// What lies at `file`-journal.
JournalBeside journal_beside(const std::filesystem::path& file);

/// "file:" URI of `path` (percent-encoded) with `query`, for sqlite3_open_v2 with SQLITE_OPEN_URI.
std::string sqlite_uri(const std::filesystem::path& path, const char* query);

}  // namespace palpa::session::detail
