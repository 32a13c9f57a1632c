// The run-time lookup of the bundled data (core io/data_paths): order, the authority of
// $PALPA_DATA_DIR, the build-tree fallback, bundled case names. Each test builds its own
// small trees in a temporary folder.
#include "palpa/io/data_paths.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <functional>
#include <optional>
#include <string>

namespace fs = std::filesystem;
using palpa::io::DataDirError;
using palpa::io::DataSearch;

namespace {

/// A temporary folder with an installed tree (root/usr/bin/palpa-cli,
/// root/usr/share/palpa/cases) and a source tree (root/src/data/cases), both optional.
class DataPaths : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string name = "palpa-data-paths-";
    name += std::to_string(::getpid());
    name += "-";
    name += ::testing::UnitTest::GetInstance()->current_test_info()->name();
    root_ = fs::temp_directory_path() / name;
    fs::remove_all(root_);
    fs::create_directories(root_ / "usr" / "bin");
    std::ofstream(exe()) << "not really a program";
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path exe() const { return root_ / "usr" / "bin" / "palpa-cli"; }
  fs::path installed() const { return root_ / "usr" / "share" / "palpa"; }
  fs::path source_data() const { return root_ / "src" / "data"; }
  fs::path env_data() const { return root_ / "elsewhere"; }

  static void add_case(const fs::path& data_dir, const std::string& file) {
    fs::create_directories(data_dir / "cases");
    std::ofstream(data_dir / "cases" / file) << "{}";
  }
  DataSearch search(bool with_build_tree = true, bool with_env = false) const {
    DataSearch s;
    s.executable = exe();
    if (with_build_tree) s.build_tree_data = source_data();
    if (with_env) s.env_dir = env_data();
    return s;
  }

  fs::path root_;
};

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const DataDirError& e) {
    return e.what();
  }
  return "(no DataDirError)";
}

}  // namespace

TEST_F(DataPaths, CandidatesAreInstalledThenBuildTree) {
  const auto c = palpa::io::data_dir_candidates(search());
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0], installed());  // bin/../share/palpa, normalized
  EXPECT_EQ(c[1], source_data());
}

TEST_F(DataPaths, EnvironmentIsTheOnlyCandidateWhenSet) {
  const auto c = palpa::io::data_dir_candidates(search(true, true));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0], env_data());
}

TEST_F(DataPaths, InstalledDataWinsOverTheBuildTree) {
  add_case(installed(), "default.json");
  add_case(source_data(), "default.json");
  EXPECT_EQ(palpa::io::find_data_dir(search()), installed());
}

TEST_F(DataPaths, BuildTreeDataWhenNothingIsInstalled) {
  add_case(source_data(), "default.json");
  EXPECT_EQ(palpa::io::find_data_dir(search()), source_data());
  // A share/palpa without cases/ does not count as a data folder.
  fs::create_directories(installed() / "schema");
  EXPECT_EQ(palpa::io::find_data_dir(search()), source_data());
}

TEST_F(DataPaths, EnvironmentWinsAndIsNotSecondGuessed) {
  add_case(installed(), "default.json");
  add_case(env_data(), "default.json");
  EXPECT_EQ(palpa::io::find_data_dir(search(true, true)), env_data());
  // Set but unusable: an error naming it, not a silent fall back to the installed data.
  fs::remove_all(env_data());
  const std::string m = message_of([&] { palpa::io::find_data_dir(search(true, true)); });
  EXPECT_NE(m.find("PALPA_DATA_DIR=" + env_data().string()), std::string::npos) << m;
}

TEST_F(DataPaths, NothingFoundNamesEveryPlaceLookedAt) {
  const std::string m = message_of([&] { palpa::io::find_data_dir(search()); });
  EXPECT_NE(m.find(installed().string()), std::string::npos) << m;
  EXPECT_NE(m.find(source_data().string()), std::string::npos) << m;
  EXPECT_NE(m.find("PALPA_DATA_DIR"), std::string::npos) << m;
  // An installed program has no build-tree fallback: only its own share/palpa is named.
  const std::string installed_only = message_of([&] { palpa::io::find_data_dir(search(false)); });
  EXPECT_EQ(installed_only.find(source_data().string()), std::string::npos) << installed_only;
}

TEST_F(DataPaths, BareNamesAreBundledCases) {
  add_case(installed(), "flat-5x5.json");
  const fs::path expected = installed() / "cases" / "flat-5x5.json";
  EXPECT_EQ(palpa::io::resolve_case_argument("flat-5x5", search()), expected);
  EXPECT_EQ(palpa::io::resolve_case_argument("flat-5x5.json", search()), expected);
}

TEST_F(DataPaths, PathsAreTakenAsTyped) {
  add_case(installed(), "flat-5x5.json");
  // An existing file, and a path with a folder in it (existing or not), are the user's.
  const fs::path mine = root_ / "mine.json";
  std::ofstream(mine) << "{}";
  EXPECT_EQ(palpa::io::resolve_case_argument(mine.string(), search()), mine);
  EXPECT_EQ(palpa::io::resolve_case_argument("cases/flat-5x5.json", search()), fs::path("cases/flat-5x5.json"));
  EXPECT_EQ(palpa::io::resolve_case_argument("", search()), fs::path());
}

TEST_F(DataPaths, UnknownBareNameSaysWhereItLooked) {
  add_case(installed(), "flat-5x5.json");
  const std::string m = message_of([&] { palpa::io::resolve_case_argument("no-such-case", search()); });
  EXPECT_EQ(m.rfind("no-such-case: ", 0), 0u) << m;
  EXPECT_NE(m.find((installed() / "cases").string()), std::string::npos) << m;
  fs::remove_all(installed());
  const std::string none = message_of([&] { palpa::io::resolve_case_argument("default", search(false)); });
  EXPECT_NE(none.find("not found"), std::string::npos) << none;
}

TEST(DataPathsOfThisProcess, ReadsTheEnvironmentAndFallsBackToTheSourceTree) {
  const char* saved = std::getenv("PALPA_DATA_DIR");
  const std::optional<std::string> restore = saved ? std::optional<std::string>(saved) : std::nullopt;

  ::unsetenv("PALPA_DATA_DIR");
  DataSearch s = palpa::io::this_process_data_search();
  EXPECT_FALSE(s.env_dir.has_value());
  EXPECT_EQ(fs::weakly_canonical(s.executable), fs::weakly_canonical("/proc/self/exe"));
  // This test runs from the build tree, so the sources' data/ is its fallback.
  ASSERT_TRUE(s.build_tree_data.has_value());
  EXPECT_EQ(fs::weakly_canonical(*s.build_tree_data), fs::weakly_canonical(fs::path(PALPA_SOURCE_DIR) / "data"));
  EXPECT_TRUE(fs::is_regular_file(palpa::io::bundled_case_path("default")));
  EXPECT_EQ(palpa::io::bundled_case_path("default").filename(), "default.json");

  ::setenv("PALPA_DATA_DIR", "/nonexistent/palpa-data", 1);
  s = palpa::io::this_process_data_search();
  ASSERT_TRUE(s.env_dir.has_value());
  EXPECT_EQ(*s.env_dir, fs::path("/nonexistent/palpa-data"));
  // Not found: the place it would be, so that opening it names the file.
  EXPECT_EQ(palpa::io::bundled_case_path("default.json"), fs::path("/nonexistent/palpa-data/cases/default.json"));

  if (restore) {
    ::setenv("PALPA_DATA_DIR", restore->c_str(), 1);
  } else {
    ::unsetenv("PALPA_DATA_DIR");
  }
}
