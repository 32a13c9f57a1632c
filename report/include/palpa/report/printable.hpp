#pragma once
// Untrusted text (ids, names, trainees from session files or the store) made safe to show:
// on a terminal an ESC could clear the screen or fake colours, a bidirectional override
// could reorder what a reader sees (Trojan Source, CVE-2021-42574), a NUL could end the
// text early. JSON keeps the exact value; this is for terminals, logs and layout.
#include <cstddef>
#include <string>
#include <string_view>

namespace palpa::report {

/// `text` with control characters (C0, DEL, C1), NUL, bidirectional controls (U+061C,
/// U+200E/F, U+202A-202E, U+2066-2069), line/paragraph separators, invisible characters
/// (zero-width spaces and joiners, U+FEFF, soft hyphen, Hangul fillers, variation selectors,
/// tags: Unicode's default-ignorable code points) and invalid UTF-8 written as \xNN or
/// \u{XXXX}; longer than `max_chars` code points, shortened with "…" at the end.
std::string printable(std::string_view text, std::size_t max_chars = 120);

/// True when printable(text, any size) would change nothing: plain text to show as it is.
bool is_printable(std::string_view text);

}  // namespace palpa::report
