#pragma once
// Converting format-1 session files (one SQLite row per tick) into format 2 (compact sample
// blocks; docs/session-format.md, "Version 2"). `palpa-cli session upgrade` drives it and
// checks the copy before it replaces anything.
#include <filesystem>
#include <optional>

namespace palpa::session {

/// The id of another process that has the session at `path` open in write-ahead-log mode
/// (a lock on its -shm: a recording in progress, or a reader of a live file); empty when
/// none does or it cannot be told (Linux /proc/locks).
std::optional<long> process_holding(const std::filesystem::path& path);

/// Writes to `to` (which must not exist) a format-2 copy of the format-1 session `from`:
/// meta (format_version 2) and events as they are, the samples compacted into blocks.
/// `from` is only read. Throws SessionError naming `from` (not a format-1 session, a value
/// that does not fit format 2's units) or `to` (cannot be created or written); nothing is
/// left at `to` then. The copy is not checked against the original: read both to do that.
void write_compacted_copy(const std::filesystem::path& from, const std::filesystem::path& to);

}  // namespace palpa::session
