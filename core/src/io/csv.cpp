#include "palpa/io/csv.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <istream>

#include <fmt/format.h>

namespace palpa::io {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == ',') {
      out.emplace_back();
    } else {
      out.back().push_back(c);
    }
  }
  for (auto& s : out) {
    const auto b = s.find_first_not_of(" \t");
    const auto e = s.find_last_not_of(" \t");
    s = b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  }
  return out;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + v[i];
  return s;
}

}  // namespace

NumericTable read_numeric_csv(const std::filesystem::path& path, const std::vector<std::string>& header) {
  const std::string name = path.string();
  std::error_code fs_error;
  if (!std::filesystem::is_regular_file(path, fs_error)) {
    throw CsvError(name + (std::filesystem::exists(path, fs_error) ? ": not a regular file"
                                                                   : ": cannot open (no such file)"));
  }
  if (std::filesystem::file_size(path, fs_error) > kMaxCsvBytes) {
    throw CsvError(fmt::format("{}: larger than {} MiB", name, kMaxCsvBytes >> 20));
  }
  std::ifstream in(path);
  if (!in) throw CsvError(name + ": cannot open (not readable)");
  return parse_numeric_csv(in, name, header);
}

NumericTable parse_numeric_csv(std::istream& in, const std::string& name, const std::vector<std::string>& header) {
  NumericTable table;
  table.columns = header;
  std::string line;
  std::size_t number = 0;
  bool have_header = false;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    const auto fields = split(line);
    if (!have_header) {
      if (fields != header) {
        throw CsvError(
            fmt::format("{}: line {}: header must be \"{}\", got \"{}\"", name, number, joined(header), line));
      }
      have_header = true;
      continue;
    }
    if (fields.size() != header.size()) {
      throw CsvError(
          fmt::format("{}: line {}: expected {} values, got {}", name, number, header.size(), fields.size()));
    }
    std::vector<double> row(fields.size());
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const auto& f = fields[c];
      const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), row[c]);
      if (f.empty() || ec != std::errc() || end != f.data() + f.size() || !std::isfinite(row[c])) {
        throw CsvError(
            fmt::format("{}: line {}: column {}: \"{}\" is not a finite number", name, number, header[c], f));
      }
    }
    table.rows.push_back(std::move(row));
    table.line_numbers.push_back(number);
  }
  if (in.bad()) throw CsvError(name + ": read error");
  if (!have_header) throw CsvError(name + ": empty file (expected the header \"" + joined(header) + "\")");
  return table;
}

}  // namespace palpa::io
