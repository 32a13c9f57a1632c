#pragma once
// Where the windows record sessions: $XDG_DATA_HOME/palpa/sessions, else
// ~/.local/share/palpa/sessions, and a fresh file name there that never overwrites.
#include <filesystem>
#include <string>

namespace palpa::ui {

/// The sessions folder (not created here).
std::filesystem::path sessions_dir();
/// Where the instructor's "Try it" records: sessions_dir()/try-it, apart from the
/// trainees' sessions (a test-run of a case is not an exercise to review or upload).
std::filesystem::path try_it_sessions_dir();
/// The time now in UTC as 20261122T213000Z (file names).
std::string utc_stamp();
/// DIR/PREFIX-UTCSTAMP.palpa, or with -2, -3 ... when that file exists already (two
/// exercises started in the same second).
std::filesystem::path new_session_path(const std::filesystem::path& dir, const std::string& prefix);

}  // namespace palpa::ui
