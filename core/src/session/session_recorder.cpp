#include "palpa/session/session_recorder.hpp"

#include <algorithm>
#include <chrono>
#include <exception>
#include <string>

#include <fmt/format.h>

namespace palpa::session {

SessionRecorder::SessionRecorder(engine::RealtimeLoop& loop, SessionWriter& writer, double commit_interval)
    : loop_(&loop), writer_(&writer), commit_interval_(commit_interval) {
  // The format promises at most a second lost to a crash (docs/session-format.md).
  if (!(commit_interval > 0.0 && commit_interval <= 1.0)) {
    throw SessionError(writer.path().string(), "commit_interval",
                       fmt::format("must be in (0, 1] s, not {:f}", commit_interval));
  }
}

SessionRecorder::~SessionRecorder() {
  try {
    stop();
  } catch (...) {  // a destructor cannot report; error() kept what the thread met
  }
}

void SessionRecorder::start() {
  if (thread_.joinable() || stop_.load()) return;  // once per recorder
  thread_ = std::thread([this] { run(); });
}

void SessionRecorder::event(const Event& event) {
  // Checked here, on the caller's thread: a bad event is the caller's error, and must not
  // stop the writer thread (and with it the recording).
  check_event(writer_->path().string(), event);
  std::lock_guard lock(mutex_);
  if (stopped_) {
    throw SessionError(writer_->path().string(), "events",
                       "the recorder is stopped: nothing more is recorded (the End event is finish()'s)");
  }
  if (event.kind == EventKind::End) end_queued_ = true;
  pending_events_.push_back(event);
}

std::string SessionRecorder::error() const {
  std::lock_guard lock(mutex_);
  return error_;
}

void SessionRecorder::drain() {
  std::vector<Event> events;
  {
    std::lock_guard lock(mutex_);
    events.swap(pending_events_);
  }
  // Samples and events live in separate tables (the reader orders events by time), so
  // only the events among themselves need their time order.
  std::stable_sort(events.begin(), events.end(), [](const Event& a, const Event& b) { return a.t < b.t; });
  for (const auto& e : events) writer_->event(e);
  engine::Sample sample;
  // A bad tick (non-finite value) is stored as a fault, not refused: it must not end the recording.
  while (loop_->pop_sample(sample)) writer_->append_repairing(sample);
}

void SessionRecorder::run() {
  using clock = std::chrono::steady_clock;
  const auto interval = std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(commit_interval_));
  auto last_commit = clock::now();
  try {
    while (!stop_.load(std::memory_order_acquire)) {
      drain();
      if (clock::now() - last_commit >= interval) {
        writer_->commit();
        last_commit = clock::now();
      }
      // 5 ms of 1 kHz ticks is 5 samples: the 16384-sample ring never comes close to full.
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  } catch (const std::exception& e) {
    std::lock_guard lock(mutex_);
    error_ = e.what();
  } catch (...) {
    std::lock_guard lock(mutex_);
    error_ = "unknown error in the session writer thread";
  }
}

void SessionRecorder::stop() {
  {
    std::lock_guard lock(mutex_);
    if (stopped_) return;  // once
    stopped_ = true;       // from here event() refuses: everything queued is drained below
  }
  stop_.store(true, std::memory_order_release);
  if (thread_.joinable()) thread_.join();
  if (!error().empty()) return;  // the file keeps what was committed before the error
  // The thread has ended: this thread is now the ring's (and the statistics') only consumer.
  try {
    drain();
    writer_->set_loop_stats(loop_->stats(), loop_->dropped_samples());
    writer_->commit();
  } catch (const std::exception& e) {
    std::lock_guard lock(mutex_);
    error_ = e.what();
  }
}

void SessionRecorder::finish(double t_end, const std::string& note) {
  Event end;
  end.t = t_end;
  end.kind = EventKind::End;
  end.note = note;
  check_event(writer_->path().string(), end);
  {
    std::lock_guard lock(mutex_);
    if (!end_queued_) {
      // Queued directly (event() refuses once stopped): finish() after stop() still ends the session.
      pending_events_.push_back(end);
      end_queued_ = true;
    }
  }
  stop();
  // A session whose recording failed stays incomplete: no End after a gap.
  if (error().empty()) drain();  // what was queued after stop(): the End at least
  writer_->finish();
}

}  // namespace palpa::session
