#pragma once
// A trainee's live exercise, headless (the Logic under the trainee window, testable
// without Qt or VTK): the case with its tumours placed from a seed, the scene, a virtual
// device the pointer steers, the haptic engine on its real-time loop, and the session
// recorder writing every tick and every mark to the session file. finish() stops it all,
// reads the session back and scores it, exactly as `palpa-cli score` would.
//
// Threads: every member function belongs to one thread (the GUI's); the haptic and writer
// threads are started by start() and stopped by finish() or the destructor.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "palpa/engine/fallback_device.hpp"
#include "palpa/engine/realtime_loop.hpp"
#include "palpa/engine/stalling_device.hpp"
#include "palpa/engine/virtual_device.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/score/score.hpp"
#include "palpa/session/session_recorder.hpp"
#include "palpa/session/session_writer.hpp"
#include "palpa/live/display_meshes.hpp"
#include "palpa/live/felt_path.hpp"
#include "palpa/live/press_control.hpp"
#include "palpa/render/surface_pick.hpp"

namespace palpa::live {

struct LiveOptions {
  std::string trainee = "trainee";    ///< recorded in the session; non-empty
  std::uint64_t seed = 0;             ///< places the tumours that have a placement rule
  std::filesystem::path session_path; ///< created by start(); must not exist
  std::string mode = "trainee";       ///< recorded in the session's extra metadata
  std::string station;                ///< the station's name (extra.station); empty: not recorded
  engine::EngineOptions engine{};
  engine::RealtimeOptions realtime{};
  /// s: how softly the virtual probe follows its target. The surface follower already limits
  /// speeds and rates (press_control.hpp); this only smooths its 60 Hz steps. Slower, the
  /// probe trails a fast slide by centimetres and overshoots where the slide turns.
  double device_settling = 0.015;
  /// The device the trainee palpates with (device/: a SpaceMouse, a Falcon, a replay);
  /// null: the virtual device the pointer steers. Its workspace is placed over the first
  /// body (centre of its rest box, top) at `device_scale` scene metres per device metre.
  /// If it faults (unplugged) the force ramps to zero and the virtual device takes over at
  /// its last pose; the session goes on (see device_switched()).
  std::shared_ptr<engine::Device> device;
  double device_scale = 1.0;
  /// Fault injection for tests and acceptance runs only: wraps the device the engine reads
  /// (the virtual device behind the pointer, or the chosen one) in an engine::StallingDevice
  /// that stalls the haptic loop 20-50 ms in bursts and now and then faults. Unset: none.
  std::optional<engine::StallOptions> inject_stalls;
  double commit_interval = 0.25;      ///< s between session commits
  render::TessellationOptions tessellation{};
};

// PressureLevel (press_control.hpp): indentation over the local tissue thickness 2R, with
// the case's score::Thresholds (light below light_max, deep from deep_min): the score's levels.

/// The haptic loop as the trainee should hear of it: running, stalled (late ticks: the
/// machine was busy; the force is held, not dropped) or faulted (the device failed: the
/// force ramps to zero). Each lasts while it does plus LiveExercise::kLoopStateHold.
enum class LoopState : std::uint8_t { Ok, Stalled, Fault };
/// "", "haptic loop stalled", "device fault".
const char* to_string(LoopState state);

struct ContactInfo {
  int body = -1;             ///< contacted body, -1 when none
  double force = 0.0;        ///< N, |F| sent to the device
  double depth = 0.0;        ///< m, indentation
  double thickness = 0.0;    ///< m, local tissue thickness 2R at the contact
  double fraction = 0.0;     ///< depth / thickness
  PressureLevel level = PressureLevel::None;
  /// Pa: the apparent firmness here at this depth (apparent_firmness()): the tissue's
  /// modulus times the tumours' contrast; 0 without contact or for a body given in N/m.
  double firmness = 0.0;
  /// N/m: force over depth (the secant stiffness, never negative), what force mode shows
  /// for a body given in N/m; 0 without contact.
  double stiffness = 0.0;
  bool force_mode = false;   ///< the finger presses to a force (force_target), not a share
  double force_target = 0.0; ///< N, in force mode
  bool at_force_bound = false;  ///< the press is held at force_bound (SurfaceFollower::at_force_bound)
  double force_bound = 0.0;  ///< N: where presses stop, kForceBoundShare of safety_limit
  double safety_limit = 0.0; ///< N: the case's safety gate (Thresholds::max_force)
  LoopState loop = LoopState::Ok;
  /// s between the window's last two frames that moved the finger (0 before the first): the
  /// finger follows the pointer only at these frames, so a busy computer makes it lag.
  double frame_gap = 0.0;
};
/// s: frames further apart than this make the gauge say the window is late (a tenth of a
/// second is where a pointer's lag is seen; the window aims at 60 frames a second).
inline constexpr double kLateFrame = 0.1;

struct LiveMark {
  std::int64_t id = -1;  ///< from 1, as in the session's Mark events
  double t = 0.0;        ///< s, on the haptic clock
  Vec3 position = Vec3::Zero();
};

class LiveExercise {
 public:
  /// Places the tumours (seed) and builds the scene. Throws io::CaseError naming
  /// case_source. Nothing runs and no file is written until start().
  LiveExercise(const io::CaseFile& file, const std::string& case_source, const LiveOptions& options);
  /// Stops the threads; a started session that was not finished stays incomplete.
  ~LiveExercise();
  LiveExercise(const LiveExercise&) = delete;
  LiveExercise& operator=(const LiveExercise&) = delete;

  /// Creates the session file, starts the haptic loop and the recorder, records Start.
  /// Returns the loop's scheduling line. Throws session::SessionError (e.g. the file exists).
  std::string start();
  bool started() const { return started_; }
  bool finished() const { return finished_; }

  /// Where the probe should go (m); the virtual device follows it smoothly. Without effect
  /// while a chosen device (LiveOptions::device) is in use. Stops following the pointer
  /// (aim) until the next aim().
  void set_probe_target(const Vec3& target);
  /// The mouse's way: the pointer is over this pick of a top contour (or off the bodies).
  /// update() then walks the finger along the surface to it at the pressure set with
  /// set_pressure_share / set_force_target (press_control.hpp), lifting off the bodies.
  void aim(const std::optional<render::SurfacePick>& pick);
  void set_pressure_share(double share) { follower_.set_share(share); }
  void set_force_target(double newtons) { follower_.set_force_target(newtons); }
  const SurfaceFollower& follower() const { return follower_; }
  /// Takes the newest snapshot, if a new one arrived, and re-tessellates the bodies whose
  /// version changed (meshes().changed(b)); returns true when a new snapshot arrived. Also
  /// handles a device switch (device_switched()).
  bool update();
  const engine::SceneSnapshot& snapshot() const { return loop_->snapshot(); }
  /// The drawn bodies as of the last update() (at rest before start()).
  const DisplayMeshes& meshes() const { return meshes_; }
  /// Off-screen culling: update() skips bodies the view cannot see (DisplayMeshes::set_visible).
  void set_body_visible(std::size_t body, bool visible) { meshes_.set_visible(body, visible); }
  /// Level of detail: the display tolerance (m) of the body's drawn contours
  /// (DisplayMeshes::set_tolerance), applied at the next update() with a new snapshot or
  /// refresh_meshes(). Returns true when it changed.
  bool set_body_tolerance(std::size_t body, double tolerance) { return meshes_.set_tolerance(body, tolerance); }
  /// Re-tessellates the bodies whose detail changed without waiting for a new snapshot
  /// (the view moved while the exercise is not running); returns how many changed.
  std::size_t refresh_meshes() { return meshes_.update(loop_->snapshot()); }
  /// Picks the rest top contour under a pointer ray (see surface_pick.hpp).
  std::optional<render::SurfacePick> pick(const Vec3& origin, const Vec3& direction) const {
    return picker_.pick(origin, direction);
  }
  /// The contact of the last snapshot taken by update(), with the loop's state.
  ContactInfo contact() const;
  /// The finger's path from the snapshot before the last update() that took one to that
  /// one, felt every kFeltStep (felt_path.hpp); empty after an update() that took none.
  /// What the push-back trace is fed, whatever the frame rate.
  const std::vector<FeltPoint>& felt() const { return felt_; }
  /// s of haptic time a stall or fault is still reported after it ended, so that a 60 Hz
  /// GUI shows a 20 ms stall.
  static constexpr double kLoopStateHold = 0.25;
  /// The loop's state as of the last update(): a device fault in the last kLoopStateHold,
  /// else a stall in it (or no snapshot for a while: the loop is stalled now), else Ok.
  LoopState loop_state() const;
  /// The fault-injection device, when LiveOptions::inject_stalls asked for one (else null).
  const engine::StallingDevice* stalling_device() const { return stalling_.get(); }

  /// Marks the current probe position (a Mark event); returns the mark. Throws
  /// std::logic_error unless started and not finished.
  LiveMark place_mark();
  /// Removes a standing mark (an Unmark event); false when no such mark stands.
  bool remove_mark(std::int64_t id);
  const std::vector<LiveMark>& marks() const { return marks_; }

  /// Pause: the force ramps to zero and the time does not count (Pause/Resume events).
  void pause(bool paused);
  bool paused() const { return paused_; }

  /// Stops the loop, finishes the session file, reads it back and scores it. Once only:
  /// a second call throws std::logic_error. Throws session::SessionError if the file
  /// cannot be read back.
  score::Score finish(const std::string& note = "trainee finished");
  /// The trainee gives the attempt up: stops like finish() and ends the session with an End
  /// event "abandoned: REASON" (session::kAbandonedNote), so that reports call it abandoned
  /// rather than failed and learning curves leave it out. Nothing is scored. Once only, and
  /// not after finish(): throws std::logic_error.
  void abandon(const std::string& reason);

  /// Loop statistics published by the haptic thread (GUI thread only).
  const engine::LoopStats& loop_stats() { return loop_->stats(); }
  /// The device in use: the chosen one, or the virtual device after a switch.
  const std::string& device_name() const { return fallback_.active_name(); }
  /// The chosen device faulted and the virtual device took over (seen by update()).
  bool device_switched() const { return switch_seen_; }
  /// For the GUI, once device_switched(): e.g. "SpaceMouse Pro disconnected: using the
  /// mouse (SpaceMouse Pro: read failed: ...)". Empty before.
  const std::string& device_message() const { return device_message_; }
  const scene::Scene& scene() const { return *scene_; }
  const io::CaseFile& placed_case() const { return placed_; }
  const score::Thresholds& thresholds() const { return thresholds_; }
  /// The deepest share the pressure dial offers on this case (deepest_plain_share).
  double deepest_share() const { return deepest_share_; }
  const std::filesystem::path& session_path() const { return options_.session_path; }
  std::uint64_t seed() const { return options_.seed; }

 private:
  double now() const;  ///< s on the haptic clock: the newest snapshot's t, never decreasing
  double not_before_last_event(double t) const;  ///< t, or the last event's t if that is later
  void record(const session::Event& event);
  void handle_device_switch();
  void follow();  ///< advances the surface follower and steers the virtual device
  void end(const std::string& note);  ///< stops the loop and records the End event
  void close_device_pause();
  void feel_snapshot();  ///< felt_ from the last snapshot felt to the one just taken

  LiveOptions options_;
  std::string case_source_;
  io::CaseFile placed_;
  std::unique_ptr<scene::Scene> scene_;
  score::Thresholds thresholds_;
  engine::VirtualDevice device_;
  std::shared_ptr<engine::Device> primary_;
  engine::FallbackDevice fallback_;
  std::unique_ptr<engine::StallingDevice> stalling_;  // around fallback_, when injecting
  std::unique_ptr<engine::Engine> engine_;
  std::unique_ptr<engine::RealtimeLoop> loop_;
  std::unique_ptr<session::SessionWriter> writer_;
  std::unique_ptr<session::SessionRecorder> recorder_;
  DisplayMeshes meshes_;
  render::TopContourPicker picker_;
  SurfaceFollower follower_;
  bool following_ = false;                        // aim() drives the probe target
  std::chrono::steady_clock::time_point last_follow_{};
  double frame_gap_ = 0.0;  // s between the last two follow() calls
  std::chrono::steady_clock::time_point last_fresh_{};  // when update() last got a snapshot
  scene::ProbeState felt_state_;  // felt()'s fresh probes
  std::vector<FeltPoint> felt_;
  ContactEnd felt_from_;  // the snapshot felt() last ended at
  FeltPoint felt_now_;    // what the finger felt at that snapshot: contact()'s thickness and firmness
  double deepest_share_ = PressureDial::kMaxShare;
  std::vector<LiveMark> marks_;
  std::int64_t next_mark_ = 1;
  mutable double last_event_t_ = 0.0;
  bool started_ = false;
  bool finished_ = false;
  bool paused_ = false;
  bool switch_seen_ = false;          // update() saw the fallback switch
  bool device_pause_open_ = false;    // a Pause event for the switch awaits its Resume
  std::string device_message_;
  std::string device_note_;           // what finish() adds to the End note
};

}  // namespace palpa::live
