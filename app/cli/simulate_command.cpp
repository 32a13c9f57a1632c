// palpa-cli simulate CASE --trajectory TRAJ.csv --out PATH [--session S.palpa]: drives the
// haptic engine with a scripted probe and writes one CSV row per haptic tick, and/or records
// the run as a session (marks become Mark events) that palpa-cli score can score.
#include <cstdio>
#include <limits>
#include <filesystem>
#include <memory>
#include <string>

#include "commands.hpp"
#include "output_guard.hpp"
#include "palpa/options/number_checks.hpp"
#include <chrono>
#include <thread>

#include "palpa/device/device_error.hpp"
#include "palpa/device/registry.hpp"
#include "palpa/device/replay_device.hpp"
#include "palpa/engine/engine.hpp"
#include "palpa/engine/realtime_loop.hpp"
#include "palpa/engine/virtual_device.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/io/csv.hpp"
#include "palpa/io/json_text.hpp"
#include "palpa/scripted/exercise.hpp"
#include "palpa/session/session.hpp"
#include "palpa/session/session_writer.hpp"
#include "palpa/version.hpp"
#include "simulate_output.hpp"
#include "timed_points.hpp"

namespace palpa::cli {
namespace {

struct SimulateOptions {
  std::string case_path;
  std::string trajectory_path;
  std::string marks_path;
  std::string out_path;
  std::string session_path;
  std::string trainee = "simulate";
  double rate = 1000.0;
  bool fast = false;
  bool realtime = false;
  bool no_dynamics = false;
  bool no_shear = false;
  bool force = false;      ///< --out may replace an existing file (never an input)
  std::string device;      ///< instead of --trajectory: replay:SESSION, or a live device with --realtime
  double duration = 0.0;   ///< s, with a live device
  std::string falcon_firmware;
};

// Reads a `t,x,y,z` file; false (after printing why) when it cannot be used.
bool read_timed_points(const std::string& path, TimeOrder order, engine::Trajectory& out) {
  try {
    out = timed_points(io::read_numeric_csv(path, {"t", "x", "y", "z"}), path, order);
    return true;
  } catch (const io::CsvError& e) {
    print_error(e.what());
    return false;
  }
}

// --out must not replace an input, nor an existing file without --force.
int check_outputs(const SimulateOptions& o) {
  if (o.out_path.empty() && o.session_path.empty()) {
    print_error("simulate: --out or --session is required (see palpa-cli simulate --help)");
    return kBadInput;
  }
  if (o.out_path.empty()) return kOk;
  std::vector<std::filesystem::path> outputs{o.out_path};
  if (!o.marks_path.empty()) outputs.emplace_back(o.out_path + ".marks.csv");
  std::vector<std::filesystem::path> inputs{o.case_path, o.trajectory_path, o.marks_path, o.falcon_firmware,
                                            o.session_path};
  if (o.device.rfind("replay:", 0) == 0) inputs.emplace_back(o.device.substr(7));
  if (auto why = refusal_to_write(outputs, o.force, inputs); !why.empty()) {
    print_error("--out: " + why);
    return kBadInput;
  }
  return kOk;
}

// What a run drives the engine with: the case, and the trajectory or a device.
struct SimulateInputs {
  io::CaseFile case_file;
  std::unique_ptr<scene::Scene> scene;
  engine::Trajectory trajectory, marks;
  std::unique_ptr<engine::Device> chosen;  ///< the --device, when given
  double duration = 0.0;                   ///< s of haptic time to run
};

// A device instead of the trajectory: a replayed session (its duration) or a live one
// (--realtime for --duration seconds, its workspace over the first body).
int open_chosen_device(const SimulateOptions& o, SimulateInputs& in) {
  const bool replay = o.device.rfind("replay:", 0) == 0;
  if (!replay && (!o.realtime || !(o.duration > 0.0))) {
    print_error("--device " + o.device + ": a live device needs --realtime and --duration SECONDS");
    return kBadInput;
  }
  if (o.device == "virtual") {
    print_error("--device virtual: nothing steers the virtual device here (the GUI's mouse does)");
    return kBadInput;
  }
  try {
    device::OpenOptions open;
    open.falcon.firmware = o.falcon_firmware;
    open.progress = [](const std::string& line) { std::fprintf(stderr, "simulate: %s\n", line.c_str()); };
    in.chosen = device::open_device(o.device, open);
  } catch (const device::DeviceError& e) {
    print_error(e.what());
    return kBadInput;
  } catch (const session::SessionError& e) {
    print_error(e.what());
    return kBadInput;
  }
  if (replay) {
    in.duration = dynamic_cast<device::ReplayDevice&>(*in.chosen).duration();
    return kOk;
  }
  in.duration = o.duration;
  if (in.scene->size() > 0) {
    const auto& b = in.scene->body(0).bounds;
    in.chosen->place_workspace(palpa::Vec3(0.5 * (b.lo.x() + b.hi.x()), 0.5 * (b.lo.y() + b.hi.y()), b.hi.z()), 1.0);
  }
  return kOk;
}

int load_inputs(const SimulateOptions& o, SimulateInputs& in) {
  try {
    in.case_file = io::load_case(o.case_path);
    in.scene = std::make_unique<scene::Scene>(scene::Scene::build(in.case_file, o.case_path));
  } catch (const io::CaseError& e) {
    for (const auto& line : e.lines()) print_error(line);
    return kBadInput;
  }
  if (o.trajectory_path.empty() == o.device.empty()) {
    print_error("simulate: give either --trajectory or --device (see palpa-cli simulate --help)");
    return kBadInput;
  }
  if (!o.trajectory_path.empty() && !read_timed_points(o.trajectory_path, TimeOrder::Increasing, in.trajectory))
    return kBadInput;
  in.duration = in.trajectory.duration();
  if (!o.device.empty()) {
    if (const int status = open_chosen_device(o, in); status != kOk) return status;
  }
  if (!o.marks_path.empty() && !read_timed_points(o.marks_path, TimeOrder::NotDecreasing, in.marks))
    return kBadInput;
  return kOk;
}

// Where the ticks go: the CSV of --out and the session of --session, with the trainee's
// marks as Mark events at their times, in order, between the ticks.
class SimulateSink {
 public:
  SimulateSink(const SimulateOptions& o, const SimulateInputs& in) : o_(o), in_(in) {}

  int open(const std::string& device_name) {
    if (!o_.out_path.empty()) {
      writer_ = std::make_unique<SampleCsvWriter>(o_.out_path);
      if (!writer_->ok()) {
        print_error(o_.out_path + ": cannot write");
        return kFailure;
      }
    }
    if (o_.session_path.empty()) return kOk;
    try {
      recording_ = std::make_unique<session::SessionWriter>(o_.session_path, session_info(device_name));
      session::Event start;
      start.kind = session::EventKind::Start;
      recording_->event(start);
    } catch (const session::SessionError& e) {
      print_error(e.what());
      return e.where() == "file" ? kBadInput : kFailure;
    }
    return kOk;
  }

  void write(const engine::Sample& s) {
    if (writer_) writer_->write(s, in_.scene->body(static_cast<std::size_t>(s.body >= 0 ? s.body : 0)).body.id());
    if (recording_) {
      record_marks_until(s.t);
      recording_->append(s);
      if (ticks_ % kCommitEvery == kCommitEvery - 1) recording_->commit();
    }
    last_t_ = s.t;
    ++ticks_;
  }

  int close() {
    if (writer_ && !writer_->close()) {
      print_error(o_.out_path + ": write failed (disk full?)");
      return kFailure;
    }
    if (writer_ && !in_.marks.t.empty() && !write_marks_csv(o_.out_path + ".marks.csv", in_.marks)) {
      print_error(o_.out_path + ".marks.csv: cannot write");
      return kFailure;
    }
    if (recording_) {
      record_marks_until(std::numeric_limits<double>::infinity());  // marks placed after the last tick
      session::Event end;
      end.kind = session::EventKind::End;
      end.t = last_t_;
      end.note = o_.device.empty() ? "trajectory ended" : "device run ended";
      recording_->event(end);
      recording_->finish();
    }
    return kOk;
  }

  std::uint64_t ticks() const { return ticks_; }

 private:
  static constexpr std::uint64_t kCommitEvery = 250;  // ticks per session transaction (0.25 s at 1 kHz)

  session::SessionInfo session_info(const std::string& device_name) const {
    session::SessionInfo info;
    info.trainee = o_.trainee;
    info.device = device_name;
    info.software_version = palpa::kVersion;
    info.started_at = scripted::iso8601_utc_now();
    info.rate_hz = o_.rate;
    info.case_source = o_.case_path;
    info.case_document = io::to_json(in_.case_file);
    info.extra = {{"recorded_by", "palpa-cli simulate"}, {"mode", "simulated"}};
    if (o_.device.empty()) {
      info.extra["trajectory"] = o_.trajectory_path;
    } else {
      info.extra["device_id"] = o_.device;
    }
    return info;
  }

  void record_marks_until(double t) {
    const engine::Trajectory& marks = in_.marks;
    for (; next_mark_ < marks.t.size() && marks.t[next_mark_] <= t; ++next_mark_) {
      session::Event mark;
      mark.kind = session::EventKind::Mark;
      mark.t = marks.t[next_mark_];
      mark.mark = static_cast<std::int64_t>(next_mark_ + 1);
      mark.position = {marks.position[next_mark_].x(), marks.position[next_mark_].y(),
                       marks.position[next_mark_].z()};
      recording_->event(mark);
    }
  }

  const SimulateOptions& o_;
  const SimulateInputs& in_;
  std::unique_ptr<SampleCsvWriter> writer_;
  std::unique_ptr<session::SessionWriter> recording_;
  std::size_t next_mark_ = 0;
  double last_t_ = 0.0;
  std::uint64_t ticks_ = 0;
};

// The haptic thread paces the ticks; this thread is the writer, draining the ring.
void run_realtime(engine::Engine& eng, double duration, SimulateSink& sink) {
  auto loop_owner = std::make_unique<engine::RealtimeLoop>(eng);  // 1.6 MB of rings: not on the stack
  auto& loop = *loop_owner;
  std::fprintf(stderr, "%s\n", loop.start().c_str());
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(duration);
  engine::Sample s;
  while (std::chrono::steady_clock::now() < end) {
    while (loop.pop_sample(s)) sink.write(s);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  loop.stop();  // ramps the force to zero first
  while (loop.pop_sample(s)) sink.write(s);
  std::fprintf(stderr, "%s\n", loop.stats().summary().c_str());
  if (loop.dropped_samples() > 0) {
    std::fprintf(stderr, "simulate: %llu samples dropped (the writer fell behind)\n",
                 static_cast<unsigned long long>(loop.dropped_samples()));
  }
}

int run_simulate(const SimulateOptions& o) {
  if (const int status = check_outputs(o); status != kOk) return status;
  SimulateInputs in;
  if (const int status = load_inputs(o, in); status != kOk) return status;
  engine::EngineOptions options;
  options.rate_hz = o.rate;
  options.dynamics = !o.no_dynamics;
  options.shear = !o.no_shear;
  engine::ScriptedDevice scripted(in.trajectory);
  engine::Device& device = in.chosen ? *in.chosen : scripted;
  engine::Engine eng(*in.scene, device, options);

  SimulateSink sink(o, in);
  if (const int status = sink.open(device.capabilities().name); status != kOk) return status;
  if (o.realtime) {
    run_realtime(eng, in.duration, sink);
  } else {
    engine::run_fast(eng, in.duration, [&sink](const engine::Sample& s) { sink.write(s); });
  }
  if (const int status = sink.close(); status != kOk) return status;
  std::fprintf(stderr, "simulate: %llu ticks at %.0f Hz (%.3f s of trajectory) written to %s\n",
               static_cast<unsigned long long>(sink.ticks()), o.rate, in.duration,
               (o.out_path.empty() ? o.session_path : o.out_path).c_str());
  return kOk;
}

}  // namespace

Command add_simulate_command(CLI::App& parent) {
  auto o = std::make_shared<SimulateOptions>();
  auto* app = parent.add_subcommand(
      "simulate", "Drive the haptic engine with a scripted probe (TRAJ.csv: header t,x,y,z in s and m, linear in "
                  "between) and write one CSV row per tick to --out: "
                  "t,x,y,z,fx,fy,fz,body,u,v,depth,buttons,overrun,fault, and/or record it as a session (--session). "
                  "--fast (the default) is deterministic: the same inputs give the same bytes.");
  app->add_option("CASE", o->case_path, "case file (JSON)")->required();
  app->add_option("--trajectory", o->trajectory_path, "probe trajectory CSV: t,x,y,z (or --device)");
  app->add_option("--device", o->device,
                  "drive the probe with a device instead of --trajectory: replay:SESSION (the probe path of a "
                  "recorded session, for its duration), or a live device from palpa-cli devices (spacemouse..., "
                  "falcon...) with --realtime for --duration seconds, its workspace over the first body");
  app->add_option("--duration", o->duration, "s: how long to run a live --device")->check(options::finite_positive(86400.0, "s"));
  app->add_option("--falcon-firmware", o->falcon_firmware,
                  "the Novint Falcon's firmware file (from Novint's driver package; Palpa cannot ship it), uploaded "
                  "when --device is a Falcon (docs/devices.md)");
  app->add_option("--out", o->out_path,
                  "output CSV of samples; never replaces a file without --force, nor any input of the command");
  app->add_flag("--force", o->force, "let --out (and OUT.marks.csv) replace files that exist");
  app->add_option(
      "--session", o->session_path,
      "also (or instead of --out) record the run as a session file (docs/session-format.md): the samples, the "
      "--marks as Mark events, the case; palpa-cli score scores it. Never overwrites a file");
  app->add_option("--trainee", o->trainee, "trainee id recorded in the --session (default: simulate)");
  app->add_option("--rate", o->rate, "haptic rate in Hz; default 1000")->check(options::finite_in(10.0, 100000.0, "Hz"));
  auto* fast = app->add_flag("--fast", o->fast, "run the ticks as fast as possible, deterministically (default)");
  app->add_flag("--realtime", o->realtime,
                "run on the real-time haptic thread at --rate for the trajectory's duration and print the loop "
                "statistics (period and compute time percentiles, missed deadlines)")
      ->excludes(fast);
  app->add_option("--marks", o->marks_path,
                  "the trainee's tumour marks, CSV t,x,y,z: Mark events in the --session, and copied to OUT.marks.csv");
  app->add_flag("--no-dynamics", o->no_dynamics, "released control points return to rest at once");
  app->add_flag("--no-shear", o->no_shear, "leave out the shear springs");
  return {app, [o] { return run_simulate(*o); }};
}

}  // namespace palpa::cli
