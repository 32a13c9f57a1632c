// palpa-cli score SESSION [--json] [--report DIR]: scores one recorded session against its
// case's hidden truth; prints the score card or the report JSON, and can write the report
// files (HTML, JSON, xAPI, CSV).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "commands.hpp"
#include "output_guard.hpp"
#include "xapi_send.hpp"
#include "palpa/report/force_trace.hpp"
#include "palpa/report/report_json.hpp"
#include "palpa/report/session_report.hpp"
#include "palpa/score/score.hpp"
#include "palpa/session/session_reader.hpp"

namespace palpa::cli {
namespace {

struct ScoreOptions {
  std::string session;
  bool json = false;
  ReportRequest report;
};

int run_score(const ScoreOptions& o) { return score_and_report(o.session, o.json, o.report); }

// Reads and scores a session as a stream: `head` gets no samples, and memory stays that of
// the case however long the session is.
void read_and_score(const std::filesystem::path& path, session::Session& head, score::Score& score) {
  session::SampleStream stream(path);
  score = score::score_stream(stream, path.string());
  head = stream.head();
}

}  // namespace

std::string report_refusal(const std::filesystem::path& session, const ReportRequest& request,
                           const std::vector<std::filesystem::path>& inputs) {
  if (request.dir.empty()) return {};
  std::vector<std::filesystem::path> all = inputs;
  all.push_back(session);
  return refusal_to_write(report::session_report_paths(request.dir, session.stem().string()), request.force, all);
}

int score_and_report(const std::filesystem::path& path, bool json, const ReportRequest& report) {
  if (auto why = report_refusal(path, report, {}); !why.empty()) {
    print_error("--report: " + why);
    return kBadInput;
  }
  const std::string& report_dir = report.dir;
  session::Session session;
  score::Score score;
  try {
    read_and_score(path, session, score);
  } catch (const session::SessionError& e) {
    print_error(e.what());
    return kBadInput;
  }
  const auto header = report::header_of(session.info, path);
  const auto xapi = xapi_settings(report);
  if (!xapi) return kBadInput;
  if (json) {
    std::printf("%s\n", report::report_json(header, score).dump(2).c_str());
  } else {
    std::fputs(score::summary_text(score).c_str(), stdout);
  }
  std::fflush(stdout);
  if (!report_dir.empty()) {
    try {
      report::ReportFiles files;
      files.xapi_home_page = xapi->home_page;
      report::write_session_report(report_dir, path.stem().string(), header, *report::read_force_trace(path), score, files);
    } catch (const std::exception& e) {
      print_error(e.what());
      return kFailure;
    }
    if (!json) {
      const auto stem = (std::filesystem::path(report_dir) / path.stem()).string();
      std::printf("report: %s.html (.json, .xapi.json, .csv)\n", stem.c_str());
    }
  }
  return send_statement(header, score, report, *xapi);
}

Command add_score_command(CLI::App& parent) {
  auto o = std::make_shared<ScoreOptions>();
  auto* app = parent.add_subcommand(
      "score", "Score a recorded session against its case's hidden tumours: sensitivity, false positives, "
               "localization error, coverage, deep coverage, pressure, search pattern, duration, peak force; "
               "pass/fail by gates. Exit 0 when scored (passed or failed), 2 for an unreadable session.");
  app->add_option("SESSION", o->session, "session file (.palpa)")->required();
  app->add_flag("--json", o->json, "print the report as JSON (score and session) instead of the score card");
  app->add_option("--report", o->report.dir,
                  "also write DIR/STEM.html (self-contained page with maps), STEM.json, STEM.xapi.json (xAPI "
                  "statement) and STEM.csv, STEM being the session file's stem; never replaces a file without "
                  "--force, nor the session itself");
  app->add_flag("--force", o->report.force, "let --report replace report files that exist");
  add_lrs_option(app, o->report);
  return {app, [o] { return run_score(*o); }};
}

}  // namespace palpa::cli
