#pragma once
// Numeric CSV files with a fixed header (probe points, parameter lists, trajectories).
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

namespace palpa::io {

/// A CSV file that cannot be used; what() is "FILE: line N: reason" (or "FILE: reason").
class CsvError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Larger files are refused before reading (an hour of 10 kHz samples fits comfortably).
inline constexpr std::uintmax_t kMaxCsvBytes = 4ull << 30;

struct NumericTable {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;  ///< one vector of columns.size() values per data line
  std::vector<std::size_t> line_numbers;  ///< the file line of each row, for later messages
};

/// Reads a CSV whose first line is exactly `header` (e.g. {"u", "v"}) and whose other
/// non-blank lines hold that many finite numbers. CRLF line ends are accepted.
NumericTable read_numeric_csv(const std::filesystem::path& path, const std::vector<std::string>& header);
/// The same from a stream; messages name `name` in place of the file.
NumericTable parse_numeric_csv(std::istream& in, const std::string& name, const std::vector<std::string>& header);

}  // namespace palpa::io
