#include "quit_on_signal.hpp"

#include <csignal>
#include <cstdio>

#include <fcntl.h>
#include <unistd.h>

#include <QApplication>
#include <QSocketNotifier>
#include <QWidget>

#include "palpa/ui/trainee_window.hpp"

namespace palpa::gui {

namespace {

int signal_pipe[2] = {-1, -1};

extern "C" void on_signal(int) {
  const char byte = 1;
  [[maybe_unused]] const auto written = ::write(signal_pipe[1], &byte, 1);  // async-signal-safe
}

}  // namespace

void quit_on_signals() {
  if (signal_pipe[0] >= 0 || ::pipe2(signal_pipe, O_CLOEXEC | O_NONBLOCK) != 0) return;
  auto* notifier = new QSocketNotifier(signal_pipe[0], QSocketNotifier::Read, qApp);
  QObject::connect(notifier, &QSocketNotifier::activated, qApp, [] {
    char byte = 0;
    while (::read(signal_pipe[0], &byte, 1) > 0) {
    }
    static bool asked = false;
    // Each window finishes its work in closeEvent; a running exercise ends complete without
    // asking the trainee (nobody may be at the station to answer).
    for (auto* w : QApplication::topLevelWidgets()) w->setProperty(ui::TraineeWindow::kCloseWithoutAsking, true);
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
  });
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

}  // namespace palpa::gui
