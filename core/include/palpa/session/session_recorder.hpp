#pragma once
// The writer thread of a live session: drains the haptic loop's sample ring into a
// SessionWriter and commits every `commit_interval` seconds, so a crash loses at most that
// much. Events come from the GUI thread (event() takes a mutex: never call it from the
// haptic thread).
#include <atomic>
#include <mutex>
#include <thread>
#include <vector>

#include "palpa/engine/realtime_loop.hpp"
#include "palpa/session/session_writer.hpp"

namespace palpa::session {

class SessionRecorder {
 public:
  /// commit_interval (s) must be in (0, 1] (docs/session-format.md promises at most a
  /// second lost to a crash); throws SessionError otherwise.
  SessionRecorder(engine::RealtimeLoop& loop, SessionWriter& writer, double commit_interval = 0.25);
  ~SessionRecorder();  ///< stops (without finishing the session)
  SessionRecorder(const SessionRecorder&) = delete;
  SessionRecorder& operator=(const SessionRecorder&) = delete;

  void start();
  /// Queues an event; written in time order with the samples at the next drain. Throws
  /// SessionError at once for an event the file would refuse (check_event()) and after
  /// stop() (the end of a stopped session is finish()'s).
  void event(const Event& event);
  /// Drains what the loop produced so far, writes queued events, stores the loop statistics
  /// (with the samples the loop dropped) and commits; then the thread ends. Call after
  /// RealtimeLoop::stop(). A second call does nothing.
  void stop();
  /// Writes the End event if none was queued, stops (if not stopped yet), writes what is
  /// still queued and finishes the file. Unless the writer thread met an error (error()):
  /// then the file is finished as it was, without End (the session is incomplete).
  void finish(double t_end, const std::string& note = {});

  /// The first error the writer thread met (empty if none): recording stops, the file keeps
  /// what was committed. Bad samples do not stop it: they are stored with fault = 1
  /// (SessionWriter::append_repairing).
  std::string error() const;

 private:
  void run();
  void drain();
  engine::RealtimeLoop* loop_;
  SessionWriter* writer_;
  double commit_interval_;
  mutable std::mutex mutex_;
  std::vector<Event> pending_events_;
  std::string error_;
  bool end_queued_ = false;  ///< an End event was queued (finish() adds none then)
  bool stopped_ = false;     ///< stop() began: event() refuses, nothing more is queued
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace palpa::session
