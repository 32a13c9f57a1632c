#pragma once
// The text headers of NRRD and MetaImage (internal): bounded reading and "key: value" lines.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "common.hpp"

namespace palpa::anatomy_io::detail {

/// The most header text read: 1 MiB.
inline constexpr std::size_t kMaxHeaderBytes = std::size_t{1} << 20;

/// The first min(file size, kMaxHeaderBytes) bytes of a file.
std::string read_head(const fs::path& file, std::uintmax_t file_size);

/// Splits text into lines (without "\r\n" or "\n"), stopping after `max_lines`.
std::vector<std::string> split_lines(const std::string& text);

/// The value of (key, value) pairs for a lower-case key; nullptr when absent.
const std::string* find_field(const std::vector<std::pair<std::string, std::string>>& fields, const std::string& key);

/// The directory-relative path of a detached data file, refusing anything but a plain name
/// or relative path.
fs::path detached_path(const fs::path& header, const std::string& field, const std::string& name);

}  // namespace palpa::anatomy_io::detail
