// Fuzz target: a session file as palpa-cli score, batch and review read it. Read it (the
// schema check, the per-row range checks), then score it with its own case's thresholds.
// The bytes are written to a file: the reader opens files (SQLite, its -wal beside it).
#include <stdlib.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "palpa/score/score.hpp"
#include "palpa/session/session_reader.hpp"

namespace {

// One scratch folder per process, removed at exit; in memory where the machine has /dev/shm.
const std::filesystem::path& scratch() {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path base = std::filesystem::is_directory("/dev/shm") ? std::filesystem::path("/dev/shm")
                                                                                 : std::filesystem::temp_directory_path();
    std::string pattern = (base / "palpa-fuzz-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) std::abort();
    std::atexit([] { std::filesystem::remove_all(scratch()); });
    return std::filesystem::path(pattern);
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = scratch() / "fuzz.palpa";
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) std::filesystem::remove(path.string() + suffix);
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try {
    const auto session = palpa::session::read_session(path);
    (void)palpa::score::score_session(session, path.string());
  } catch (const palpa::session::SessionError&) {
    // refused with a message naming the file and the place
  }
  return 0;
}
