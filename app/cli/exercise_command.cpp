// palpa-cli exercise CASE --trainee ID [--style expert|sloppy|light] [--seed N] --out SESSION:
// a scripted trainee palpates the case through the haptic engine (deterministically, as
// fast as the machine allows), the session is recorded and scored. The headless demo of
// the README's run command.
#include <cstdio>
#include <memory>
#include <optional>
#include <random>
#include <string>

#include "commands.hpp"
#include "exercise_replay.hpp"
#include "palpa/options/number_checks.hpp"
#include "palpa/scripted/exercise.hpp"
#include "palpa/scripted/scripted_trainee.hpp"
#include "palpa/scripted/tumour_placement.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/io/data_paths.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/session/session_writer.hpp"

namespace palpa::cli {
namespace {

struct ExerciseCliOptions {
  std::string case_path;
  std::string trainee;
  std::string style = "expert";
  std::optional<std::uint64_t> seed;
  std::string out_path;
  bool json = false;
  ReportRequest report;
  std::string device = "scripted";
};

/// A seed nobody chose: every attempt meets its tumours somewhere new, and the session
/// records the seed so the attempt can be repeated.
std::uint64_t fresh_seed() {
  std::random_device device;
  return (static_cast<std::uint64_t>(device()) << 32) ^ device();
}

// Runs the exercise into the session file at `out_path`, one commit per simulated second
// as a live recording makes. kOk or the exit code.
int record_exercise(const scene::Scene& scene, scripted::ScriptedTrainee& trainee, const session::SessionInfo& info,
                    const std::string& out_path, scripted::ExerciseSummary& summary) {
  try {
    session::SessionWriter writer(out_path, info);
    std::uint64_t since_commit = 0;
    summary = scripted::run_exercise(
        scene, trainee,
        [&](const engine::Sample& s) {
          writer.append(s);
          if (++since_commit == 1000) {
            writer.commit();
            since_commit = 0;
          }
        },
        [&](const session::Event& e) { writer.event(e); });
    writer.finish();
  } catch (const session::SessionError& e) {
    print_error(e.what());
    return e.where() == "file" ? kBadInput : kFailure;
  }
  return kOk;
}

// The arguments of a scripted exercise: a live device is refused, CASE resolved (a bare
// name is a bundled case), the trainee and the style checked. kOk or the exit code.
int check_scripted_arguments(ExerciseCliOptions& o) {
  if (o.device != "scripted") {
    print_error("--device: " + o.device +
                ": a headless exercise is scripted or replay:SESSION; a live device palpates in the GUI (palpa "
                "--device ID)");
    return kBadInput;
  }
  if (o.case_path.empty()) {
    print_error("exercise: CASE is required (except with --device replay:SESSION)");
    return kBadInput;
  }
  // A bare name ("default", "flat-5x5") is a bundled case when no such file is here.
  try {
    o.case_path = io::resolve_case_argument(o.case_path, io::this_process_data_search()).string();
  } catch (const io::DataDirError& e) {
    print_error(e.what());
    return kBadInput;
  }
  if (o.trainee.empty()) {
    print_error("exercise: --trainee is required");
    return kBadInput;
  }
  const auto style = scripted::style_from_string(o.style);
  if (!style) {
    print_error("--style: unknown style \"" + o.style + "\" (expert, sloppy or light)");
    return kBadInput;
  }
  return kOk;
}

int run_exercise_command(ExerciseCliOptions o) {
  // Before palpating: a report that could not be written is said now, not after the run.
  std::vector<std::filesystem::path> inputs{o.case_path};
  if (o.device.rfind("replay:", 0) == 0) inputs.emplace_back(o.device.substr(7));
  if (auto why = report_refusal(o.out_path, o.report, inputs); !why.empty()) {
    print_error("--report: " + why);
    return kBadInput;
  }
  if (o.device.rfind("replay:", 0) == 0) {
    if (!o.case_path.empty()) {
      print_error("exercise: CASE is not used with --device replay: (the session's own case, as placed, is replayed)");
      return kBadInput;
    }
    if (o.device.size() == 7) {
      print_error("--device: replay needs a session file: replay:SESSION");
      return kBadInput;
    }
    return run_replay_exercise(o.device.substr(7), o.trainee, o.out_path, o.json, o.report);
  }
  if (const int status = check_scripted_arguments(o); status != kOk) return status;
  const auto style = scripted::style_from_string(o.style);
  const std::uint64_t seed = o.seed ? *o.seed : fresh_seed();
  std::unique_ptr<scene::Scene> scene;
  io::CaseFile placed;
  try {
    placed = scripted::place_tumours(io::load_case(o.case_path), seed, o.case_path);
    scene = std::make_unique<scene::Scene>(scene::Scene::build(placed, o.case_path));
  } catch (const io::CaseError& e) {
    for (const auto& line : e.lines()) print_error(line);
    return kBadInput;
  }

  scripted::ScriptedTrainee trainee(*scene, scripted::whole_top_contours(*scene), *style, seed);
  const auto info = scripted::exercise_session_info(placed, o.case_path, seed, *style, o.trainee,
                                                    trainee.capabilities().name, scripted::iso8601_utc_now());
  scripted::ExerciseSummary summary;
  if (const int status = record_exercise(*scene, trainee, info, o.out_path, summary); status != kOk) return status;
  std::fprintf(stderr, "exercise: %s palpated %s (seed %llu): %.1f s, %llu ticks, %lld marks, recorded in %s\n",
               o.trainee.c_str(), o.case_path.c_str(), static_cast<unsigned long long>(seed), summary.duration,
               static_cast<unsigned long long>(summary.ticks), static_cast<long long>(summary.marks),
               o.out_path.c_str());

  // Score what was recorded, read back from the file: exactly what `palpa-cli score` does.
  const int scored = score_and_report(o.out_path, o.json, o.report);
  return scored == kBadInput ? kFailure : scored;  // the session we just wrote must read back
}

}  // namespace

Command add_exercise_command(CLI::App& parent) {
  auto o = std::make_shared<ExerciseCliOptions>();
  auto* app = parent.add_subcommand(
      "exercise",
      "Run a whole scripted exercise on CASE: a scripted trainee palpates through the haptic engine at 1 kHz "
      "(deterministic, as fast as possible), the session is recorded to --out and scored; the score card "
      "(or --json) goes to standard output. Tumours with a placement rule are placed from --seed.");
  app->add_option("CASE", o->case_path,
                  "case file (JSON), or the name of a bundled case (default, flat-5x5, two-bodies, ...: the files in "
                  "share/palpa/cases of the installation); not with --device replay:");
  app->add_option("--trainee", o->trainee, "trainee id recorded in the session (with replay: default the recorded one)")
      ->check([](const std::string& id) { return id.empty() ? std::string("must not be empty") : std::string(); });
  app->add_option("--style", o->style,
                  "expert: strips a finger pad apart at light, medium and deep pressure, marks what it feels; "
                  "sloppy: gaps, medium pressure, wrong marks; light: too light to reach deep tumours "
                  "(default expert)");
  app->add_option("--seed", o->seed,
                  "seed for tumour placement and the trainee's random choices; default: a fresh one, printed and "
                  "recorded in the session")
      ->check(options::seed_value());
  app->add_option("--out", o->out_path, "session file to create (never overwritten; suggested extension .palpa)")
      ->required();
  app->add_option("--device", o->device,
                  "who palpates: scripted (default: the scripted trainee of --style) or replay:SESSION (re-scoring: "
                  "the recorded probe path of SESSION palpates its recorded case through this engine again, with its "
                  "marks; the new session goes to --out)");
  app->add_flag("--json", o->json, "print the score report as JSON instead of the score card");
  app->add_option("--report", o->report.dir,
                  "also write the session's report into this folder: STEM.html (maps and force plot), STEM.json, "
                  "STEM.xapi.json, STEM.csv; never replaces a file without --force, nor the case");
  app->add_flag("--force", o->report.force, "let --report replace report files that exist");
  add_lrs_option(app, o->report);
  return {app, [o] { return run_exercise_command(*o); }};
}

}  // namespace palpa::cli
