#include "palpa/io/data_paths.hpp"

#include <algorithm>
#include <iterator>
#include <cstdlib>
#include <system_error>

namespace palpa::io {
namespace {

namespace fs = std::filesystem;

bool holds_cases(const fs::path& dir) {
  std::error_code ec;
  return fs::is_directory(dir / "cases", ec);
}

/// Whether `inner` is `outer` or lies below it (both made absolute and free of symlinks
/// as far as they exist).
bool is_inside(const fs::path& inner, const fs::path& outer) {
  std::error_code ec;
  const fs::path a = fs::weakly_canonical(inner, ec);
  if (ec) return false;
  const fs::path b = fs::weakly_canonical(outer, ec);
  if (ec || b.empty()) return false;
  const auto [in_b, in_a] = std::mismatch(b.begin(), b.end(), a.begin(), a.end());
  // A trailing separator of `outer` shows up as one empty element.
  return in_b == b.end() || (std::next(in_b) == b.end() && in_b->empty());
}

std::string with_json_extension(const std::string& name) {
  return fs::path(name).extension() == ".json" ? name : name + ".json";
}

}  // namespace

std::vector<fs::path> data_dir_candidates(const DataSearch& search) {
  if (search.env_dir) return {*search.env_dir};
  std::vector<fs::path> out;
  if (!search.executable.empty()) {
    out.push_back((search.executable.parent_path() / ".." / "share" / "palpa").lexically_normal());
  }
  if (search.build_tree_data) out.push_back(*search.build_tree_data);
  return out;
}

fs::path find_data_dir(const DataSearch& search) {
  const auto candidates = data_dir_candidates(search);
  for (const auto& dir : candidates) {
    if (holds_cases(dir)) return dir;
  }
  if (search.env_dir) {
    std::string message = "PALPA_DATA_DIR=";
    message += search.env_dir->string();
    message += ": no cases/ folder there (it should name the folder holding cases/, such as /usr/share/palpa)";
    throw DataDirError(message);
  }
  std::string message = "Palpa's data folder (cases/) not found; looked in ";
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (i > 0) message += ", ";
    message += candidates[i].string();
  }
  if (candidates.empty()) message += "nothing (the executable's location is unknown)";
  message += "; set PALPA_DATA_DIR to the folder holding cases/";
  throw DataDirError(message);
}

DataSearch this_process_data_search() {
  DataSearch search;
  if (const char* env = std::getenv("PALPA_DATA_DIR"); env != nullptr && *env != '\0') search.env_dir = env;
  std::error_code ec;
  search.executable = fs::read_symlink("/proc/self/exe", ec);
  if (ec) search.executable.clear();
#if defined(PALPA_BUILD_TREE_DIR) && defined(PALPA_SOURCE_DATA_DIR)
  // Only a program running from the build tree may fall back to the sources: an installed
  // one must find its own data or say it cannot.
  if (!search.executable.empty() && is_inside(search.executable, PALPA_BUILD_TREE_DIR)) {
    search.build_tree_data = fs::path(PALPA_SOURCE_DATA_DIR);
  }
#endif
  return search;
}

fs::path bundled_case_path(const std::string& name) {
  const DataSearch search = this_process_data_search();
  const std::string file = with_json_extension(name);
  try {
    return find_data_dir(search) / "cases" / file;
  } catch (const DataDirError&) {
    const auto candidates = data_dir_candidates(search);
    return (candidates.empty() ? fs::path("share/palpa") : candidates.front()) / "cases" / file;
  }
}

fs::path resolve_case_argument(const std::string& argument, const DataSearch& search) {
  const fs::path given(argument);
  std::error_code ec;
  if (argument.empty() || fs::exists(given, ec) || given.has_parent_path()) return given;
  std::string message = argument;
  message += ": no such file here, and ";
  try {
    const fs::path cases = find_data_dir(search) / "cases";
    const fs::path bundled = cases / with_json_extension(argument);
    if (fs::is_regular_file(bundled, ec)) return bundled;
    message += "no bundled case of that name in ";
    message += cases.string();
  } catch (const DataDirError& e) {
    message += e.what();
  }
  throw DataDirError(message);
}

}  // namespace palpa::io
