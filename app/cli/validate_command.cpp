// palpa-cli validate CASE...: checks case files and their fit; "FILE: ok" or one line per problem.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/mat/mat_body.hpp"

namespace palpa::cli {
namespace {

// Problems of one file, one line each; empty when the file is valid.
std::vector<std::string> check(const std::string& path) {
  try {
    const auto file = io::load_case(path);
    std::vector<std::string> lines;
    // A valid file must also fit: this catches what a per-field check cannot see
    // (a collapsed grid, a pole with a non-zero radius).
    for (std::size_t k = 0; k < file.bodies.size(); ++k) {
      try {
        (void)mat::MatBody::fit(file.bodies[k]);
      } catch (const mat::FitError& e) {
        lines.push_back(path + ": /bodies/" + std::to_string(k) + ": cannot fit: " + e.what());
      }
    }
    return lines;
  } catch (const io::CaseError& e) {
    return e.lines();
  } catch (const std::exception& e) {  // e.g. out of memory: report this file, go on with the next
    return {path + ": file: cannot be checked: " + e.what()};
  }
}

}  // namespace

Command add_validate_command(CLI::App& parent) {
  auto files = std::make_shared<std::vector<std::string>>();
  auto* app = parent.add_subcommand("validate", "Check case files: prints 'FILE: ok' per valid file; "
                                                "one line per problem and exit 2 otherwise.");
  app->add_option("CASE", *files, "case files (JSON, docs/case-format.md)")->required();
  return {app, [files] {
            int code = kOk;
            for (const auto& path : *files) {
              const auto problems = check(path);
              if (problems.empty()) {
                std::printf("%s: ok\n", path.c_str());
              } else {
                for (const auto& line : problems) std::fprintf(stderr, "%s\n", line.c_str());
                code = kBadInput;
              }
            }
            return code;
          }};
}

}  // namespace palpa::cli
