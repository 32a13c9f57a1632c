#pragma once
// The force gauge: how deep the trainee presses as a share of the local tissue thickness,
// over the light / medium / deep bands the score uses, with the force in newtons.
#include <QRectF>
#include <QStringList>
#include <QWidget>

#include "palpa/live/live_exercise.hpp"

namespace palpa::ui {

class ForceGauge : public QWidget {
  Q_OBJECT
 public:
  /// light_max, deep_min: the case's thresholds (fractions of the thickness 2R).
  ForceGauge(double light_max, double deep_min, QWidget* parent = nullptr);
  void set_contact(const live::ContactInfo& contact);
  const live::ContactInfo& contact() const { return contact_; }
  /// The two lines under the bar, e.g. "7.4 N  medium" and "depth 13.1 mm (32 % of 41 mm)".
  QStringList lines() const;
  /// Both lines in one, for messages and tests.
  QString text() const;
  /// Where paintEvent draws the band names and the two lines (widget pixels): they never
  /// overlap, and each text is elided to its box at any width.
  struct Layout {
    QRectF bar, force_line, depth_line;
  };
  Layout layout() const;
  QSize sizeHint() const override;
  QSize minimumSizeHint() const override;

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  double light_max_, deep_min_;
  double scale_;  // the bar's full length, as a fraction of the thickness
  live::ContactInfo contact_;
};

}  // namespace palpa::ui
