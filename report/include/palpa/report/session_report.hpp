#pragma once
// Writes the report files of one session into a folder: STEM.html, STEM.json,
// STEM.xapi.json and optionally STEM.csv (header + one row).
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "palpa/report/session_header.hpp"
#include "palpa/score/score.hpp"
#include "palpa/session/session.hpp"

namespace palpa::report {

class ForceTrace;

struct ReportFiles {
  bool html = true, json = true, xapi = true, csv = true;
  std::string xapi_home_page = "urn:palpa";  ///< the actor account's homePage in STEM.xapi.json
};

/// The files write_session_report writes for these `files`, in `dir` (a caller checks them
/// before writing: palpa-cli refuses to replace any without --force).
std::vector<std::filesystem::path> session_report_paths(const std::filesystem::path& dir, const std::string& stem,
                                                        const ReportFiles& files = {});

/// Creates `dir` if needed. Throws std::runtime_error "PATH: cannot write" on failure.
void write_session_report(const std::filesystem::path& dir, const std::string& stem, const SessionHeader& header,
                          const session::Session& session, const score::Score& score, const ReportFiles& files = {});
/// The same with the force plot from a trace gathered while the samples streamed by
/// (force_trace.hpp): the report of a session of any length in the memory of its plots.
void write_session_report(const std::filesystem::path& dir, const std::string& stem, const SessionHeader& header,
                          const ForceTrace& trace, const score::Score& score, const ReportFiles& files = {});

/// Writes `text` to `path` (replacing it); throws std::runtime_error "PATH: cannot write".
void write_text(const std::filesystem::path& path, std::string_view text);

}  // namespace palpa::report
