#pragma once
// The sub-commands of palpa-cli. Each registers its options on the app and returns the
// function that runs it; the function returns the process exit code.
#include <filesystem>
#include <functional>
#include <string>

#include <CLI/CLI.hpp>

namespace palpa::cli {

/// Exit codes shared by all commands.
enum ExitCode : int { kOk = 0, kFailure = 1, kBadInput = 2 };

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
Command add_devices_command(CLI::App& parent);

/// Reads and scores the session at `path`; prints the score card (or with `json` the report
/// JSON) and writes the report files into `report_dir` when it is not empty. Returns the
/// exit code (2 for a bad session, 1 when the report cannot be written).
int score_and_report(const std::filesystem::path& path, bool json, const std::string& report_dir);

/// Prints "palpa-cli: error: <message>" on one line of stderr.
void print_error(const std::string& message);

}  // namespace palpa::cli
