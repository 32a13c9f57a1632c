#pragma once
// The haptic thread: ticks an Engine at a fixed rate against absolute deadlines
// (clock_nanosleep with TIMER_ABSTIME), at real-time priority where the system allows it,
// handing samples to a consumer through a lock-free ring and loop statistics through a
// triple buffer. Nothing in the loop allocates, locks or does I/O.
#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

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

class RealtimeLoop {
 public:
  RealtimeLoop(Engine& engine, const RealtimeOptions& options = {});
  ~RealtimeLoop();
  RealtimeLoop(const RealtimeLoop&) = delete;
  RealtimeLoop& operator=(const RealtimeLoop&) = delete;

  /// Starts the haptic thread and returns one line saying how it is scheduled (real-time
  /// priority granted, or refused and why). start() and stop() belong to one owner thread.
  std::string start();
  /// Ramps the force to zero over the safety ramp time, then stops the thread and joins.
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
  /// The latest statistics the loop published (consumer thread only).
  const LoopStats& stats();
  /// True while the thread has real-time priority.
  bool realtime_priority() const { return fifo_granted_.load(std::memory_order_acquire); }

 private:
  void run();

  Engine* engine_;
  RealtimeOptions options_;
  SampleRing samples_;
  SpscQueue<Command, 64> commands_;
  TripleBuffer<SceneSnapshot> snapshots_;
  TripleBuffer<LoopStats> stats_;
  std::atomic<bool> running_{false};
  std::atomic<bool> stop_requested_{false};
  std::atomic<bool> paused_{false};
  std::atomic<bool> fifo_granted_{false};
  std::atomic<int> started_{0};  // 0 starting, 1 reported
  std::atomic<std::uint64_t> dropped_{0};
  std::string scheduling_;  // written by the thread before started_ = 1
  std::thread thread_;
};

}  // namespace palpa::engine
