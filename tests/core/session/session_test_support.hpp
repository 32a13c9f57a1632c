#pragma once
// Shared by the session tests: a scratch folder, a valid SessionInfo on a real case, and
// samples that are a deterministic function of their tick (so a reader can check every
// value against what the writer must have written).
#include <sqlite3.h>
#include <stdlib.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>

#include "palpa/engine/engine.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/session/session.hpp"
#include "palpa/session/session_writer.hpp"

namespace palpa::session::test {

/// A fresh folder under the system's temporary folder, removed with everything in it.
class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "palpa-session-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline SessionInfo flat_case_info() {
  SessionInfo info;
  info.id = "0123456789abcdef0123456789abcdef";
  info.trainee = "trainee-07";
  info.device = "virtual";
  info.software_version = "0.1.0";
  info.started_at = "2026-11-22T16:40:00Z";
  info.rate_hz = 1000.0;
  info.case_source = "data/cases/flat-5x5.json";
  info.case_document = io::to_json(io::load_case(PALPA_SOURCE_DIR "/data/cases/flat-5x5.json"));
  return info;
}

/// Tick k's sample: every field depends on k, with values that have all 52 mantissa bits
/// in use; every third tick is out of contact. flat-5x5 has one body (index 0).
inline engine::Sample sample_at(std::uint64_t k) {
  const double x = static_cast<double>(k);
  engine::Sample s;
  s.t = x / 1000.0;
  s.position = {0.02 * std::sin(x / 97.0) + 1.0 / 3.0, 0.01 * std::cos(x / 89.0) + 0.1, 0.03 + x * 1e-7};
  s.force = {std::sin(x / 7.0) / 3.0 + 5.0, -std::cos(x / 11.0) / 7.0 - 3.0, std::sqrt(x + 2.0)};
  if (k % 3 != 0) {
    s.body = 0;
    s.u = std::fmod(x / 1000.0, 1.0) + 1e-9;
    s.v = 1.0 / (x + 3.0);
    s.depth = 1e-3 * std::exp(-x / 1e4) + 1e-12;
  }
  s.buttons = static_cast<std::uint32_t>(k % 4);
  s.overrun = k % 7 == 0;
  s.fault = k % 11 == 0;
  return s;
}

/// Format 1: one row per tick, every double read back to the bit (what the exactness tests
/// and the tests that edit the samples table by hand need).
inline const WriterOptions kRows{1};

/// True when a is b as format 2 stores it: each value within half its unit (1 us, 1 um,
/// 1 mN, 1e-6), the integers and flags the same (docs/session-format.md).
inline bool near_sample(const engine::Sample& a, const engine::Sample& b) {
  const auto near = [](double x, double y, double unit) { return std::fabs(x - y) <= unit / 2 * (1 + 1e-9); };
  bool same = near(a.t, b.t, 1e-6) && a.body == b.body && a.buttons == b.buttons && a.overrun == b.overrun &&
              a.fault == b.fault;
  for (std::size_t i = 0; i < 3; ++i) same = same && near(a.position[i], b.position[i], 1e-6) && near(a.force[i], b.force[i], 1e-3);
  if (a.body >= 0) same = same && near(a.u, b.u, 1e-6) && near(a.v, b.v, 1e-6) && near(a.depth, b.depth, 1e-6);
  return same;
}

inline bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

/// True when every field of a and b is the same, doubles to the bit.
inline bool same_sample(const engine::Sample& a, const engine::Sample& b) {
  bool same = same_bits(a.t, b.t) && same_bits(a.u, b.u) && same_bits(a.v, b.v) && same_bits(a.depth, b.depth) &&
              a.body == b.body && a.buttons == b.buttons && a.overrun == b.overrun && a.fault == b.fault;
  for (std::size_t i = 0; i < 3; ++i) {
    same = same && same_bits(a.position[i], b.position[i]) && same_bits(a.force[i], b.force[i]);
  }
  return same;
}

/// Runs SQL on a file with a read-write connection (to damage sessions on purpose).
inline void sql(const std::filesystem::path& file, const std::string& statements) {
  sqlite3* db = nullptr;
  if (sqlite3_open(file.string().c_str(), &db) != SQLITE_OK) {
    sqlite3_close(db);
    throw std::runtime_error("cannot open " + file.string());
  }
  char* error = nullptr;
  const int rc = sqlite3_exec(db, statements.c_str(), nullptr, nullptr, &error);
  std::string message = error != nullptr ? error : "";
  sqlite3_free(error);
  sqlite3_close(db);
  if (rc != SQLITE_OK) throw std::runtime_error(statements + ": " + message);
}

}  // namespace palpa::session::test
