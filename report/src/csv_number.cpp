#include "palpa/report/csv_number.hpp"

#include <cmath>

#include <fmt/format.h>

namespace palpa::report {

int csv_decimals(CsvUnit unit) {
  switch (unit) {
    case CsvUnit::Millimetre: return 1;
    case CsvUnit::Newton: return 2;
    case CsvUnit::Second: return 2;
    case CsvUnit::Fraction: return 3;
    case CsvUnit::Ratio: return 2;
    case CsvUnit::Score100: return 1;
    case CsvUnit::Cusum: return 2;
  }
  return 3;
}

std::string csv_number(double value, CsvUnit unit) {
  if (!std::isfinite(value)) return {};
  std::string text = fmt::format("{:.{}f}", value, csv_decimals(unit));
  // -0.04 mm to 0.1 mm prints "-0.0": a sign on zero only confuses a reader or a diff.
  if (text.front() == '-' && text.find_first_not_of("-0.") == std::string::npos) text.erase(0, 1);
  return text;
}

}  // namespace palpa::report
