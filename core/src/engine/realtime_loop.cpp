#include "palpa/engine/realtime_loop.hpp"

#include <pthread.h>
#include <sched.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

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

RealtimeLoop::RealtimeLoop(Engine& engine, const RealtimeOptions& options)
    : engine_(&engine), options_(options), snapshots_(SceneSnapshot::sized_for(engine)), stats_(LoopStats{}) {}

RealtimeLoop::~RealtimeLoop() { stop(); }

std::string RealtimeLoop::start() {
  if (running_.load()) return scheduling_;
  stop_requested_.store(false);
  started_.store(0);
  thread_ = std::thread([this] { run(); });  // throws if no thread can be made: nothing set yet
  running_.store(true, std::memory_order_release);
  while (started_.load(std::memory_order_acquire) == 0) std::this_thread::yield();
  return scheduling_;
}

void RealtimeLoop::stop() {
  if (!thread_.joinable()) return;
  stop_requested_.store(true, std::memory_order_release);
  thread_.join();
  running_.store(false, std::memory_order_release);
}

const LoopStats& RealtimeLoop::stats() {
  stats_.update();
  return stats_.read();
}

void RealtimeLoop::run() {
  // Scheduling: ask, and say what we got. Runs before the first tick, so the strings and
  // system calls here are outside the loop.
  std::string message;
  if (options_.request_fifo) {
    sched_param param{};
    param.sched_priority = options_.fifo_priority;
    const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
    if (err == 0) {
      fifo_granted_.store(true, std::memory_order_release);
      message = "haptic thread: SCHED_FIFO priority " + std::to_string(options_.fifo_priority) + " granted";
    } else {
      message = std::string("haptic thread: SCHED_FIFO refused (") + std::strerror(err) +
                "); running at normal priority, expect jitter under load (grant CAP_SYS_NICE or an rtprio limit)";
    }
  } else {
    message = "haptic thread: normal priority (real-time scheduling not requested)";
  }
  if (options_.cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(static_cast<unsigned>(options_.cpu), &set);
    const int err = pthread_setaffinity_np(pthread_self(), sizeof set, &set);
    message += err == 0 ? "; pinned to CPU " + std::to_string(options_.cpu)
                        : std::string("; pinning to CPU ") + std::to_string(options_.cpu) + " refused (" +
                              std::strerror(err) + ")";
  }
  scheduling_ = message;
  started_.store(1, std::memory_order_release);

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
  double fault_until = -1.0;   // a stall or a stop keeps the fault (force ramping to 0) until then
  double stop_at = -1.0;
  int since_publish = 0;
  const int snapshot_every = std::max(1, static_cast<int>(rate / std::max(1.0, options_.snapshot_rate) + 0.5));
  int since_snapshot = 0;
  std::uint64_t tick_number = 0;
  for (;;) {
    advance(deadline, period_ns);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline, nullptr) == EINTR) {
    }  // a signal must not start the tick early
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    const double start = seconds(now) - seconds(origin);
    const double due = seconds(deadline) - seconds(origin);
    const bool overrun = start - due > 0.5 * period;
    // Watchdog: a tick that comes far too late means the loop stalled; whatever force it
    // would send now is stale, so ramp to zero from there.
    if (previous_start >= 0.0 && start - previous_start > watchdog) fault_until = start + ramp;
    if (stop_requested_.load(std::memory_order_acquire) && stop_at < 0.0) stop_at = start + ramp;
    Command command;
    while (commands_.try_pop(command)) {
      switch (command.kind) {
        case Command::Kind::Pause: paused_.store(true, std::memory_order_release); break;
        case Command::Kind::Resume: paused_.store(false, std::memory_order_release); break;
        case Command::Kind::Shear: engine_->set_shear(command.on); break;
        case Command::Kind::Dynamics: engine_->set_dynamics(command.on); break;
      }
    }
    const bool fault = paused_.load(std::memory_order_acquire) || start < fault_until || stop_at >= 0.0;

    const Sample s = engine_->tick(start, overrun, fault);
    ++tick_number;
    if (++since_snapshot >= snapshot_every) {
      snapshots_.write_slot().capture(*engine_, s, tick_number);
      snapshots_.publish();
      since_snapshot = 0;
    }
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
    if (end > due + period) {
      deadline = now;
    }
    if (stop_at >= 0.0 && start >= stop_at && s.force == std::array<double, 3>{}) break;
  }
  stats_.write_slot() = stats;
  stats_.publish();
}

}  // namespace palpa::engine
