#include "palpa/live/live_exercise.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "palpa/scripted/exercise.hpp"
#include "palpa/scripted/tumour_placement.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/vec3.hpp"

namespace palpa::live {

namespace {

io::Thresholds thresholds_of(const io::CaseFile& placed, const std::string& source) {
  std::vector<io::Problem> problems;
  auto thresholds = io::thresholds_from_case(io::to_json(placed), problems);
  if (!problems.empty()) throw io::CaseError(source, problems);
  return thresholds;
}

engine::Device& engine_device(engine::FallbackDevice& fallback, std::unique_ptr<engine::StallingDevice>& stalling,
                              const LiveOptions& options) {
  if (options.inject_stalls) stalling = std::make_unique<engine::StallingDevice>(fallback, *options.inject_stalls);
  return stalling ? static_cast<engine::Device&>(*stalling) : fallback;
}

// The follower predicts its force bound with the probe the engine's tick runs.
FollowerOptions follower_options(const LiveOptions& options, const io::Thresholds& thresholds) {
  FollowerOptions f;
  f.force_bound = force_bound(thresholds);
  f.probe = options.engine.probe;
  f.probe.force.shear = options.engine.shear;
  return f;
}

}  // namespace

const char* to_string(LoopState state) {
  switch (state) {
    case LoopState::Stalled: return "haptic loop stalled";
    case LoopState::Fault: return "device fault";
    case LoopState::Ok: break;
  }
  return "";
}

LiveExercise::LiveExercise(const io::CaseFile& file, const std::string& case_source, const LiveOptions& options)
    : options_(options),
      case_source_(case_source),
      placed_(scripted::place_tumours(file, options.seed, case_source)),
      scene_(std::make_unique<scene::Scene>(scene::Scene::build(placed_, case_source))),
      thresholds_(thresholds_of(placed_, case_source)),
      device_(options.device_settling),
      primary_(options.device),
      // Held at least twice the ramp time, so the force is at zero before the virtual device takes over.
      fallback_(primary_.get(), device_, 2.0 * options.engine.safety.ramp_time),
      engine_(std::make_unique<engine::Engine>(*scene_, engine_device(fallback_, stalling_, options), options.engine)),
      loop_(std::make_unique<engine::RealtimeLoop>(*engine_, options.realtime)),
      meshes_(*scene_, options.engine.deform, options.tessellation),
      picker_(*scene_),
      follower_(*scene_, follower_options(options, thresholds_)),
      felt_state_(scene_->make_state()),
      deepest_share_(deepest_plain_share(*scene_, thresholds_, follower_options(options, thresholds_).probe,
                                         force_bound(thresholds_))) {
  if (options_.trainee.empty()) throw std::invalid_argument("trainee id must not be empty");
  // The follower stops at the bound from 60 Hz predictions; between two frames (a fast
  // slide onto a stiff lump) the virtual finger itself gives way at the haptic rate.
  device_.set_force_limit(force_bound(thresholds_));
  // Start the probe well above the first body, so that the first ticks touch nothing.
  if (scene_->size() > 0) {
    const auto& bounds = scene_->body(0).bounds;
    const Vec3 above(0.5 * (bounds.lo.x() + bounds.hi.x()), 0.5 * (bounds.lo.y() + bounds.hi.y()),
                     bounds.hi.z() + 0.05);
    device_.set_target(above);
    // A chosen device's workspace goes over the middle of the first body's top.
    if (primary_) primary_->place_workspace(Vec3(above.x(), above.y(), bounds.hi.z()), options_.device_scale);
  }
}

LiveExercise::~LiveExercise() {
  if (loop_) loop_->stop();
  if (recorder_) recorder_->stop();
}

std::string LiveExercise::start() {
  if (started_) throw std::logic_error("the exercise has already started");
  auto info = scripted::exercise_session_info(placed_, case_source_, options_.seed, scripted::Style::Expert,
                                              options_.trainee, fallback_.capabilities().name,
                                              scripted::iso8601_utc_now(), options_.engine.rate_hz);
  info.extra = nlohmann::json::object();  // not a scripted exercise: no style, the GUI mode instead
  info.extra["mode"] = options_.mode;
  if (!options_.station.empty()) info.extra["station"] = options_.station;
  if (options_.session_path.has_parent_path()) std::filesystem::create_directories(options_.session_path.parent_path());
  writer_ = std::make_unique<session::SessionWriter>(options_.session_path, info);
  recorder_ = std::make_unique<session::SessionRecorder>(*loop_, *writer_, options_.commit_interval);
  const std::string scheduling = loop_->start();
  recorder_->start();
  started_ = true;
  session::Event start;
  start.t = 0.0;
  start.kind = session::EventKind::Start;
  record(start);
  return scheduling;
}

void LiveExercise::set_probe_target(const Vec3& target) {
  // While a chosen device drives the probe the target waits; after a switch the virtual
  // device starts from the chosen device's last pose (handle_device_switch), then follows.
  following_ = false;
  if (primary_ && !switch_seen_) return;
  device_.set_target(target);
}

void LiveExercise::aim(const std::optional<render::SurfacePick>& pick) {
  follower_.aim(pick);
  if (!following_) last_follow_ = std::chrono::steady_clock::now();
  following_ = true;
  follow();
}

void LiveExercise::follow() {
  if (!following_) return;
  const auto now = std::chrono::steady_clock::now();
  const double dt = std::chrono::duration<double>(now - last_follow_).count();
  last_follow_ = now;
  frame_gap_ = dt;
  const auto& s = loop_->snapshot();
  const double felt = std::sqrt(s.force[0] * s.force[0] + s.force[1] * s.force[1] + s.force[2] * s.force[2]);
  // A stalled or faulted loop reports a stale or zero force: the finger waits.
  const bool hold = s.fault || loop_state() != LoopState::Ok;
  const auto target = follower_.advance(dt, felt, hold);
  if (!target || (primary_ && !switch_seen_)) return;
  device_.set_target(*target);
}

bool LiveExercise::update() {
  handle_device_switch();
  const bool fresh = loop_->update_snapshot();
  if (fresh) last_fresh_ = std::chrono::steady_clock::now();
  follow();
  felt_.clear();
  if (!fresh) return false;
  feel_snapshot();
  meshes_.update(loop_->snapshot());
  return true;
}

void LiveExercise::feel_snapshot() {
  const auto& s = loop_->snapshot();
  const ContactEnd now{s.t, Vec3(s.probe[0], s.probe[1], s.probe[2]), s.body, s.u, s.v, s.depth};
  felt_between(*scene_, felt_state_, options_.engine.probe, felt_from_, now, felt_);
  felt_from_ = now;
  felt_now_ = felt_.back();
}

LoopState LiveExercise::loop_state() const {
  const auto& s = loop_->snapshot();
  const auto& e = s.events;
  if (e.last_device_fault >= 0.0 && s.t - e.last_device_fault < kLoopStateHold) return LoopState::Fault;
  if (e.last_stall >= 0.0 && s.t - e.last_stall < kLoopStateHold) return LoopState::Stalled;
  // No snapshot for longer than the watchdog allows (they come every 8 ms): stalled now.
  const double stale = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_fresh_).count();
  const double late = options_.engine.safety.watchdog_timeout + 2.0 / std::max(1.0, options_.realtime.snapshot_rate);
  if (started_ && !finished_ && last_fresh_ != std::chrono::steady_clock::time_point{} && stale > late) {
    return LoopState::Stalled;
  }
  return LoopState::Ok;
}

ContactInfo LiveExercise::contact() const {
  const auto& s = loop_->snapshot();
  ContactInfo c;
  c.force = std::sqrt(s.force[0] * s.force[0] + s.force[1] * s.force[1] + s.force[2] * s.force[2]);
  c.loop = loop_state();
  c.frame_gap = following_ ? frame_gap_ : 0.0;
  c.force_mode = follower_.force_target() > 0.0;
  c.force_target = follower_.force_target();
  c.force_bound = follower_.force_bound();
  c.safety_limit = thresholds_.max_force;
  c.at_force_bound = following_ && follower_.on_body() && (follower_.at_force_bound() || device_.yielded() > 2e-4);
  if (s.body < 0 || static_cast<std::size_t>(s.body) >= scene_->size() || !(s.depth > 0.0)) return c;
  c.body = s.body;
  c.depth = s.depth;
  c.thickness = felt_now_.thickness;  // read when the snapshot was taken (feel_snapshot)
  c.fraction = c.thickness > 0.0 ? c.depth / c.thickness : 1.0;
  c.level = level_of(c.fraction, thresholds_);
  c.stiffness = c.force / s.depth;
  c.firmness = felt_now_.firmness;
  return c;
}

double LiveExercise::now() const {
  last_event_t_ = std::max(last_event_t_, loop_->snapshot().t);
  return last_event_t_;
}

double LiveExercise::not_before_last_event(double t) const {
  last_event_t_ = std::max(last_event_t_, t);
  return last_event_t_;
}

void LiveExercise::handle_device_switch() {
  if (!primary_ || !fallback_.switched()) return;
  if (!switch_seen_) {
    switch_seen_ = true;
    const std::string& name = primary_->capabilities().name;
    const bool unplugged = fallback_.switch_status() == engine::DeviceStatus::Disconnected;
    device_message_ = name;
    device_message_ += unplugged ? " disconnected: using the mouse" : " failed: using the mouse";
    const std::string reason = fallback_.fault_message();
    if (!reason.empty()) {
      device_message_ += " (";
      device_message_ += reason;
      device_message_ += ")";
    }
    // The virtual device takes over where the chosen one was last seen.
    device_.set_target(fallback_.last_position());
    fallback_.resume();
    device_note_ = fmt::format("{} at t = {:.3f} s", device_message_, fallback_.switched_at());
    // Recorded as a pause: the force ramps to zero and nothing is palpated until the virtual
    // device has taken over. A trainee already paused needs no second pause.
    if (started_ && !finished_ && !paused_) {
      session::Event e;
      e.t = not_before_last_event(fallback_.switched_at());  // the haptic time of the unplug
      e.kind = session::EventKind::Pause;
      e.note = "device: ";
      e.note += device_note_;
      record(e);
      device_pause_open_ = true;
    }
  }
  if (device_pause_open_ && fallback_.on_fallback()) close_device_pause();
}

void LiveExercise::close_device_pause() {
  if (!device_pause_open_) return;
  device_pause_open_ = false;
  session::Event e;
  e.t = now();
  e.kind = session::EventKind::Resume;
  e.note = "device: continuing with ";
  e.note += device_.capabilities().name;
  record(e);
}

void LiveExercise::record(const session::Event& event) { recorder_->event(event); }

LiveMark LiveExercise::place_mark() {
  if (!started_ || finished_) throw std::logic_error("marks are placed during a running exercise");
  const auto& s = loop_->snapshot();
  LiveMark mark;
  mark.id = next_mark_++;
  mark.t = now();
  mark.position = to_vec3(s.probe);
  session::Event e;
  e.t = mark.t;
  e.kind = session::EventKind::Mark;
  e.mark = mark.id;
  e.position = s.probe;
  record(e);
  marks_.push_back(mark);
  return mark;
}

bool LiveExercise::remove_mark(std::int64_t id) {
  if (!started_ || finished_) return false;
  const auto it = std::find_if(marks_.begin(), marks_.end(), [id](const LiveMark& m) { return m.id == id; });
  if (it == marks_.end()) return false;
  session::Event e;
  e.t = now();
  e.kind = session::EventKind::Unmark;
  e.mark = id;
  record(e);
  marks_.erase(it);
  return true;
}

void LiveExercise::pause(bool paused) {
  if (!started_ || finished_ || paused == paused_) return;
  close_device_pause();  // the trainee's pause follows the device's, never nests in it
  loop_->pause(paused);
  paused_ = paused;
  session::Event e;
  e.t = now();
  e.kind = paused ? session::EventKind::Pause : session::EventKind::Resume;
  record(e);
}

score::Score LiveExercise::finish(const std::string& note) {
  end(note);
  const auto recorded = session::read_session(options_.session_path);
  return score::score_session(recorded, options_.session_path.string());
}

void LiveExercise::abandon(const std::string& reason) {
  end(std::string(session::kAbandonedNote) + ": " + reason);
}

void LiveExercise::end(const std::string& note) {
  if (!started_) throw std::logic_error("the exercise has not started");
  if (finished_) throw std::logic_error("the exercise has already finished");
  handle_device_switch();
  close_device_pause();
  finished_ = true;
  loop_->stop();
  if (loop_->update_snapshot()) feel_snapshot();
  const double t_end = now();
  std::string end_note = note;
  if (!device_note_.empty()) {
    end_note += " (device: ";
    end_note += device_note_;
    end_note += ")";
  }
  recorder_->finish(t_end, end_note);
  const std::string error = recorder_->error();
  if (!error.empty()) throw session::SessionError(options_.session_path.string(), "recorder", error);
}

}  // namespace palpa::live
