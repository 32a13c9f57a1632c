#include "palpa/trainer/live_exercise.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "palpa/exercise/exercise.hpp"
#include "palpa/exercise/tumour_placement.hpp"
#include "palpa/session/session_reader.hpp"

namespace palpa::trainer {

const char* to_string(PressureLevel level) {
  switch (level) {
    case PressureLevel::Light: return "light";
    case PressureLevel::Medium: return "medium";
    case PressureLevel::Deep: return "deep";
    case PressureLevel::None: break;
  }
  return "none";
}

namespace {

score::Thresholds thresholds_of(const io::CaseFile& placed, const std::string& source) {
  std::vector<io::Problem> problems;
  auto thresholds = score::thresholds_from_case(io::to_json(placed), problems);
  if (!problems.empty()) throw io::CaseError(source, problems);
  return thresholds;
}

}  // namespace

LiveExercise::LiveExercise(const io::CaseFile& file, const std::string& case_source, const LiveOptions& options)
    : options_(options),
      case_source_(case_source),
      placed_(exercise::place_tumours(file, options.seed, case_source)),
      scene_(std::make_unique<scene::Scene>(scene::Scene::build(placed_, case_source))),
      thresholds_(thresholds_of(placed_, case_source)),
      device_(options.device_settling),
      engine_(std::make_unique<engine::Engine>(*scene_, device_, options.engine)),
      loop_(std::make_unique<engine::RealtimeLoop>(*engine_, options.realtime)),
      meshes_(*scene_, options.tessellation),
      picker_(*scene_) {
  if (options_.trainee.empty()) throw std::invalid_argument("trainee id must not be empty");
  // Start the probe well above the first body, so that the first ticks touch nothing.
  if (scene_->size() > 0) {
    const auto& bounds = scene_->body(0).bounds;
    const Vec3 above(0.5 * (bounds.lo.x() + bounds.hi.x()), 0.5 * (bounds.lo.y() + bounds.hi.y()),
                     bounds.hi.z() + 0.05);
    device_.set_target(above);
  }
}

LiveExercise::~LiveExercise() {
  if (loop_) loop_->stop();
  if (recorder_) recorder_->stop();
}

std::string LiveExercise::start() {
  if (started_) throw std::logic_error("the exercise has already started");
  auto info = exercise::exercise_session_info(placed_, case_source_, options_.seed, exercise::Style::Expert,
                                              options_.trainee, device_.capabilities().name,
                                              exercise::iso8601_utc_now(), options_.engine.rate_hz);
  info.extra = nlohmann::json::object();  // not a scripted exercise: no style, the GUI mode instead
  info.extra["mode"] = options_.mode;
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

void LiveExercise::set_probe_target(const Vec3& target) { device_.set_target(target); }

bool LiveExercise::update() {
  if (!loop_->update_snapshot()) return false;
  meshes_.update(loop_->snapshot());
  return true;
}

ContactInfo LiveExercise::contact() const {
  const auto& s = loop_->snapshot();
  ContactInfo c;
  c.force = std::sqrt(s.force[0] * s.force[0] + s.force[1] * s.force[1] + s.force[2] * s.force[2]);
  if (s.body < 0 || static_cast<std::size_t>(s.body) >= scene_->size() || !(s.depth > 0.0)) return c;
  c.body = s.body;
  c.depth = s.depth;
  // The rest skeleton is never changed: evaluating it here, beside the haptic thread, is safe.
  std::array<double, 4> sk{};
  scene_->body(static_cast<std::size_t>(s.body)).body.skeleton().evaluate(s.u, s.v, sk, 4);
  c.thickness = 2.0 * std::max(0.0, sk[3]);
  c.fraction = c.thickness > 0.0 ? c.depth / c.thickness : 1.0;
  c.level = c.fraction < thresholds_.light_max ? PressureLevel::Light
            : c.fraction >= thresholds_.deep_min ? PressureLevel::Deep
                                                 : PressureLevel::Medium;
  return c;
}

double LiveExercise::now() const {
  last_event_t_ = std::max(last_event_t_, loop_->snapshot().t);
  return last_event_t_;
}

void LiveExercise::record(const session::Event& event) { recorder_->event(event); }

LiveMark LiveExercise::place_mark() {
  if (!started_ || finished_) throw std::logic_error("marks are placed during a running exercise");
  const auto& s = loop_->snapshot();
  LiveMark mark;
  mark.id = next_mark_++;
  mark.t = now();
  mark.position = Vec3(s.probe[0], s.probe[1], s.probe[2]);
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
  loop_->pause(paused);
  paused_ = paused;
  session::Event e;
  e.t = now();
  e.kind = paused ? session::EventKind::Pause : session::EventKind::Resume;
  record(e);
}

score::Score LiveExercise::finish(const std::string& note) {
  if (!started_) throw std::logic_error("the exercise has not started");
  if (finished_) throw std::logic_error("the exercise has already finished");
  finished_ = true;
  loop_->stop();
  loop_->update_snapshot();
  const double t_end = now();
  recorder_->finish(t_end, note);
  const std::string error = recorder_->error();
  if (!error.empty()) throw session::SessionError(options_.session_path.string(), "recorder", error);
  const auto recorded = session::read_session(options_.session_path);
  return score::score_session(recorded, options_.session_path.string());
}

}  // namespace palpa::trainer
