#pragma once
// Small encodings the reports need: base64 (images inside self-contained HTML), SHA-1 and
// name-based UUIDs (RFC 4122 version 5: the xAPI statement id derived from the session id),
// HTML escaping and RFC 4180 CSV fields.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace palpa::report {

/// Standard base64 (RFC 4648, alphabet A-Z a-z 0-9 + /, '=' padding, no line breaks).
std::string base64(std::span<const std::uint8_t> bytes);
std::string base64(std::string_view bytes);

/// SHA-1 digest (FIPS 180-4). Used for ids, not for security.
std::array<std::uint8_t, 20> sha1(std::string_view bytes);

/// RFC 4122 name-based UUID, version 5 (SHA-1), lower-case 8-4-4-4-12 text.
/// `name_space` is the namespace UUID in the same text form; throws std::invalid_argument
/// if it is not one.
std::string uuid_v5(std::string_view name_space, std::string_view name);

/// The namespace of Palpa's statement ids: uuid_v5(URL namespace, "urn:palpa").
inline constexpr std::string_view kPalpaNamespace = "2bb29d3e-4f5a-5c29-9df1-d089ca901658";

/// Text safe inside HTML elements and quoted attributes: & < > " ' escaped.
std::string html_escape(std::string_view text);

/// One CSV field of text (RFC 4180): quoted when it holds a comma, a quote, CR or LF, with
/// inner quotes doubled; otherwise as is. Text a spreadsheet would run as a formula (a
/// leading =, +, -, @, tab or CR) is quoted with a ' before it (OWASP, "CSV Injection",
/// https://owasp.org/www-community/attacks/CSV_Injection). Numbers go through number_text.
std::string csv_field(std::string_view text);

/// A number for CSV and text: the shortest form that reads back to the same double;
/// empty for NaN and infinities.
std::string number_text(double value);

}  // namespace palpa::report
