#include "palpa/ui/screenshot.hpp"

#include <QApplication>
#include <QElapsedTimer>
#include <QPainter>
#include <QThread>
#include <QWidget>

#include "palpa/ui/vtk_view.hpp"

namespace palpa::ui {

QImage grab_window(QWidget& window) {
  window.show();
  // A few event-loop turns: the window is mapped, the GL windows initialized and painted
  // (the frame timer renders the view).
  QElapsedTimer clock;
  clock.start();
  while (clock.elapsed() < 300) {
    QApplication::processEvents(QEventLoop::AllEvents, 20);
    QThread::msleep(5);
  }
  QImage image = window.grab().toImage();
  // A VTK view draws in its own native window, which QWidget::grab() does not see: paint
  // each view's frame over its place in the widget image.
  QPainter painter(&image);
  for (auto* view : window.findChildren<VtkView*>()) {
    if (!view->isVisible()) continue;
    const QImage frame = view->frame();
    if (frame.isNull()) continue;
    painter.drawImage(QRect(view->mapTo(&window, QPoint(0, 0)), view->size()), frame);
  }
  return image;
}

bool save_screenshot(QWidget& window, const QString& path) {
  const QImage image = grab_window(window);
  return !image.isNull() && image.save(path);
}

}  // namespace palpa::ui
