// palpa-cli exercise --device replay:SESSION: re-scoring. The recorded hand (the probe
// path of SESSION) palpates the recorded case (its tumours as placed then) again through
// this version's haptic engine; the recorded events (marks, pauses, end) are copied at
// their times. The new session is written to --out and scored like any other.
#include "exercise_replay.hpp"

#include <cstdio>

#include "commands.hpp"
#include "palpa/device/device_error.hpp"
#include "palpa/device/replay_device.hpp"
#include "palpa/engine/engine.hpp"
#include "palpa/scripted/exercise.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/session/session_writer.hpp"
#include "palpa/version.hpp"

namespace palpa::cli {

int run_replay_exercise(const std::string& session_path, const std::string& trainee, const std::string& out_path,
                        bool json, const ReportRequest& report) {
  session::Session recorded;
  std::unique_ptr<scene::Scene> scene;
  io::CaseFile placed;
  try {
    recorded = session::read_session(session_path);
    placed = io::parse_case(recorded.info.case_document.dump(), session_path + " (recorded case)");
    scene = std::make_unique<scene::Scene>(scene::Scene::build(placed, session_path));
  } catch (const session::SessionError& e) {
    print_error(e.what());
    return kBadInput;
  } catch (const io::CaseError& e) {
    for (const auto& line : e.lines()) print_error(line);
    return kBadInput;
  }
  std::unique_ptr<device::ReplayDevice> replay;
  try {
    replay = std::make_unique<device::ReplayDevice>(recorded, session_path);
  } catch (const device::DeviceError& e) {
    print_error(e.what());
    return kBadInput;
  }
  session::SessionInfo info = recorded.info;
  info.id.clear();  // a new session
  info.trainee = trainee.empty() ? recorded.info.trainee : trainee;
  info.device = replay->capabilities().name;
  info.software_version = palpa::kVersion;
  info.started_at = scripted::iso8601_utc_now();
  info.extra["replayed_from"] = session_path;
  info.extra["mode"] = "replay";
  info.extra["replayed_session_id"] = recorded.info.id;

  engine::EngineOptions options;
  options.rate_hz = recorded.info.rate_hz;
  engine::Engine eng(*scene, *replay, options);
  const double t0 = recorded.samples.front().t;
  std::uint64_t ticks = 0;
  try {
    session::SessionWriter writer(out_path, info);
    for (const auto& e : recorded.events) writer.event(e);
    // The engine's clock starts at the first recorded sample: the samples keep the recorded times.
    for (const auto& r : recorded.samples) {
      auto s = eng.tick(r.t - t0);
      s.t = r.t;
      writer.append(s);
      if (++ticks % 1000 == 0) writer.commit();
    }
    writer.finish();
  } catch (const session::SessionError& e) {
    print_error(e.what());
    return e.where() == "file" ? kBadInput : kFailure;
  }
  std::fprintf(stderr, "exercise: replayed %s (%llu ticks, %.1f s) through the engine, recorded in %s\n",
               session_path.c_str(), static_cast<unsigned long long>(ticks), replay->duration(), out_path.c_str());
  const int scored = score_and_report(out_path, json, report);
  return scored == kBadInput ? kFailure : scored;
}

}  // namespace palpa::cli
