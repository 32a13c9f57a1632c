#pragma once
// Claiming a session file's name. A new session is built under a hidden name beside its
// final one (".NAME.PID.creating") and given its name only once its schema and header are
// committed, so that a process killed while creating leaves nothing under NAME: the next
// run with the same name is not blocked. The name is given without replacing anything
// (renameat2 RENAME_NOREPLACE, or link + unlink): of two writers racing for one name,
// exactly one gets it and the other is told so.
#include <filesystem>
#include <optional>

namespace palpa::session::detail {

/// Throws SessionError (where "file") when `path` cannot become a new session: it exists
/// (saying so when another process has it open, with that process's id), a -wal or
/// -journal of an earlier session lies beside it, or its folder does not exist.
void refuse_taken_name(const std::filesystem::path& path);

/// The hidden sibling a new session of `path` is built under by this process.
std::filesystem::path creating_path(const std::filesystem::path& path);

/// Removes the hidden siblings (and their journals) that creations of `path` by processes
/// that no longer run left behind. Best effort: what cannot be removed stays.
void remove_abandoned_creations(const std::filesystem::path& path);

/// Creates `path` empty with O_EXCL; SessionError when it exists or cannot be made.
void create_exclusive(const std::filesystem::path& path);

/// Gives the finished file `built` the name `path`, never replacing a file that appeared
/// there meanwhile (then SessionError, and `built` is left for the caller to remove).
void publish(const std::filesystem::path& built, const std::filesystem::path& path);

/// The id of another process holding a POSIX or flock lock on `file` (SQLite holds one on
/// a WAL session's -shm while it has the session open), from Linux's /proc/locks; empty
/// when there is none or it cannot be told.
std::optional<long> other_process_locking(const std::filesystem::path& file);

}  // namespace palpa::session::detail
