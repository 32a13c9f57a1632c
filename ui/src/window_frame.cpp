#include "palpa/ui/window_frame.hpp"

#include <QGuiApplication>
#include <QRect>
#include <QScreen>
#include <QWidget>

namespace palpa::ui {

QSize fitted_size(QSize preferred, const QRect& available, QSize decoration) {
  const QSize room = kLargestFrame.boundedTo(available.size()) - decoration;
  return preferred.boundedTo(room).expandedTo(QSize(1, 1));
}

void fit_to_screen(QWidget& window, QSize preferred) {
  const QWidget* parent = window.parentWidget() ? window.parentWidget()->window() : nullptr;
  QScreen* screen = parent ? parent->screen() : window.screen();
  if (!screen) screen = QGuiApplication::primaryScreen();
  if (!screen) {
    window.resize(preferred);
    return;
  }
  // Framed already (shown once under a window manager): its own decorations.
  const QSize framed = window.frameGeometry().size() - window.geometry().size();
  const QSize decoration = framed.isEmpty() ? kDecoration : framed.expandedTo(QSize(0, 0));
  window.resize(fitted_size(preferred, screen->availableGeometry(), decoration));
}

}  // namespace palpa::ui
