// palpa-cli session upgrade SESSION... [--out DIR]: converts format-1 session files (one
// SQLite row per tick) into format 2 (compact sample blocks; docs/session-format.md). Each
// copy is checked against its original (samples, events, meta, score gates and score)
// before it replaces the original atomically, or is placed in --out; nothing is lost.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "palpa/score/score.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/session/session_upgrade.hpp"

namespace palpa::cli {
namespace {

namespace fs = std::filesystem;

/// The largest score difference an upgrade accepts between a session and its format-2 copy
/// (scores are 0..1; the quantization moves them by less than 1e-4 on the sample sessions,
/// docs/session-format.md "Equivalence").
constexpr double kScoreTolerance = 0.001;

struct UpgradeOptions {
  std::vector<std::string> sessions;
  std::string out;  ///< empty: replace each file in place
};

/// Why `copy` is not `original` in everything but the quantization of its samples; empty
/// when it is.
std::string difference(const session::Session& original, const session::Session& copy) {
  if (copy.samples.size() != original.samples.size()) {
    return fmt::format("{} samples instead of {}", copy.samples.size(), original.samples.size());
  }
  if (copy.events.size() != original.events.size()) return "its events differ";
  for (std::size_t k = 0; k < copy.events.size(); ++k) {
    const auto& a = original.events[k];
    const auto& b = copy.events[k];
    if (a.t != b.t || a.kind != b.kind || a.mark != b.mark || a.position != b.position || a.note != b.note) {
      return fmt::format("event {} differs", k);
    }
  }
  const auto& i = original.info;
  const auto& j = copy.info;
  if (i.id != j.id || i.trainee != j.trainee || i.started_at != j.started_at || i.case_document != j.case_document ||
      i.extra != j.extra || i.seed != j.seed || original.loop_stats != copy.loop_stats ||
      original.complete != copy.complete) {
    return "its meta differs";
  }
  return {};
}

std::string score_difference(const session::Session& original, const session::Session& copy, const std::string& file) {
  const score::Score a = score::score_session(original, file);
  const score::Score b = score::score_session(copy, file);
  std::size_t found_a = 0, found_b = 0;
  for (const auto& t : a.tumours) found_a += t.found ? 1 : 0;
  for (const auto& t : b.tumours) found_b += t.found ? 1 : 0;
  if (a.passed != b.passed || a.safe != b.safe || a.complete != b.complete || found_a != found_b) {
    return "its score gates differ (passed, safe, complete or tumours found)";
  }
  if (std::fabs(a.score - b.score) > kScoreTolerance) {
    return fmt::format("its score differs by {:.6f} (more than {})", std::fabs(a.score - b.score), kScoreTolerance);
  }
  return {};
}

/// Refusals that need no reading: a recording in progress, a file with a -wal beside it
/// replaced in place (the -wal would be applied to the new file), a target that exists.
std::string refusal(const fs::path& file, const fs::path& target, bool in_place) {
  if (const auto pid = session::process_holding(file)) {
    return fmt::format("{}: being recorded or read by another process (pid {}); upgrade it once it is finished",
                       file.string(), *pid);
  }
  if (in_place) {
    for (const char* suffix : {"-wal", "-journal"}) {
      if (fs::exists(file.string() + suffix)) {
        return fmt::format("{}: has a {} beside it (a session cut short, or open in another program); upgrade a copy "
                           "with --out DIR, which leaves it as it is",
                           file.string(), suffix);
      }
    }
  } else if (fs::exists(fs::symlink_status(target))) {
    return fmt::format("{}: {} exists; upgrade never replaces a file in --out", file.string(), target.string());
  }
  return {};
}

/// The format-2 copy at `temporary`, checked, then given the target's name: renamed over the
/// original in place (atomic), or linked into --out without replacing anything.
int place(const fs::path& temporary, const fs::path& target, bool in_place) {
  std::error_code ec;
  if (in_place) {
    fs::rename(temporary, target, ec);
  } else {
    fs::create_hard_link(temporary, target, ec);
    if (!ec) fs::remove(temporary);
  }
  if (ec) {
    fs::remove(temporary);
    print_error(fmt::format("{}: cannot be given its name: {}", target.string(), ec.message()));
    return kFailure;
  }
  return kOk;
}

int upgrade_one(const fs::path& file, const UpgradeOptions& o) {
  const bool in_place = o.out.empty();
  const fs::path target = in_place ? file : fs::path(o.out) / file.filename();
  try {
    const session::Session original = session::read_session(file);
    if (original.format_version >= 2) {
      std::printf("%s: already format %d\n", file.string().c_str(), original.format_version);
      return kOk;
    }
    if (const auto why = refusal(file, target, in_place); !why.empty()) {
      print_error(why);
      return kBadInput;
    }
    const fs::path temporary =
        target.parent_path() / fmt::format(".{}.upgrade-{}.tmp", target.filename().string(), ::getpid());
    session::write_compacted_copy(file, temporary);
    std::string why;
    try {
      const session::Session copy = session::read_session(temporary);
      why = difference(original, copy);
      if (why.empty()) why = score_difference(original, copy, file.string());
    } catch (const session::SessionError& e) {
      why = std::string("it does not read back (") + e.what() + ")";
    }
    if (!why.empty()) {
      fs::remove(temporary);
      print_error(fmt::format("{}: the format-2 copy is refused: {}; the file is left as it was", file.string(), why));
      return kFailure;
    }
    const auto before = fs::file_size(file);
    const auto after = fs::file_size(temporary);
    if (const int placed = place(temporary, target, in_place); placed != kOk) return placed;
    std::printf("%s: format 2, %zu samples, %ju -> %ju bytes\n", target.string().c_str(), original.samples.size(),
                static_cast<std::uintmax_t>(before), static_cast<std::uintmax_t>(after));
    return kOk;
  } catch (const session::SessionError& e) {
    print_error(e.what());
    return kBadInput;
  }
}

int run_upgrade(const UpgradeOptions& o) {
  if (!o.out.empty() && !fs::is_directory(o.out)) {
    print_error(fmt::format("--out {}: not a folder", o.out));
    return kBadInput;
  }
  int status = kOk;
  for (const auto& name : o.sessions) {
    const int one = upgrade_one(name, o);
    if (one != kOk && status == kOk) status = one;
  }
  std::fflush(stdout);
  return status;
}

}  // namespace

Command add_session_command(CLI::App& parent) {
  auto o = std::make_shared<UpgradeOptions>();
  auto* app = parent.add_subcommand("session", "Session files: convert format-1 files to the compact format 2.");
  app->require_subcommand(1);
  auto* upgrade = app->add_subcommand(
      "upgrade",
      "Convert format-1 sessions (one row per tick) to format 2 (compact blocks, about a tenth of the size; "
      "docs/session-format.md). Each copy is read back and scored before it replaces the file atomically "
      "(or goes into --out); a format-2 file is left alone, a session being recorded is refused. "
      "Exit 0 when every file is format 2, 2 for a file that cannot be upgraded, 1 for a failed write.");
  upgrade->add_option("SESSION", o->sessions, "session files (.palpa)")->required();
  upgrade->add_option("--out", o->out, "write the format-2 copies into DIR (same file names), leaving the originals");
  return {app, [o] { return run_upgrade(*o); }};
}

}  // namespace palpa::cli
