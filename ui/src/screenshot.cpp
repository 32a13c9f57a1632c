#include "palpa/ui/screenshot.hpp"

#include <QApplication>
#include <QElapsedTimer>
#include <QThread>
#include <QWidget>

namespace palpa::ui {

QImage grab_window(QWidget& window) {
  window.show();
  // A few event-loop turns: the window is mapped, the GL widget initialized and painted
  // (the frame timer renders the view).
  QElapsedTimer clock;
  clock.start();
  while (clock.elapsed() < 300) {
    QApplication::processEvents(QEventLoop::AllEvents, 20);
    QThread::msleep(5);
  }
  return window.grab().toImage();
}

bool save_screenshot(QWidget& window, const QString& path) {
  const QImage image = grab_window(window);
  return !image.isNull() && image.save(path);
}

}  // namespace palpa::ui
