#include "palpa/store/score_claim.hpp"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>

#include "palpa/score/score.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/store/sha256.hpp"
#include "palpa/version.hpp"

namespace palpa::store {
namespace {

namespace fs = std::filesystem;

// A temporary copy of the claimed bytes, removed when it goes out of scope.
class TempSession {
 public:
  explicit TempSession(const std::string& bytes) {
    std::error_code ec;
    auto dir = fs::temp_directory_path(ec);
    if (ec) dir = "/tmp";
    std::string name = (dir / "palpa-worker-XXXXXX.palpa").string();
    const int fd = mkstemps(name.data(), 6);
    if (fd < 0) throw StoreError(fmt::format("worker: cannot create a temporary file in {}", dir.string()), false);
    path_ = name;
    std::size_t done = 0;
    while (done < bytes.size()) {
      const auto n = write(fd, bytes.data() + done, bytes.size() - done);
      if (n <= 0) break;
      done += static_cast<std::size_t>(n);
    }
    close(fd);
    if (done != bytes.size()) {
      fs::remove(path_, ec);
      throw StoreError(fmt::format("worker: cannot write {}", name), false);
    }
  }
  ~TempSession() {
    std::error_code ec;
    fs::remove(path_, ec);
  }
  TempSession(const TempSession&) = delete;
  TempSession& operator=(const TempSession&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

}  // namespace

ScoreRow score_claim(const Claim& claim) {
  const TempSession file(claim.file);
  const auto session = session::read_session(file.path());
  const auto score = score::score_session(session, claim.file_name);
  ScoreRow row;
  row.scorer_version = palpa::kVersion;
  row.thresholds_sha256 = sha256_hex(score::to_json(score.thresholds).dump());
  row.result_json = score::to_json(score, false).dump();
  row.score = score.score;
  row.passed = score.passed;
  return row;
}

}  // namespace palpa::store
