// Stalls and faults handled as what they are, on the real haptic loop: the mouse-driven
// LiveExercise with a fault-injection device (engine::StallingDevice) that stalls the loop
// 20-50 ms in bursts and now and then faults. In level mode and in force mode no tick's
// force rises more than 10 % above the force before the events began (a stall holds the
// force, a fault ramps it to zero and back no higher), the GUI never shows a silent 0 N on
// the body (it says "haptic loop stalled" or "device fault"), and the session file keeps
// the flags of every tick that had no force on the body.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <thread>

#include "palpa/live/live_exercise.hpp"
#include "palpa/session/session_reader.hpp"
#include "../session/session_test_support.hpp"

namespace palpa::live {
namespace {

const std::string kDefaultCase = PALPA_SOURCE_DIR "/data/cases/default.json";

using session::test::ScratchDir;  // the session tests' temporary folder

constexpr double kQuiet = 1.2;  // s of haptic time before the first injected event

LiveOptions stalling_options(const std::filesystem::path& session) {
  LiveOptions o;
  o.trainee = "t1";
  o.seed = 7;
  o.session_path = session;
  o.realtime.request_fifo = false;
  engine::StallOptions stalls;
  stalls.seed = 11;
  stalls.quiet_until = kQuiet;
  stalls.burst_every = 0.3;
  stalls.fault_every = 0.8;
  o.inject_stalls = stalls;
  return o;
}

double norm(const std::array<double, 3>& f) { return std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]); }

struct Seen {
  bool stalled = false, faulted = false;
  int silent_zero = 0;  // GUI frames with 0 N on the body and the loop said to be fine
};

// Presses beside the tumour at a steady pointer for `seconds` of wall time, as a 60 Hz GUI.
Seen press_through_events(LiveExercise& live, double seconds) {
  Seen seen;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    live.update();
    const auto c = live.contact();
    seen.stalled = seen.stalled || c.loop == LoopState::Stalled;
    seen.faulted = seen.faulted || c.loop == LoopState::Fault;
    const bool on_body = live.follower().on_body() && live.follower().press() > 0.05;
    if (on_body && live.snapshot().t > kQuiet && c.force < 1e-6 && c.loop == LoopState::Ok && !live.snapshot().fault) {
      ++seen.silent_zero;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(16));
  }
  return seen;
}

void run_mode(bool force_mode) {
  ScratchDir dir;
  const auto file = io::load_case(kDefaultCase);
  LiveExercise live(file, kDefaultCase, stalling_options(dir / "s.palpa"));
  live.start();
  live.set_pressure_share(0.35);
  if (force_mode) live.set_force_target(6.0);
  live.aim(live.pick(Vec3(0.02, 0.02, 0.5), Vec3(0, 0, -1)));
  const Seen seen = press_through_events(live, 4.0);
  live.finish();
  ASSERT_NE(live.stalling_device(), nullptr);
  EXPECT_GE(live.stalling_device()->stalls(), 3) << "the injection ran";
  EXPECT_GE(live.stalling_device()->faults(), 1);
  EXPECT_TRUE(seen.stalled) << "the GUI saw a stall";
  EXPECT_TRUE(seen.faulted) << "the GUI saw a fault";
  EXPECT_EQ(seen.silent_zero, 0) << "0 N on the body without a word";

  const auto session = session::read_session(live.session_path());
  double before = 0.0;  // the settled force just before the first event
  for (const auto& s : session.samples) {
    if (s.t > kQuiet - 0.3 && s.t < kQuiet) before = std::max(before, norm(s.force));
  }
  ASSERT_GT(before, 1.0) << "pressing before the events";
  const double ceiling = 1.1 * (force_mode ? std::max(before, 6.0) : before);
  int over = 0, unflagged_zero = 0;
  for (const auto& s : session.samples) {
    if (s.t < kQuiet) continue;
    if (norm(s.force) > ceiling) ++over;
    if (s.depth > 0.0 && norm(s.force) == 0.0 && !s.fault && !s.overrun) ++unflagged_zero;
  }
  EXPECT_EQ(over, 0) << "force above " << ceiling << " N after a stall or fault";
  EXPECT_EQ(unflagged_zero, 0);
}

TEST(LiveExerciseStalls, LevelModeHoldsThroughStallsAndRecoversNoHigher) { run_mode(false); }

TEST(LiveExerciseStalls, ForceModeDoesNotSinkDuringAFault) { run_mode(true); }

// The deepest step over the tumour through the real loop: held at the bound under the gate,
// and the contact says so for the gauge.
TEST(LiveExerciseBound, DeepestStepOverTheTumourIsHeldUnderTheGate) {
  ScratchDir dir;
  const auto file = io::load_case(kDefaultCase);
  LiveOptions o = stalling_options(dir / "b.palpa");
  o.inject_stalls.reset();
  LiveExercise live(file, kDefaultCase, o);
  live.start();
  const auto& t = live.placed_case().tumours.at(0);
  live.set_pressure_share(PressureDial(live.thresholds(), PressureDial::kSettings - 1).share());
  live.aim(live.pick(Vec3(t.center[0], t.center[1], 0.5), Vec3(0, 0, -1)));
  bool held = false;
  for (int k = 0; k < 90; ++k) {
    live.update();
    held = held || live.contact().at_force_bound;
    std::this_thread::sleep_for(std::chrono::milliseconds(16));
  }
  const auto c = live.contact();
  EXPECT_TRUE(held);
  EXPECT_DOUBLE_EQ(c.safety_limit, live.thresholds().max_force);
  EXPECT_DOUBLE_EQ(c.force_bound, kForceBoundShare * live.thresholds().max_force);
  EXPECT_GT(c.stiffness, 0.0);
  EXPECT_GT(c.firmness, 0.0);  // the default breast is given in kPa
  live.finish();
  double peak = 0.0;
  for (const auto& s : session::read_session(live.session_path()).samples) peak = std::max(peak, norm(s.force));
  EXPECT_LE(peak, live.thresholds().max_force);
  EXPECT_GT(peak, 0.85 * c.force_bound);
}

}  // namespace
}  // namespace palpa::live
