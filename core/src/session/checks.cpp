#include "checks.hpp"

#include <cmath>

#include <fmt/format.h>

#include "palpa/session/session_writer.hpp"
#include "sqlite_util.hpp"

namespace palpa::session {
namespace detail {

bool valid_utf8(std::string_view text) {
  std::size_t i = 0;
  const std::size_t n = text.size();
  while (i < n) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x80) {
      ++i;
      continue;
    }
    std::size_t length = 0;
    std::uint32_t code = 0;
    std::uint32_t min = 0;
    if ((c & 0xE0) == 0xC0) {
      length = 2;
      code = c & 0x1F;
      min = 0x80;
    } else if ((c & 0xF0) == 0xE0) {
      length = 3;
      code = c & 0x0F;
      min = 0x800;
    } else if ((c & 0xF8) == 0xF0) {
      length = 4;
      code = c & 0x07;
      min = 0x10000;
    } else {
      return false;  // a continuation byte first, or 0xF8..0xFF
    }
    if (n - i < length) return false;
    for (std::size_t k = 1; k < length; ++k) {
      const auto next = static_cast<unsigned char>(text[i + k]);
      if ((next & 0xC0) != 0x80) return false;
      code = (code << 6) | (next & 0x3F);
    }
    if (code < min || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return false;
    i += length;
  }
  return true;
}

void check_utf8(const std::string& file, const std::string& where, std::string_view text) {
  if (!valid_utf8(text)) throw SessionError(file, where, "not valid UTF-8 text (other programs could not read it)");
}

std::string dump_json(const std::string& file, const std::string& where, const nlohmann::json& value) {
  try {
    return value.dump();
  } catch (const nlohmann::json::exception&) {
    // type_error 316: a string in it is not UTF-8 (the only way dump() fails).
    throw SessionError(file, where, "holds a string that is not valid UTF-8 text");
  }
}

}  // namespace detail

void check_event(const std::string& file, const Event& e) {
  std::string where = "events ";
  where += to_string(e.kind);
  where += " at t=";
  where += detail::exact_text(e.t);
  if (!std::isfinite(e.t)) throw SessionError(file, where, "the time is not a finite number");
  const bool has_mark = e.kind == EventKind::Mark || e.kind == EventKind::Unmark;
  if (has_mark && e.mark < 1) {
    throw SessionError(file, where, fmt::format("a mark id must be >= 1, not {}", e.mark));
  }
  if (e.kind == EventKind::Mark) {
    for (double x : e.position) {
      if (!std::isfinite(x)) throw SessionError(file, where, "the mark's position is not finite");
    }
  }
  detail::check_utf8(file, where + ": note", e.note);
}

}  // namespace palpa::session
