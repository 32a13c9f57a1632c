#include "palpa/ui/window_frame.hpp"

#include <QEvent>
#include <QGuiApplication>
#include <QKeyEvent>
#include <QRect>
#include <QScreen>
#include <QShortcut>
#include <QWidget>
#include <QWindow>

namespace palpa::ui {
namespace {

bool is_ctrl_w(const QKeyEvent& key) {
  const auto mods = key.modifiers() & (Qt::ShiftModifier | Qt::ControlModifier | Qt::AltModifier | Qt::MetaModifier);
  return key.key() == Qt::Key_W && mods == Qt::ControlModifier;
}

/// Closes its window on a Ctrl+W that reached the window or the view without a shortcut
/// firing (no active window: no window manager, or none activated it yet).
class CloseKey : public QObject {
 public:
  explicit CloseKey(QWidget& window) : QObject(&window), window_(window) {}

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override {
    if (event->type() == QEvent::KeyPress && is_ctrl_w(*static_cast<QKeyEvent*>(event))) {
      window_.close();
      return true;
    }
    return QObject::eventFilter(watched, event);
  }

 private:
  QWidget& window_;
};

}  // namespace

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

void take_keys(QWidget& window, QWidget* focus) {
  window.activateWindow();
  window.raise();
  if (focus) focus->setFocus(Qt::ActiveWindowFocusReason);
}

void close_on_ctrl_w(QWidget& window, QWindow* view) {
  auto* shortcut = new QShortcut(QKeySequence(QObject::tr("Ctrl+W")), &window);
  QObject::connect(shortcut, &QShortcut::activated, &window, &QWidget::close);
  auto* filter = new CloseKey(window);
  window.installEventFilter(filter);
  if (view) view->installEventFilter(filter);
}

}  // namespace palpa::ui
