#include "text_header.hpp"

#include <fmt/format.h>

#include <fstream>

namespace palpa::anatomy_io::detail {

std::string read_head(const fs::path& file, std::uintmax_t file_size) {
  const std::size_t n = file_size < kMaxHeaderBytes ? static_cast<std::size_t>(file_size) : kMaxHeaderBytes;
  std::string text(n, '\0');
  std::ifstream in(file, std::ios::binary);
  if (!in) fail(file, "file", "cannot be opened");
  in.read(text.data(), static_cast<std::streamsize>(n));
  text.resize(static_cast<std::size_t>(in.gcount()));
  return text;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(std::move(line));
    start = end + 1;
  }
  return lines;
}

const std::string* find_field(const std::vector<std::pair<std::string, std::string>>& fields, const std::string& key) {
  for (const auto& [k, v] : fields) {
    if (k == key) return &v;
  }
  return nullptr;
}

fs::path detached_path(const fs::path& header, const std::string& field, const std::string& name) {
  if (name.empty()) fail(header, field, "names no data file");
  // Only a file beside the header, as 3D Slicer and ITK write them: a header is untrusted,
  // and a path of its choosing could make Palpa read any file, or a pipe that never ends.
  if (name.find_first_of("/\\") != std::string::npos || name == "." || name == "..") {
    fail(header, field, "the data file must be a file beside the header (a name without folders)");
  }
  const fs::path resolved = header.parent_path() / name;
  std::error_code error;
  if (!fs::is_regular_file(resolved, error)) fail(header, field, "the data file beside the header is missing or not a regular file");
  checked_file_size(resolved);
  return resolved;
}

}  // namespace palpa::anatomy_io::detail
