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
#include <fmt/format.h>
#include <QApplication>
#include <QSurfaceFormat>
#include <QVTKOpenGLNativeWidget.h>

#include "app_windows.hpp"
#include "frame_bench.hpp"
#include "palpa/options/number_checks.hpp"
#include "quit_on_signal.hpp"
#include "session_upload.hpp"
#include "palpa/author/case_draft.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/io/data_paths.hpp"
#include "palpa/score/score.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/live/live_exercise.hpp"
#include "palpa/ui/instructor_window.hpp"
#include "palpa/ui/review_window.hpp"
#include "palpa/ui/screenshot.hpp"
#include "palpa/ui/trainee_window.hpp"
#include "palpa/version.hpp"

namespace {

enum ExitCode : int { kOk = 0, kFailure = 1, kBadInput = 2 };

void print_error(const std::string& message) { std::fprintf(stderr, "palpa: error: %s\n", message.c_str()); }

// A case or session file that cannot be used: one line that starts with the file, as
// everywhere in Palpa ("FILE: FIELD: problem"; palpa-cli and the File menu say the same).
void print_file_error(const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); }

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
    print_file_error(e.what());
    return kBadInput;
  } catch (const std::exception& e) {
    std::string line = session_path;
    line += ": ";
    line += e.what();
    print_file_error(line);
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
    print_file_error(e.what());
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
      print_file_error(e.what());
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

// The command line of `palpa`.
struct GuiOptions {
  std::string case_path = palpa::io::bundled_case_path("default.json").string();  // installed or build tree
  std::string mode = "trainee";
  std::string session_path;
  std::string trainee;
  std::optional<std::uint64_t> seed;
  std::string screenshot;
  palpa::gui::DeviceChoice device;
  bool bench = false;
  palpa::gui::FrameBenchOptions bench_options;
  std::string bench_csv;
};

void add_options(CLI::App& cli, GuiOptions& o) {
  cli.set_version_flag("--version", std::string("palpa ") + palpa::kVersion);
  cli.add_option("--case", o.case_path, "case file (JSON; default: the bundled data/cases/default.json)");
  cli.add_option("--mode", o.mode,
                 "trainee, instructor (author a case: --case FILE to edit it, default a new breast) or review")
      ->check(CLI::IsMember({"trainee", "instructor", "review"}));
  cli.add_option("--session", o.session_path,
                 "trainee: session file to record (never overwritten; default "
                 "~/.local/share/palpa/sessions/trainee-UTCTIME.palpa); review: the session file to replay");
  cli.add_option("--trainee", o.trainee, "trainee id recorded in the session (default: $USER)");
  cli.add_option("--seed", o.seed, "seed for placing the case's randomized tumours (default: a fresh one)")
      ->check(palpa::options::seed_value());
  cli.add_option("--device", o.device.id,
                 "trainee: the device to palpate with, an id from 'palpa-cli devices' (virtual = the mouse, "
                 "spacemouse, falcon, replay:SESSION; default virtual); the Device menu changes it for later exercises");
  cli.add_option("--falcon-firmware", o.device.falcon_firmware,
                 "with --device falcon: the Falcon firmware file to upload (you supply it; see docs/devices.md)");
  cli.add_option("--screenshot", o.screenshot,
                 "render the window once at its default size, save this PNG and exit (no session is recorded)");
  cli.add_flag("--bench", o.bench,
               "measure the frame rate of the paper's Table 1 scenes (1-35 bodies) with the haptic loop at 1 kHz "
               "and a scripted finger, dynamics on and off; print a table and exit");
  cli.add_option("--seconds", o.bench_options.seconds, "with --bench: seconds measured per scene and mode (default 3)")
      ->check(palpa::options::finite_positive(3600.0, "s"));
  cli.add_option("--csv", o.bench_csv, "with --bench: also write the rows to this CSV file");
  cli.add_flag("--no-overlay", [&o](std::int64_t) { o.bench_options.overlay = false; },
               "with --bench: the coverage overlay off (as its checkbox turns it off), to measure its cost");
  cli.add_option("--max-bodies", o.bench_options.max_bodies,
                 "with --bench: only the scenes with at most this many bodies (default: all)")
      ->check(palpa::options::integer_in(1, 1000));
  cli.add_option("--detail-px", o.bench_options.detail_px,
                 fmt::format("with --bench: the level of detail's tolerance on screen, px (default {:g}; 0 draws every "
                             "body at full detail), to measure what it buys",
                             palpa::ui::TraineeWindow::kDetailPixels))
      ->check(palpa::options::finite_in(0.0, 1000.0, "px"));
  cli.footer("Exit codes: 0 success, 1 failure, 2 bad input or usage.");
}

int run_bench(int argc, char** argv, GuiOptions& o) {
  if (!o.bench_csv.empty()) o.bench_options.csv = o.bench_csv;
  init_gui_format();
  QApplication app(argc, argv);
  try {
    return palpa::gui::run_frame_bench(o.bench_options);
  } catch (const std::exception& e) {
    print_error(e.what());
    return kFailure;
  }
}

// The live exercise of the trainee mode, before any window: the seed, the session file
// (never overwritten), the device and the case. Null after printing why it cannot start.
std::unique_ptr<palpa::live::LiveExercise> trainee_exercise(const GuiOptions& o, int& status) {
  palpa::live::LiveOptions options;
  options.trainee = o.trainee;
  options.mode = o.mode;
  options.station = palpa::gui::station_name();
  if (o.seed) {
    options.seed = *o.seed;
  } else {
    std::random_device entropy;
    options.seed = (static_cast<std::uint64_t>(entropy()) << 32) ^ entropy();
  }
  options.session_path =
      o.session_path.empty() ? palpa::gui::default_session_path() : std::filesystem::path(o.session_path);
  status = kBadInput;
  if (o.screenshot.empty() && std::filesystem::exists(options.session_path)) {
    print_file_error(options.session_path.string() + ": file: exists (a session is never overwritten)");
    return nullptr;
  }
  try {
    if (o.screenshot.empty()) options.device = palpa::gui::open_chosen_device(o.device);
  } catch (const std::exception& e) {  // device::DeviceError, session::SessionError: one line naming the device
    print_error(e.what());
    return nullptr;
  }
  try {
    return std::make_unique<palpa::live::LiveExercise>(palpa::io::load_case(o.case_path), o.case_path, options);
  } catch (const palpa::io::CaseError& e) {
    std::string line = e.what();
    if (e.problems().size() > 1) line += fmt::format(" (and {} more: palpa-cli validate lists them)", e.problems().size() - 1);
    print_file_error(line);
  } catch (const std::exception& e) {
    print_error(e.what());
    status = kFailure;
  }
  return nullptr;
}

int run_trainee(int argc, char** argv, const GuiOptions& o, const palpa::gui::TraineeSettings& settings) {
  int status = kOk;
  std::unique_ptr<palpa::live::LiveExercise> exercise = trainee_exercise(o, status);
  if (!exercise) return status;
  init_gui_format();
  QApplication app(argc, argv);
  QApplication::setApplicationName("palpa");
  QApplication::setApplicationVersion(palpa::kVersion);
  try {
    const QString name = QString::fromStdString(std::filesystem::path(o.case_path).filename().string());
    if (!o.screenshot.empty()) {
      palpa::ui::TraineeWindow window(std::move(exercise), name, false);
      return screenshot_of(window, o.screenshot);
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

}  // namespace

int main(int argc, char** argv) {
  GuiOptions o;
  CLI::App cli{"Palpa: find the hidden tumour by palpating a soft body with the mouse (the wheel sets how deep you "
               "press), mark it with M, finish for your score card.",
               "palpa"};
  add_options(cli, o);
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
  if (o.bench) return run_bench(argc, argv, o);
  if (!o.bench_csv.empty() || cli.count("--seconds") > 0 || cli.count("--max-bodies") > 0 ||
      cli.count("--no-overlay") > 0 || cli.count("--detail-px") > 0) {
    print_error("--seconds, --csv, --max-bodies, --no-overlay and --detail-px go with --bench (see palpa --help)");
    return kBadInput;
  }
  if (o.trainee.empty()) {
    const char* user = std::getenv("USER");
    o.trainee = user && *user ? user : "trainee";
  }
  // What every trainee window opened from a File menu uses (a fresh seed and session
  // file per exercise unless --seed is given).
  const palpa::gui::TraineeSettings settings{o.trainee, o.seed, {}, o.device};
  if (o.mode == "review") return run_review(argc, argv, o.session_path, o.screenshot, settings);
  if (o.mode == "instructor") {
    if (!o.session_path.empty()) {
      print_error("--session goes with trainee or review mode; \"Try it\" records in the default sessions folder");
      return kBadInput;
    }
    return run_instructor(argc, argv, cli.count("--case") > 0 ? o.case_path : std::string(), o.screenshot, settings);
  }
  return run_trainee(argc, argv, o, settings);
}
