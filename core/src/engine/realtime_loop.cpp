#include "palpa/engine/realtime_loop.hpp"

#include <pthread.h>
#include <sched.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>

#include <fmt/format.h>

namespace palpa::engine {
namespace {

constexpr long kNanos = 1'000'000'000L;

double seconds(const timespec& t) { return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9; }

void advance(timespec& t, long ns) {
  t.tv_nsec += ns;
  while (t.tv_nsec >= kNanos) {
    t.tv_nsec -= kNanos;
    ++t.tv_sec;
  }
}

}  // namespace

// The most haptic periods the drawn bodies catch up on after lost touches: 1 s of springs,
// enough for any dent to settle, and a bounded amount of work whatever the gap.
constexpr std::uint64_t kMaxCatchUp = 1000;

RealtimeLoop::RealtimeLoop(Engine& engine, const RealtimeOptions& options)
    : engine_(&engine),
      options_(options),
      drawn_(engine),
      snapshots_(SceneSnapshot::sized_for(drawn_)),
      stats_(LoopStats{}) {}

RealtimeLoop::~RealtimeLoop() { stop(); }

std::string RealtimeLoop::start() {
  if (running_.load()) return scheduling_;
  stop_requested_.store(false);
  display_stop_.store(false);
  started_.store(0);
  display_ = std::thread([this] { run_display(); });  // throws if no thread can be made: nothing set yet
  try {
    thread_ = std::thread([this] { run(); });
  } catch (...) {
    display_stop_.store(true, std::memory_order_release);
    display_.join();
    throw;
  }
  running_.store(true, std::memory_order_release);
  while (started_.load(std::memory_order_acquire) == 0) std::this_thread::yield();
  return scheduling_;
}

void RealtimeLoop::stop() {
  if (!thread_.joinable()) return;
  stop_requested_.store(true, std::memory_order_release);
  thread_.join();
  display_stop_.store(true, std::memory_order_release);  // after the last touch was pushed
  display_.join();
  running_.store(false, std::memory_order_release);
}

int RealtimeLoop::snapshot_every() const {
  const double rate = engine_->options().rate_hz;
  return std::max(1, static_cast<int>(rate / std::max(1.0, options_.snapshot_rate) + 0.5));
}

void RealtimeLoop::run_display() {
  // Normal priority, and it may sleep: it only has to keep up on average. The snapshot is
  // published every snapshot_every() ticks of haptic time, and after the last touch.
  const int every = snapshot_every();
  int since_snapshot = 0;
  std::uint64_t last_tick = 0;
  Touch touch;
  Sample last;
  LoopEvents events;
  for (;;) {
    const bool stopping = display_stop_.load(std::memory_order_acquire);  // before draining: nothing is missed
    bool took = false;
    while (touches_.try_pop(touch)) {
      took = true;
      const std::uint64_t gap = last_tick == 0 ? 1 : std::clamp<std::uint64_t>(touch.tick - last_tick, 1, kMaxCatchUp);
      drawn_.follow(touch, static_cast<int>(gap));
      last_tick = touch.tick;
      last = touch.sample;
      events.note(touch);
      if (++since_snapshot >= every) {
        snapshots_.write_slot().capture(drawn_, last, last_tick, events);
        snapshots_.publish();
        since_snapshot = 0;
      }
    }
    if (!took) {
      if (stopping) break;
      std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
  }
  if (since_snapshot > 0) {  // the final state, so the GUI shows where the finger stopped
    snapshots_.write_slot().capture(drawn_, last, last_tick, events);
    snapshots_.publish();
  }
}

const LoopStats& RealtimeLoop::stats() {
  stats_.update();
  return stats_.read();
}

void RealtimeLoop::run() {
  // Before the first tick, so the strings and system calls here are outside the loop.
  scheduling_ = set_up_scheduling();
  started_.store(1, std::memory_order_release);
  run_haptic_loop();
}

std::string RealtimeLoop::set_up_scheduling() {
  std::string message;
  if (options_.request_fifo) {
    sched_param param{};
    param.sched_priority = options_.fifo_priority;
    const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
    if (err == 0) {
      fifo_granted_.store(true, std::memory_order_release);
      message = fmt::format("haptic thread: SCHED_FIFO priority {} granted", options_.fifo_priority);
    } else {
      message = fmt::format("haptic thread: SCHED_FIFO refused ({}); running at normal priority, expect jitter "
                            "under load (grant CAP_SYS_NICE or an rtprio limit)",
                            std::strerror(err));
    }
  } else {
    message = "haptic thread: normal priority (real-time scheduling not requested)";
  }
  if (options_.cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(static_cast<unsigned>(options_.cpu), &set);
    const int err = pthread_setaffinity_np(pthread_self(), sizeof set, &set);
    message += err == 0 ? fmt::format("; pinned to CPU {}", options_.cpu)
                        : fmt::format("; pinning to CPU {} refused ({})", options_.cpu, std::strerror(err));
  }
  return message;
}

void RealtimeLoop::apply_commands() {
  Command command;
  while (commands_.try_pop(command)) {
    switch (command.kind) {
      case Command::Kind::Pause: paused_.store(true, std::memory_order_release); break;
      case Command::Kind::Resume: paused_.store(false, std::memory_order_release); break;
      case Command::Kind::Shear: engine_->set_shear(command.on); break;
      case Command::Kind::Dynamics: engine_->set_dynamics(command.on); break;
    }
  }
}

void RealtimeLoop::run_haptic_loop() {
  const double rate = engine_->options().rate_hz;
  const long period_ns = static_cast<long>(1e9 / rate + 0.5);
  const double period = static_cast<double>(period_ns) * 1e-9;
  const double watchdog = engine_->options().safety.watchdog_timeout;
  const double ramp = engine_->options().safety.ramp_time;
  LoopStats stats;
  timespec origin{};
  clock_gettime(CLOCK_MONOTONIC, &origin);
  timespec deadline = origin;
  double previous_start = -1.0;
  double stop_at = -1.0;
  int since_publish = 0;
  std::uint64_t tick_number = 0;
  for (;;) {
    advance(deadline, period_ns);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline, nullptr) == EINTR) {
    }  // a signal must not start the tick early
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    const double start = seconds(now) - seconds(origin);
    const double due = seconds(deadline) - seconds(origin);
    // Watchdog: a tick far too late means the loop stalled (a loaded machine, a blocked
    // driver). That is not a device fault: the tick computes the force afresh from where
    // the device is now (the governor's rate limit still applies) and is marked overrun.
    const bool stall = previous_start >= 0.0 && start - previous_start > watchdog;
    const bool overrun = stall || start - due > 0.5 * period;
    if (stop_requested_.load(std::memory_order_acquire) && stop_at < 0.0) stop_at = start + ramp;
    apply_commands();
    const bool fault = paused_.load(std::memory_order_acquire) || stop_at >= 0.0;

    const Sample s = engine_->tick(start, overrun, fault);
    Touch touch = engine_->last_touch();
    touch.tick = ++tick_number;
    touch.stall = stall;
    if (!touches_.try_push(touch)) dropped_touches_.fetch_add(1, std::memory_order_relaxed);
    if (!samples_.try_push(s)) dropped_.fetch_add(1, std::memory_order_relaxed);

    clock_gettime(CLOCK_MONOTONIC, &now);
    const double end = seconds(now) - seconds(origin);
    // A deadline is missed when this tick finished after the next one was due.
    stats.record(previous_start >= 0.0 ? start - previous_start : period, end - start, end > due + period);
    previous_start = start;
    if (++since_publish >= options_.stats_every) {
      stats_.write_slot() = stats;
      stats_.publish();
      since_publish = 0;
    }
    // Behind by more than a period (a stall): restart the schedule from now, no burst of
    // catch-up ticks.
    if (end > due + period) deadline = now;
    if (stop_at >= 0.0 && start >= stop_at && s.force == std::array<double, 3>{}) break;
  }
  stats_.write_slot() = stats;
  stats_.publish();
}

}  // namespace palpa::engine
