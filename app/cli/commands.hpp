#pragma once
// The sub-commands of palpa-cli. Each registers its options on the app and returns the
// function that runs it; the function returns the process exit code.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace palpa::cli {

/// Exit codes shared by all commands.
enum ExitCode : int {
  kOk = 0,
  kFailure = 1,
  kBadInput = 2,
  kQueuedForUpgrade = 3,  ///< store push: the store needs a newer Palpa; the sessions wait in the outbox
};

struct Command {
  CLI::App* app;
  std::function<int()> run;
};

Command add_validate_command(CLI::App& parent);
Command add_fit_command(CLI::App& parent);
Command add_probe_command(CLI::App& parent);
Command add_bench_command(CLI::App& parent);
Command add_simulate_command(CLI::App& parent);
Command add_exercise_command(CLI::App& parent);
Command add_score_command(CLI::App& parent);
Command add_batch_command(CLI::App& parent);
Command add_store_command(CLI::App& parent);
Command add_devices_command(CLI::App& parent);
Command add_lrs_command(CLI::App& parent);
Command add_session_command(CLI::App& parent);
Command add_import_command(CLI::App& parent);  // anatomy to a case (docs/anatomy-import.md)

/// --report DIR [--force]: where a session's report files go (none when `dir` is empty), and
/// whether files already there may be replaced.
struct ReportRequest {
  std::string dir;
  bool force = false;
  std::string lrs;                   ///< --lrs URL: send the xAPI statement there (through the outbox)
  bool lrs_when_configured = false;  ///< also send when an LRS is configured (exercises)
};

/// Why the report of the session `session` may not be written as `request` asks (a file it
/// would write exists and there is no --force, or it would be one of `inputs`); empty when it
/// may, or when no report is asked for.
std::string report_refusal(const std::filesystem::path& session, const ReportRequest& request,
                           const std::vector<std::filesystem::path>& inputs);

/// Reads and scores the session at `path`; prints the score card (or with `json` the report
/// JSON) and writes the report files as `report` asks. Returns the exit code (2 for a bad
/// session or a report it may not write, 1 when the report cannot be written).
int score_and_report(const std::filesystem::path& path, bool json, const ReportRequest& report);

/// --lrs URL on a command that finishes sessions (score, exercise): where the xAPI statement
/// goes (docs/centre.md, "Learning record store").
void add_lrs_option(CLI::App* app, ReportRequest& request);

/// Prints "palpa-cli: error: <message>" on one line of stderr.
void print_error(const std::string& message);

}  // namespace palpa::cli
