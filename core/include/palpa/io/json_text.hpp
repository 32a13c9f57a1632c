#pragma once
// Guarded reading and writing of JSON text: limits first, then the parser.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "palpa/io/case_file.hpp"

namespace palpa::io {

/// Reads a whole file if it is no larger than max_bytes. Returns the problem otherwise
/// (missing, unreadable, too large), with `where` set to "file".
std::optional<Problem> read_text_file(const std::filesystem::path& path, std::uintmax_t max_bytes,
                                      std::string& out);

/// Parses JSON after checking on the text that arrays and objects nest no deeper than
/// max_depth and that it holds at most about max_values values (so hostile input can
/// neither exhaust the stack nor the memory). Syntax errors come back as
/// { "line L, column C", "not JSON: ..." }.
std::optional<Problem> parse_json_text(std::string_view text, int max_depth, std::size_t max_values,
                                       nlohmann::json& out);

/// Writes text to path through a temporary file in the same folder and a rename, so the
/// target is either the old or the new content, never a mix. Throws std::runtime_error.
void write_text_file_atomic(const std::filesystem::path& path, std::string_view text);

}  // namespace palpa::io
