#pragma once
// Checks for the numeric options of palpa and palpa-cli (CLI11 validators). Every number
// must be finite and in a human-sized range, and says so in its message and help text:
// CLI11's own Range and PositiveNumber let "nan" through (every comparison with NaN is
// false) and print bounds such as 1.79769e+308.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

namespace palpa::options {

namespace detail {

// The whole of `text` as a finite double, or NaN.
inline double parse_finite(const std::string& text) {
  if (text.empty()) return std::nan("");
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(x)) return std::nan("");
  return x;
}

}  // namespace detail

/// A finite number in [lo, hi]; `unit` (e.g. "s", "N") follows the bounds in the messages.
inline CLI::Validator finite_in(double lo, double hi, const std::string& unit = "") {
  const std::string range = fmt::format("{:g} to {:g}{}", lo, hi, unit.empty() ? "" : " " + unit);
  return CLI::Validator(
      [lo, hi, range](std::string& text) {
        const double x = detail::parse_finite(text);
        if (std::isnan(x)) return "'" + text + "' is not a finite number (expected " + range + ")";
        if (x < lo || x > hi) return text + " is out of range: expected " + range;
        return std::string();
      },
      "in [" + range + "]");
}

/// A finite number above 0 and at most hi.
inline CLI::Validator finite_positive(double hi, const std::string& unit = "") {
  const std::string range = fmt::format("above 0, at most {:g}{}", hi, unit.empty() ? "" : " " + unit);
  return CLI::Validator(
      [hi, range](std::string& text) {
        const double x = detail::parse_finite(text);
        if (std::isnan(x)) return "'" + text + "' is not a finite number (expected " + range + ")";
        if (!(x > 0.0) || x > hi) return text + " is out of range: expected " + range;
        return std::string();
      },
      range);
}

/// An integer in [lo, hi], written in decimal digits only (no sign beyond a leading '-', no
/// exponent, no fraction).
inline CLI::Validator integer_in(long long lo, long long hi) {
  const std::string range = fmt::format("{} to {}", lo, hi);
  return CLI::Validator(
      [lo, hi, range](std::string& text) {
        long long x = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), x);
        if (error == std::errc::result_out_of_range) return text + " is out of range: expected " + range;
        if (error != std::errc() || end != text.data() + text.size()) {
          return "'" + text + "' is not a whole number (expected " + range + ")";
        }
        if (x < lo || x > hi) return text + " is out of range: expected " + range;
        return std::string();
      },
      "in [" + range + "]");
}

/// A seed: a whole number 0 to 2^64 - 1 (18446744073709551615), decimal digits only.
inline CLI::Validator seed_value() {
  return CLI::Validator(
      [](std::string& text) {
        std::uint64_t x = 0;
        const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), x);
        if (digits && error == std::errc::result_out_of_range) {
          return text + " is out of range: a seed is 0 to 18446744073709551615 (2^64 - 1)";
        }
        if (!digits || error != std::errc() || end != text.data() + text.size()) {
          return "'" + text + "' is not a seed: expected a whole number 0 to 18446744073709551615 (2^64 - 1)";
        }
        return std::string();
      },
      "0 to 2^64 - 1");
}

}  // namespace palpa::options
