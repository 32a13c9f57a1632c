#include "palpa/io/json_text.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

#include <fmt/format.h>

namespace palpa::io {
namespace {

std::string position(std::string_view text, std::size_t offset) {
  std::size_t line = 1;
  std::size_t column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return fmt::format("line {}, column {}", line, column);
}

// A look at the text's structure before the parser builds anything: how deep arrays and
// objects nest, and roughly how many values there are (separators + containers), so
// hostile input can neither exhaust the stack nor make the parser allocate gigabytes.
std::optional<Problem> scan_structure(std::string_view text, int max_depth, std::size_t max_values) {
  int depth = 0;
  std::size_t values = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      ++values;
      if (++depth > max_depth) {
        return Problem{position(text, i), fmt::format("not accepted: nesting deeper than {} levels", max_depth)};
      }
    } else if (c == ']' || c == '}') {
      --depth;
    } else if (c == ',') {
      ++values;
    }
    if (values > max_values) {
      return Problem{position(text, i), fmt::format("not accepted: more than {} values", max_values)};
    }
  }
  return std::nullopt;
}

// nlohmann's messages start "[json.exception.parse_error.101] parse error at line 1, column 5: ";
// keep what follows the position.
std::string parser_reason(const char* what) {
  std::string s(what);
  const auto at = s.find("column ");
  if (at != std::string::npos) {
    const auto colon = s.find(": ", at);
    if (colon != std::string::npos) return s.substr(colon + 2);
  }
  const auto bracket = s.find("] ");
  return bracket == std::string::npos ? s : s.substr(bracket + 2);
}

}  // namespace

std::optional<Problem> read_text_file(const std::filesystem::path& path, std::uintmax_t max_bytes,
                                      std::string& out) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return Problem{"file", "no such file"};
  if (std::filesystem::is_directory(path, ec)) return Problem{"file", "is a folder, not a file"};
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return Problem{"file", "cannot read: " + ec.message()};
  if (size > max_bytes) {
    return Problem{"file", fmt::format("is {} bytes, more than the limit of {}", size, max_bytes)};
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return Problem{"file", std::string("cannot open: ") + std::strerror(errno)};
  out.assign(static_cast<std::size_t>(size), '\0');
  in.read(out.data(), static_cast<std::streamsize>(size));
  out.resize(static_cast<std::size_t>(in.gcount()));
  if (in.bad()) return Problem{"file", "read error"};
  return std::nullopt;
}

std::optional<Problem> parse_json_text(std::string_view text, int max_depth, std::size_t max_values,
                                       nlohmann::json& out) {
  if (auto problem = scan_structure(text, max_depth, max_values)) return problem;
  try {
    out = nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    return Problem{position(text, e.byte > 0 ? e.byte - 1 : 0), "not JSON: " + parser_reason(e.what())};
  } catch (const nlohmann::json::exception& e) {
    // Number overflow and the like carry no position: point at the offending token if we can.
    std::string reason = parser_reason(e.what());
    std::size_t offset = 0;
    if (const auto q = reason.find('\''); q != std::string::npos) {
      const auto q2 = reason.find('\'', q + 1);
      if (q2 != std::string::npos) offset = text.find(reason.substr(q + 1, q2 - q - 1));
    }
    return Problem{position(text, offset == std::string_view::npos ? 0 : offset), "not JSON: " + reason};
  }
  return std::nullopt;
}

void write_text_file_atomic(const std::filesystem::path& path, std::string_view text) {
  auto temp = path;
  temp += ".tmp";
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(path.string() + ": cannot write: " + std::strerror(errno));
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.flush();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(temp, ignored);
      throw std::runtime_error(path.string() + ": write failed (disk full?)");
    }
  }
  std::error_code ec;
  std::filesystem::rename(temp, path, ec);
  if (ec) {
    std::filesystem::remove(temp, ec);
    throw std::runtime_error(path.string() + ": cannot replace: " + ec.message());
  }
}

}  // namespace palpa::io
