#include "palpa/report/printable.hpp"

#include <fmt/format.h>

namespace palpa::report {
namespace {

// One UTF-8 sequence at `i`: its code point and length; length 0 when invalid (overlong,
// surrogate, past U+10FFFF, or cut short).
std::pair<char32_t, std::size_t> decode(std::string_view s, std::size_t i) {
  const auto b0 = static_cast<unsigned char>(s[i]);
  if (b0 < 0x80) return {b0, 1};
  std::size_t n = 0;
  char32_t cp = 0, min = 0;
  if ((b0 & 0xE0) == 0xC0) { n = 2; cp = b0 & 0x1F; min = 0x80; }
  else if ((b0 & 0xF0) == 0xE0) { n = 3; cp = b0 & 0x0F; min = 0x800; }
  else if ((b0 & 0xF8) == 0xF0) { n = 4; cp = b0 & 0x07; min = 0x10000; }
  else return {0, 0};
  if (i + n > s.size()) return {0, 0};
  for (std::size_t k = 1; k < n; ++k) {
    const auto b = static_cast<unsigned char>(s[i + k]);
    if ((b & 0xC0) != 0x80) return {0, 0};
    cp = (cp << 6) | (b & 0x3F);
  }
  if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return {0, 0};
  return {cp, n};
}

// Controls, bidirectional controls, the invisible characters (Unicode's
// Default_Ignorable_Code_Point, DerivedCoreProperties.txt), the other format characters
// (Arabic number signs, Egyptian hieroglyph format controls) and the blank braille
// pattern U+2800, which renders as nothing: shown by code point.
bool hidden(char32_t cp) {
  struct Range {
    char32_t first, last;
  };
  static constexpr Range kHidden[] = {
      {0x00, 0x1F},       {0x7F, 0x9F},     {0xAD, 0xAD},     {0x34F, 0x34F},   {0x61C, 0x61C},
      {0x115F, 0x1160},   {0x17B4, 0x17B5}, {0x180B, 0x180F}, {0x200B, 0x200F}, {0x2028, 0x202E},
      {0x2060, 0x206F},   {0x3164, 0x3164}, {0xFE00, 0xFE0F}, {0xFEFF, 0xFEFF}, {0xFFA0, 0xFFA0},
      {0xFFF0, 0xFFFB},   {0x600, 0x605},   {0x6DD, 0x6DD},   {0x70F, 0x70F},   {0x8E2, 0x8E2},
      {0x2800, 0x2800},   {0x110BD, 0x110BD}, {0x110CD, 0x110CD}, {0x13430, 0x1343F}, {0x1BCA0, 0x1BCA3},
      {0x1D173, 0x1D17A}, {0xE0000, 0xE0FFF}};
  for (const auto& r : kHidden) {
    if (cp >= r.first && cp <= r.last) return true;
  }
  return false;
}

}  // namespace

std::string printable(std::string_view text, std::size_t max_chars) {
  std::string out;
  std::size_t chars = 0;
  for (std::size_t i = 0; i < text.size();) {
    if (chars == max_chars) {
      out += "\u2026";
      break;
    }
    const auto [cp, n] = decode(text, i);
    if (n == 0) {
      out += fmt::format("\\x{:02x}", static_cast<unsigned char>(text[i]));
      i += 1;
    } else {
      if (!hidden(cp)) out.append(text.substr(i, n));
      else if (cp < 0x100) out += fmt::format("\\x{:02x}", static_cast<unsigned>(cp));
      else out += fmt::format("\\u{{{:04x}}}", static_cast<unsigned>(cp));
      i += n;
    }
    ++chars;
  }
  return out;
}

bool is_printable(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const auto [cp, n] = decode(text, i);
    if (n == 0 || hidden(cp)) return false;
    i += n;
  }
  return true;
}

}  // namespace palpa::report
