// Runs a fuzz target over files, once each, without libFuzzer: the corpora's regression
// test in every build (gcc included), under the sanitizers in the dev build.
//   fuzz_replay_TARGET [--max-seconds S] [--max-rss-mb M] FILE_OR_FOLDER...
// Fails when an input takes more than S seconds of CPU time, or the process more than M MB.
#include <sys/resource.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

std::vector<std::filesystem::path> inputs_of(const std::vector<std::string>& args) {
  std::vector<std::filesystem::path> files;
  for (const auto& arg : args) {
    if (std::filesystem::is_directory(arg)) {
      for (const auto& entry : std::filesystem::directory_iterator(arg)) {
        if (entry.is_regular_file()) files.push_back(entry.path());
      }
    } else {
      files.emplace_back(arg);
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

long max_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024;
}

}  // namespace

int main(int argc, char** argv) {
  double max_seconds = 1e9;
  long max_rss = 1L << 30;
  std::vector<std::string> args;
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--max-seconds" && k + 1 < argc) {
      max_seconds = std::atof(argv[++k]);
    } else if (arg == "--max-rss-mb" && k + 1 < argc) {
      max_rss = std::atol(argv[++k]);
    } else if (arg == "--help" || arg == "-h") {
      std::printf("usage: %s [--max-seconds S] [--max-rss-mb M] FILE_OR_FOLDER...\n", argv[0]);
      return 0;
    } else {
      args.push_back(arg);
    }
  }
  const auto files = inputs_of(args);
  if (files.empty()) {
    std::fprintf(stderr, "%s: no inputs\n", argv[0]);
    return 2;
  }
  int failures = 0;
  for (const auto& file : files) {
    std::ifstream in(file, std::ios::binary);
    const std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const double start = cpu_seconds();
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    const double spent = cpu_seconds() - start;
    if (spent > max_seconds) {
      std::fprintf(stderr, "%s: %.2f s of CPU time (limit %.2f s)\n", file.c_str(), spent, max_seconds);
      ++failures;
    }
  }
  const long rss = max_rss_mb();
  std::printf("%zu inputs, peak memory %ld MB\n", files.size(), rss);
  if (rss > max_rss) {
    std::fprintf(stderr, "peak memory %ld MB (limit %ld MB)\n", rss, max_rss);
    ++failures;
  }
  return failures == 0 ? 0 : 1;
}
