#include "quit_on_signal.hpp"

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <fcntl.h>
#include <unistd.h>
#include <xcb/xcb.h>

#include <QAbstractNativeEventFilter>
#include <QApplication>
#include <QPointer>
#include <QSocketNotifier>
#include <QWidget>

#include "palpa/ui/trainee_window.hpp"

namespace palpa::gui {

namespace {

int signal_pipe[2] = {-1, -1};

extern "C" void on_signal(int number) {
  const auto byte = static_cast<char>(number);
  [[maybe_unused]] const auto written = ::write(signal_pipe[1], &byte, 1);  // async-signal-safe
}

const char* signal_name(int number) {
  switch (number) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "a signal";
  }
}

/// Marks `w` to close without a question; a running attempt in it is abandoned with `reason`.
void close_quietly(QWidget* w, const QString& reason) {
  w->setProperty(ui::TraineeWindow::kCloseWithoutAsking, true);
  w->setProperty(ui::TraineeWindow::kCloseReason, reason);
}

void on_signals_read() {
  char byte = 0;
  int number = 0;
  while (::read(signal_pipe[0], &byte, 1) > 0) number = static_cast<unsigned char>(byte);
  static bool asked = false;
  // Each window finishes its work in closeEvent; a running exercise is abandoned without
  // asking the trainee (nobody may be at the station to answer).
  for (auto* w : QApplication::topLevelWidgets()) close_quietly(w, signal_name(number));
  QApplication::closeAllWindows();
  bool open = false;
  for (auto* w : QApplication::topLevelWidgets()) open = open || w->isVisible();
  if (!open || asked) {
    QApplication::quit();
    return;
  }
  // A window kept itself open (an instructor's unsaved case, after asking): leave it to
  // the user; a second signal quits anyway.
  asked = true;
  std::fprintf(stderr, "palpa: a window is still open (unsaved changes?); send the signal again to quit anyway\n");
}

// A top-level window's X window destroyed by someone else: Qt neither closes the widget
// nor stops drawing into it (it used to record on, invisibly, at a core's worth of CPU).
class WindowGone final : public QAbstractNativeEventFilter {
 public:
  bool nativeEventFilter(const QByteArray& type, void* message, long*) override {
    if (type != "xcb_generic_event_t") return false;
    const auto* event = static_cast<const xcb_generic_event_t*>(message);
    if ((event->response_type & 0x7F) != XCB_DESTROY_NOTIFY) return false;
    const auto window = reinterpret_cast<const xcb_destroy_notify_event_t*>(event)->window;
    for (QWidget* w : QApplication::topLevelWidgets()) {
      if (!w->isVisible() || !w->testAttribute(Qt::WA_WState_Created) || w->internalWinId() != window) continue;
      QMetaObject::invokeMethod(qApp, [gone = QPointer<QWidget>(w)] {
        if (!gone) return;
        std::fprintf(stderr, "palpa: the window was destroyed: closing it\n");
        close_quietly(gone, "window destroyed");
        gone->close();
      }, Qt::QueuedConnection);
    }
    return false;
  }
};

// exit() from Qt (the X connection broke) or Xlib (a fatal I/O error): the stack is not
// unwound, so no window closes; a running attempt is abandoned here.
extern "C" void abandon_on_exit() {
  if (QApplication::instance() == nullptr) return;
  for (QWidget* w : QApplication::topLevelWidgets()) {
    auto* trainee = qobject_cast<ui::TraineeWindow*>(w);
    if (!trainee || !trainee->exercise().started() || trainee->exercise().finished()) continue;
    try {
      trainee->exercise().abandon("display lost");
      std::fprintf(stderr, "palpa: the display went away: the attempt in %s is abandoned\n",
                   trainee->exercise().session_path().c_str());
    } catch (const std::exception&) {
      // The file keeps what was committed.
    }
  }
}

}  // namespace

void quit_on_signals() {
  if (signal_pipe[0] >= 0 || ::pipe2(signal_pipe, O_CLOEXEC | O_NONBLOCK) != 0) return;
  auto* notifier = new QSocketNotifier(signal_pipe[0], QSocketNotifier::Read, qApp);
  QObject::connect(notifier, &QSocketNotifier::activated, qApp, &on_signals_read);
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGHUP, &action, nullptr);
  static WindowGone window_gone;
  qApp->installNativeEventFilter(&window_gone);
  std::atexit(abandon_on_exit);
}

}  // namespace palpa::gui
