#pragma once
// The instructor panels' number boxes: a range, a step, decimals and a unit, committing a
// value when it is finished (one undo step per value, not per keystroke).
#include <QDoubleSpinBox>
#include <QString>

namespace palpa::ui {

inline QDoubleSpinBox* spin(QWidget* parent, double lo, double hi, double step, int decimals, const QString& suffix) {
  auto* box = new QDoubleSpinBox(parent);
  box->setRange(lo, hi);
  box->setSingleStep(step);
  box->setDecimals(decimals);
  box->setSuffix(suffix);
  box->setKeyboardTracking(false);
  return box;
}

}  // namespace palpa::ui
