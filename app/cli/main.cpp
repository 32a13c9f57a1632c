// palpa-cli: the headless tools of Palpa: validate and fit case files, probe and simulate
// the haptic model, run scripted exercises, score and batch-score sessions, benchmarks,
// list devices. Each sub-command lives in its own *_command.cpp.
#include <cstdio>
#include <string>
#include <vector>

#include "commands.hpp"
#include "palpa/report/printable.hpp"
#include "palpa/version.hpp"

namespace palpa::cli {

// Messages carry names from files and the store: escaped, so no ESC, NUL or bidirectional
// override reaches the terminal (report/printable.hpp).
void print_error(const std::string& message) {
  std::fprintf(stderr, "palpa-cli: error: %s\n", report::printable(message, 1000).c_str());
}

}  // namespace palpa::cli

int main(int argc, char** argv) {
  using namespace palpa::cli;
  CLI::App app{"Palpa command-line tools: case files, the medial-axis body model, scripted exercises,\n"
               "scoring, batch reports and benchmarks.\n"
               "Units are SI (m, N, N/m, Pa, kg, s) in every file and option.",
               "palpa-cli"};
  app.set_version_flag("--version", std::string("palpa-cli ") + palpa::kVersion);
  app.require_subcommand(0, 1);  // checked after parsing, so unknown words are named first
  app.footer("Exit codes: 0 success, 1 failure, 2 bad input or usage.\nRun 'palpa-cli COMMAND --help' for a command's options.");

  std::vector<Command> commands{add_validate_command(app), add_fit_command(app), add_probe_command(app),
                                add_simulate_command(app), add_exercise_command(app), add_score_command(app),
                                add_batch_command(app), add_bench_command(app), add_devices_command(app),
                                add_lrs_command(app)};
  commands.push_back(add_store_command(app));  // the centre store (docs/centre.md)
  commands.push_back(add_session_command(app));  // session upgrade (docs/session-format.md)
  commands.push_back(add_import_command(app));   // anatomy to a case (docs/anatomy-import.md)
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    print_error(std::string(e.what()) + " (see palpa-cli --help)");
    return kBadInput;
  }
  for (const auto& c : commands) {
    if (c.app->parsed()) {
      try {
        return c.run();
      } catch (const std::exception& e) {
        print_error(e.what());
        return kFailure;
      }
    }
  }
  print_error("a command is required: validate, fit, probe, simulate, exercise, score, batch, bench, devices, lrs or store (see palpa-cli "
              "--help)");
  return kBadInput;
}
