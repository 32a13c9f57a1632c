// palpa: the Palpa application. Trainee mode: palpate a case with the mouse, mark what you
// find, finish for the score card. Instructor mode: author a case (presets, tumours,
// randomization, stiffness maps) and try it. Review mode: replay a recorded session with its
// metrics. Options and the first file are checked before any window exists, so --help,
// --version and a bad case or session answer without a display; later files come from
// the windows' File menu (AppWindows).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <string>

#include <CLI/CLI.hpp>
#include <QApplication>
#include <QSurfaceFormat>
#include <QVTKOpenGLNativeWidget.h>

#include "app_windows.hpp"
#include "frame_bench.hpp"
#include "palpa/options/number_checks.hpp"
#include "quit_on_signal.hpp"
#include "palpa/author/case_draft.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/io/data_paths.hpp"
#include "palpa/score/score.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/trainer/live_exercise.hpp"
#include "palpa/ui/instructor_window.hpp"
#include "palpa/ui/review_window.hpp"
#include "palpa/ui/screenshot.hpp"
#include "palpa/ui/trainee_window.hpp"
#include "palpa/version.hpp"

namespace {

enum ExitCode : int { kOk = 0, kFailure = 1, kBadInput = 2 };

void print_error(const std::string& message) { std::fprintf(stderr, "palpa: error: %s\n", message.c_str()); }

// --screenshot: the window drawn once at its default size, saved; the exit code.
int screenshot_of(QWidget& window, const std::string& path) {
  if (palpa::ui::save_screenshot(window, QString::fromStdString(path))) return kOk;
  print_error(path + ": could not write the screenshot");
  return kFailure;
}

void init_gui_format() {
  // VTK's OpenGL needs this format on every Qt GL surface: set before QApplication exists.
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
}

// palpa --mode review --session FILE: the session is read and scored before any window
// exists, so a bad file answers with one line and exit 2 (like palpa-cli score).
int run_review(int argc, char** argv, const std::string& session_path, const std::string& screenshot,
               const palpa::gui::TraineeSettings& settings) {
  if (session_path.empty()) {
    print_error("--mode review needs --session FILE (see palpa --help)");
    return kBadInput;
  }
  palpa::session::Session session;
  palpa::score::Score score;
  try {
    session = palpa::session::read_session(session_path);
    score = palpa::score::score_session(session, session_path);
  } catch (const palpa::session::SessionError& e) {
    print_error(e.what());
    return kBadInput;
  } catch (const std::exception& e) {
    std::string line = session_path;
    line += ": ";
    line += e.what();
    print_error(line);
    return kBadInput;
  }
  init_gui_format();
  QApplication app(argc, argv);
  QApplication::setApplicationName("palpa");
  QApplication::setApplicationVersion(palpa::kVersion);
  try {
    if (!screenshot.empty()) {
      palpa::ui::ReviewWindow window(std::move(session), std::move(score), session_path);
      window.set_time(window.span().end);  // the whole exam: every mark standing at the end
      return screenshot_of(window, screenshot);
    }
    palpa::gui::AppWindows windows(settings);
    auto* window = new palpa::ui::ReviewWindow(std::move(session), std::move(score), session_path);
    windows.adopt(*window);
    window->show();
    palpa::gui::quit_on_signals();
    return QApplication::exec();
  } catch (const palpa::io::CaseError& e) {
    print_error(e.what());
    return kBadInput;
  } catch (const std::exception& e) {
    print_error(e.what());
    return kFailure;
  }
}

// palpa --mode instructor [--case FILE]: a file that cannot be read or is not JSON answers
// with one line and exit 2 before any window exists; a JSON file that is not a valid case
// opens with its problems listed, to be fixed.
int run_instructor(int argc, char** argv, const std::string& case_path, const std::string& screenshot,
                   const palpa::gui::TraineeSettings& settings) {
  palpa::author::CaseDraft draft;  // default: a new breast preset
  if (!case_path.empty()) {
    try {
      draft = palpa::author::CaseDraft::load(case_path);
    } catch (const palpa::io::CaseError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return kBadInput;
    }
  }
  init_gui_format();
  QApplication app(argc, argv);
  QApplication::setApplicationName("palpa");
  QApplication::setApplicationVersion(palpa::kVersion);
  try {
    if (!screenshot.empty()) {
      palpa::ui::InstructorWindow window(std::move(draft));
      return screenshot_of(window, screenshot);
    }
    palpa::gui::AppWindows windows(settings);
    auto* window = new palpa::ui::InstructorWindow(std::move(draft));
    window->set_sessions_dir(palpa::gui::default_session_path().parent_path());
    windows.adopt(*window);
    window->show();
    palpa::gui::quit_on_signals();
    return QApplication::exec();
  } catch (const std::exception& e) {
    print_error(e.what());
    return kFailure;
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string case_path = palpa::io::bundled_case_path("default.json").string();  // installed or build tree
  std::string mode = "trainee";
  std::string session_path;
  std::string trainee;
  std::optional<std::uint64_t> seed;
  std::string screenshot;

  CLI::App cli{"Palpa: find the hidden tumour by palpating a soft body with the mouse (the wheel sets how deep you "
               "press), mark it with M, finish for your score card.",
               "palpa"};
  cli.set_version_flag("--version", std::string("palpa ") + palpa::kVersion);
  cli.add_option("--case", case_path, "case file (JSON; default: the bundled data/cases/default.json)");
  cli.add_option("--mode", mode,
                 "trainee, instructor (author a case: --case FILE to edit it, default a new breast) or review")
      ->check(CLI::IsMember({"trainee", "instructor", "review"}));
  cli.add_option("--session", session_path,
                 "trainee: session file to record (never overwritten; default "
                 "~/.local/share/palpa/sessions/trainee-UTCTIME.palpa); review: the session file to replay");
  cli.add_option("--trainee", trainee, "trainee id recorded in the session (default: $USER)");
  cli.add_option("--seed", seed, "seed for placing the case's randomized tumours (default: a fresh one)")
      ->check(palpa::options::seed_value());
  palpa::gui::DeviceChoice device;
  cli.add_option("--device", device.id,
                 "trainee: the device to palpate with, an id from 'palpa-cli devices' (virtual = the mouse, "
                 "spacemouse, falcon, replay:SESSION; default virtual); the Device menu changes it for later exercises");
  cli.add_option("--falcon-firmware", device.falcon_firmware,
                 "with --device falcon: the Falcon firmware file to upload (you supply it; see docs/devices.md)");
  cli.add_option("--screenshot", screenshot,
                 "render the window once at its default size, save this PNG and exit (no session is recorded)");
  bool bench = false;
  palpa::gui::FrameBenchOptions bench_options;
  std::string bench_csv;
  cli.add_flag("--bench", bench,
               "measure the frame rate of the paper's Table 1 scenes (1-35 bodies) with the haptic loop at 1 kHz "
               "and a scripted finger, dynamics on and off; print a table and exit");
  cli.add_option("--seconds", bench_options.seconds, "with --bench: seconds measured per scene and mode (default 3)")
      ->check(palpa::options::finite_positive(3600.0, "s"));
  cli.add_option("--csv", bench_csv, "with --bench: also write the rows to this CSV file");
  cli.add_option("--max-bodies", bench_options.max_bodies,
                 "with --bench: only the scenes with at most this many bodies (default: all)")
      ->check(palpa::options::integer_in(1, 1000));
  cli.footer("Exit codes: 0 success, 1 failure, 2 bad input or usage.");
  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return cli.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return cli.exit(e);
  } catch (const CLI::ParseError& e) {
    print_error(std::string(e.what()) + " (see palpa --help)");
    return kBadInput;
  }

  if (bench) {
    if (!bench_csv.empty()) bench_options.csv = bench_csv;
    init_gui_format();
    QApplication app(argc, argv);
    try {
      return palpa::gui::run_frame_bench(bench_options);
    } catch (const std::exception& e) {
      print_error(e.what());
      return kFailure;
    }
  }
  if (!bench_csv.empty() || cli.count("--seconds") > 0 || cli.count("--max-bodies") > 0) {
    print_error("--seconds, --csv and --max-bodies go with --bench (see palpa --help)");
    return kBadInput;
  }
  if (trainee.empty()) {
    const char* user = std::getenv("USER");
    trainee = user && *user ? user : "trainee";
  }
  // What every trainee window opened from a File menu uses (a fresh seed and session
  // file per exercise unless --seed is given).
  const palpa::gui::TraineeSettings settings{trainee, seed, {}, device};
  if (mode == "review") return run_review(argc, argv, session_path, screenshot, settings);
  if (mode == "instructor") {
    if (!session_path.empty()) {
      print_error("--session goes with trainee or review mode; \"Try it\" records in the default sessions folder");
      return kBadInput;
    }
    return run_instructor(argc, argv, cli.count("--case") > 0 ? case_path : std::string(), screenshot, settings);
  }

  palpa::trainer::LiveOptions options;
  options.trainee = trainee;
  options.mode = mode;
  if (seed) {
    options.seed = *seed;
  } else {
    std::random_device entropy;
    options.seed = (static_cast<std::uint64_t>(entropy()) << 32) ^ entropy();
  }
  options.session_path =
      session_path.empty() ? palpa::gui::default_session_path() : std::filesystem::path(session_path);
  if (screenshot.empty() && std::filesystem::exists(options.session_path)) {
    print_error(options.session_path.string() + ": file: exists (a session is never overwritten)");
    return kBadInput;
  }

  std::unique_ptr<palpa::trainer::LiveExercise> exercise;
  try {
    if (screenshot.empty()) options.device = palpa::gui::open_chosen_device(device);
  } catch (const std::exception& e) {  // device::DeviceError, session::SessionError: one line naming the device
    print_error(e.what());
    return kBadInput;
  }
  try {
    exercise = std::make_unique<palpa::trainer::LiveExercise>(palpa::io::load_case(case_path), case_path, options);
  } catch (const palpa::io::CaseError& e) {
    std::string line = e.what();
    if (e.problems().size() > 1) {
      line += " (and ";
      line += std::to_string(e.problems().size() - 1);
      line += " more: palpa-cli validate lists them)";
    }
    std::fprintf(stderr, "%s\n", line.c_str());
    return kBadInput;
  } catch (const std::exception& e) {
    print_error(e.what());
    return kFailure;
  }

  init_gui_format();
  QApplication app(argc, argv);
  QApplication::setApplicationName("palpa");
  QApplication::setApplicationVersion(palpa::kVersion);
  try {
    const QString name = QString::fromStdString(std::filesystem::path(case_path).filename().string());
    if (!screenshot.empty()) {
      palpa::ui::TraineeWindow window(std::move(exercise), name, false);
      return screenshot_of(window, screenshot);
    }
    palpa::gui::AppWindows windows(settings);
    auto* window = new palpa::ui::TraineeWindow(std::move(exercise), name);
    windows.adopt(*window);
    window->show();
    palpa::gui::quit_on_signals();
    std::fprintf(stderr, "palpa: recording the session in %s\n", window->exercise().session_path().c_str());
    return QApplication::exec();
  } catch (const std::exception& e) {
    print_error(e.what());
    return kFailure;
  }
}
