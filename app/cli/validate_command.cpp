// palpa-cli validate CASE...: checks case files and their fit; "FILE: ok" or one line per problem.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/scene/scene.hpp"

namespace palpa::cli {
namespace {

// Problems of one file, one line each; empty when the file is valid.
std::vector<std::string> check(const std::string& path) {
  try {
    // A valid file must also fit and hold its tumours inside their bodies: this catches
    // what a per-field check cannot see (a collapsed grid, an overshooting field).
    (void)scene::Scene::build(io::load_case(path), path);
    return {};
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
