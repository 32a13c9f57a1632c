#pragma once
// What the writer checks before anything reaches the file (text encodings, JSON), shared
// by the writer and the recorder. Internal to core/session.
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace palpa::session::detail {

/// True when `text` is well-formed UTF-8 (no overlong forms, surrogates or values above
/// U+10FFFF): what Python's sqlite3 module and every JSON reader require of TEXT.
bool valid_utf8(std::string_view text);

/// Throws SessionError(file, where, ...) when `text` is not valid UTF-8.
void check_utf8(const std::string& file, const std::string& where, std::string_view text);

/// The JSON as text; a string in it that is not valid UTF-8 is a SessionError at `where`.
std::string dump_json(const std::string& file, const std::string& where, const nlohmann::json& value);

}  // namespace palpa::session::detail
