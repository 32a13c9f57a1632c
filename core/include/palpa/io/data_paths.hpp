#pragma once
// Where Palpa's bundled data (the folder holding cases/ and schema/) is found at run time,
// so installed binaries never depend on the source tree they were built from.
//
// Order: $PALPA_DATA_DIR (when set, the only place looked at), then
// <folder of the running executable>/../share/palpa (an installed tree: /usr/bin/palpa ->
// /usr/share/palpa), then the source tree's data/ (only for an executable inside the build
// tree it was compiled in, so a build runs without installing).
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace palpa::io {

/// What the lookup starts from; this_process_data_search() fills it for the running program,
/// tests fill it by hand.
struct DataSearch {
  std::optional<std::filesystem::path> env_dir;  ///< $PALPA_DATA_DIR, if set and not empty
  std::filesystem::path executable;              ///< the running executable (/proc/self/exe)
  std::optional<std::filesystem::path> build_tree_data;  ///< source data/, for build trees only
};

/// The data folder cannot be found (or $PALPA_DATA_DIR names one without cases/).
class DataDirError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The folders looked at, in order (whether or not they exist).
std::vector<std::filesystem::path> data_dir_candidates(const DataSearch& search);

/// The first candidate holding a cases/ folder. Throws DataDirError with one line naming
/// every folder looked at, or naming $PALPA_DATA_DIR when it is set and unusable.
std::filesystem::path find_data_dir(const DataSearch& search);

/// The search of the running program: $PALPA_DATA_DIR, /proc/self/exe, and the source
/// tree's data/ when the executable lives in the build tree this file was compiled for.
DataSearch this_process_data_search();

/// data/cases/NAME of the running program (NAME with or without .json). When no data folder
/// is found, the path where an installed tree would have it, so that opening it fails with
/// a message naming the file. Never throws.
std::filesystem::path bundled_case_path(const std::string& name);

/// A CASE argument as the user typed it: an existing file, or anything with a folder in it,
/// is itself (opening it reports what is wrong); a bare name ("default", "flat-5x5.json")
/// that is no file here is the bundled case of that name. Throws DataDirError with one line
/// ("NAME: no such file here, and ...") when there is no such bundled case either.
std::filesystem::path resolve_case_argument(const std::string& argument, const DataSearch& search);

}  // namespace palpa::io
