#pragma once
// The force gauge: how deep the trainee presses as a share of the local tissue thickness,
// over the light / medium / deep bands the score uses, with the force in newtons.
#include <QWidget>

#include "palpa/trainer/live_exercise.hpp"

namespace palpa::ui {

class ForceGauge : public QWidget {
  Q_OBJECT
 public:
  /// light_max, deep_min: the case's thresholds (fractions of the thickness 2R).
  ForceGauge(double light_max, double deep_min, QWidget* parent = nullptr);
  void set_contact(const trainer::ContactInfo& contact);
  const trainer::ContactInfo& contact() const { return contact_; }
  /// The text under the bar, e.g. "7.4 N  medium  (32 % of 41 mm)".
  QString text() const;
  QSize sizeHint() const override { return {260, 64}; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  double light_max_, deep_min_;
  double scale_;  // the bar's full length, as a fraction of the thickness
  trainer::ContactInfo contact_;
};

}  // namespace palpa::ui
