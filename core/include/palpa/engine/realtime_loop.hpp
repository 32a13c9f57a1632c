#pragma once
// The haptic thread: ticks an Engine at a fixed rate against absolute deadlines
// (clock_nanosleep with TIMER_ABSTIME), at real-time priority where the system allows it,
// handing samples to a consumer through a lock-free ring and loop statistics through a
// triple buffer. Nothing in the loop allocates, locks or does I/O.
//
// Beside it, at normal priority, the display thread: it takes every tick's Touch in order
// from a second ring, makes the drawn bodies follow it (DrawnScene: the refined display
// nets are pressed and spring back) and publishes the scene snapshot the GUI draws. The
// drawn bodies cost what their refined nets cost, which is the display's business, not the
// 1 kHz deadline's; the force never depends on them.
#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

#include "palpa/engine/drawn_scene.hpp"
#include "palpa/engine/engine.hpp"
#include "palpa/engine/loop_stats.hpp"
#include "palpa/engine/scene_snapshot.hpp"
#include "palpa/engine/spsc_queue.hpp"
#include "palpa/engine/triple_buffer.hpp"

namespace palpa::engine {

/// A command from the GUI (or any one other thread) to the haptic thread.
struct Command {
  enum class Kind : std::uint8_t { Pause, Resume, Shear, Dynamics };
  Kind kind = Kind::Pause;
  bool on = false;  ///< for Shear and Dynamics
};

struct RealtimeOptions {
  bool request_fifo = true;    ///< ask for SCHED_FIFO; the outcome is reported, never ignored
  int fifo_priority = 80;      ///< 1..99
  int cpu = -1;                ///< pin the thread to this CPU (-1: no pinning)
  int stats_every = 100;       ///< publish loop statistics every N ticks
  double snapshot_rate = 125.0;  ///< Hz: how often the scene snapshot for the GUI is published
};

/// Samples buffered between the haptic thread and the consumer: 16384 ticks, 16 s at
/// 1 kHz, so a consumer that stalls for seconds loses nothing; beyond that samples are
/// dropped (and counted), never waited for.
using SampleRing = SpscQueue<Sample, 16384>;
/// Touches buffered between the haptic thread and the display thread: 4 s at 1 kHz. A
/// display thread starved that long loses touches (counted); the drawn bodies then catch up
/// on the springs' time and follow the next touch.
using TouchRing = SpscQueue<Touch, 4096>;

class RealtimeLoop {
 public:
  RealtimeLoop(Engine& engine, const RealtimeOptions& options = {});
  ~RealtimeLoop();
  RealtimeLoop(const RealtimeLoop&) = delete;
  RealtimeLoop& operator=(const RealtimeLoop&) = delete;

  /// Starts the haptic and display threads and returns one line saying how the haptic
  /// thread is scheduled (real-time priority granted, or refused and why). start() and
  /// stop() belong to one owner thread.
  std::string start();
  /// Ramps the force to zero over the safety ramp time, then stops the haptic thread, lets
  /// the display thread draw every tick it has not yet drawn, and joins both.
  void stop();
  /// While paused the force ramps to zero and stays there; the probe is still tracked.
  /// The same state as the Pause / Resume commands.
  void pause(bool paused) { paused_.store(paused, std::memory_order_release); }
  bool running() const { return running_.load(std::memory_order_acquire); }

  /// From one other thread (the GUI): queue a command for the haptic thread; false if the
  /// queue is full (64 pending), which a GUI at 60 Hz never reaches.
  bool send(const Command& command) { return commands_.try_push(command); }

  /// Reader (one GUI thread): take the newest scene snapshot if there is a new one.
  bool update_snapshot() { return snapshots_.update(); }
  const SceneSnapshot& snapshot() const { return snapshots_.read(); }

  /// Consumer side: the next sample, if any.
  bool pop_sample(Sample& out) { return samples_.try_pop(out); }
  std::uint64_t dropped_samples() const { return dropped_.load(std::memory_order_relaxed); }
  /// Touches the display thread did not take in time (the drawn bodies skipped those ticks).
  std::uint64_t dropped_touches() const { return dropped_touches_.load(std::memory_order_relaxed); }
  /// The latest statistics the loop published (consumer thread only).
  const LoopStats& stats();
  /// True while the thread has real-time priority.
  bool realtime_priority() const { return fifo_granted_.load(std::memory_order_acquire); }

 private:
  void run();                      // the haptic thread: set_up_scheduling, then the loop
  std::string set_up_scheduling();  // SCHED_FIFO and CPU pinning as asked; says what was granted
  void run_haptic_loop();
  void apply_commands();            // pause, resume, shear, dynamics: between ticks
  void run_display();
  int snapshot_every() const;

  Engine* engine_;
  RealtimeOptions options_;
  DrawnScene drawn_;  // the display thread's alone once it runs
  SampleRing samples_;
  TouchRing touches_;
  SpscQueue<Command, 64> commands_;
  TripleBuffer<SceneSnapshot> snapshots_;
  TripleBuffer<LoopStats> stats_;
  std::atomic<bool> running_{false};
  std::atomic<bool> stop_requested_{false};
  std::atomic<bool> display_stop_{false};  // set once the haptic thread has ended
  std::atomic<bool> paused_{false};
  std::atomic<bool> fifo_granted_{false};
  std::atomic<int> started_{0};  // 0 starting, 1 reported
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<std::uint64_t> dropped_touches_{0};
  std::string scheduling_;  // written by the thread before started_ = 1
  std::thread thread_;
  std::thread display_;
};

}  // namespace palpa::engine
