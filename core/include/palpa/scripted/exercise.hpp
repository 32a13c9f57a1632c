#pragma once
// A whole scripted exercise, run deterministically: the engine ticks at its rate (1 kHz by
// default) as in engine::run_fast, the scripted trainee palpates, and every sample and
// event (Start at t = 0, the trainee's Marks, End) goes to the caller's sinks, e.g. a
// session::SessionWriter (CLI) or vectors (tests).
#include <cstdint>
#include <optional>
#include <string>

#include "palpa/engine/engine.hpp"
#include "palpa/scripted/scripted_trainee.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/session/session.hpp"

namespace palpa::scripted {

struct ExerciseOptions {
  engine::EngineOptions engine{};
  double tail = 0.5;            ///< s the engine keeps ticking after the trainee's plan ends
  double max_duration = 3600.0; ///< s: a plan that has not ended by then is cut (End note says so)
};

struct ExerciseSummary {
  double duration = 0.0;  ///< s, time of the last sample (= the End event's t)
  std::uint64_t ticks = 0;
  std::int64_t marks = 0;
  bool plan_complete = false;  ///< false when max_duration cut the plan short
};

/// Runs the exercise: sample_sink(const engine::Sample&) for every tick and
/// event_sink(const session::Event&) for every event, in time order (an event's t never
/// exceeds the next sample's t). Same inputs, same calls.
template <typename SampleSink, typename EventSink>
ExerciseSummary run_exercise(const scene::Scene& scene, ScriptedTrainee& trainee, SampleSink&& sample_sink,
                             EventSink&& event_sink, const ExerciseOptions& options = {}) {
  engine::Engine engine(scene, trainee, options.engine);
  const double rate = engine.options().rate_hz;
  ExerciseSummary summary;
  session::Event event;
  event.t = 0.0;
  event.kind = session::EventKind::Start;
  event_sink(static_cast<const session::Event&>(event));
  const auto last_tick = static_cast<std::uint64_t>(options.max_duration * rate + 0.5);
  std::optional<std::uint64_t> stop;  // tick at which to stop, once the plan has ended
  double t = 0.0;
  for (std::uint64_t k = 0; k <= last_tick; ++k) {
    t = static_cast<double>(k) / rate;
    const engine::Sample sample = engine.tick(t);
    sample_sink(sample);
    ++summary.ticks;
    while (trainee.pop_event(event)) {
      if (event.kind == session::EventKind::Mark) ++summary.marks;
      event_sink(static_cast<const session::Event&>(event));
    }
    if (!stop && trainee.finished()) {
      summary.plan_complete = true;
      stop = k + static_cast<std::uint64_t>(options.tail * rate + 0.5);
    }
    if (stop && k >= *stop) break;
  }
  summary.duration = t;
  session::Event end;
  end.t = t;
  end.kind = session::EventKind::End;
  end.note = summary.plan_complete ? "scripted exam complete" : "scripted exam cut at the maximum duration";
  event_sink(static_cast<const session::Event&>(end));
  return summary;
}

/// "2026-11-22T16:40:00Z" for a time in seconds since the Unix epoch (UTC).
std::string iso8601_utc(std::int64_t unix_seconds);
/// The current time, as iso8601_utc.
std::string iso8601_utc_now();

/// The SessionInfo of a scripted exercise: a fresh random id, palpa::kVersion, the placed
/// case's document (io::to_json(placed): the ground truth), the seed (if tumours were
/// placed with one) and extra {"exercise_style": "expert" | "sloppy" | "light"}.
session::SessionInfo exercise_session_info(const io::CaseFile& placed, const std::string& case_source,
                                           std::optional<std::uint64_t> seed, Style style,
                                           const std::string& trainee, const std::string& device_name,
                                           const std::string& started_at, double rate_hz = 1000.0);

}  // namespace palpa::scripted
