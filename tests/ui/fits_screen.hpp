#pragma once
// A window (or dialog) that a person on a 1280 x 800 screen can use: its frame within
// 1280 x 730 (the screen less a title bar of about 30 px and a desktop panel of 40 px),
// inside the screen it opens on, and each button named inside the window's own geometry,
// where a click can reach it; and whatever must stay in sight at its smallest fits a
// 1024 x 600 screen too (a title bar and borders off it: 1016 x 566), the rest scrolling.
// The figures are printed for the record.
#include <QList>
#include <QRect>
#include <QScreen>
#include <QWidget>
#include <QtTest>

namespace palpa::ui::testing {

inline void check_fits_screen(QWidget& window, const QList<QWidget*>& buttons) {
  const QRect frame = window.frameGeometry();
  qInfo("%s: frame %d x %d at (%d, %d), at least %d x %d", qPrintable(window.windowTitle()), frame.width(),
        frame.height(), frame.x(), frame.y(), window.minimumSizeHint().width(), window.minimumSizeHint().height());
  QVERIFY2(frame.width() <= 1280 && frame.height() <= 730,
           qPrintable(QString("%1 x %2").arg(frame.width()).arg(frame.height())));
  QVERIFY(window.screen() && window.screen()->availableGeometry().contains(frame));
  const QSize least = window.minimumSizeHint();
  QVERIFY2(least.width() <= 1016 && least.height() <= 566,
           qPrintable(QString("at least %1 x %2").arg(least.width()).arg(least.height())));
  for (QWidget* button : buttons) {
    QVERIFY(button && button->isVisible());
    const QRect at(button->mapToGlobal(QPoint(0, 0)), button->size());
    QVERIFY2(window.geometry().contains(at),
             qPrintable(QString("%1 at (%2, %3) %4 x %5, outside the window")
                            .arg(button->objectName().isEmpty() ? button->metaObject()->className() : button->objectName())
                            .arg(at.x())
                            .arg(at.y())
                            .arg(at.width())
                            .arg(at.height())));
  }
}

}  // namespace palpa::ui::testing
