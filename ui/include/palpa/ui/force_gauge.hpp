#pragma once
// The force gauge: how deep the trainee presses as a share of the local tissue thickness,
// over the light / medium / deep bands the score uses, with the force in newtons; in force
// mode the tissue's firmness (kPa; N/mm for a body given in N/m) too. It says in colour and words when the press is held
// at the safety bound, when the haptic loop stalled and when the device faulted.
#include <QColor>
#include <QRectF>
#include <QStringList>
#include <QWidget>

#include "palpa/live/live_exercise.hpp"

class QPainter;

namespace palpa::ui {

class ForceGauge : public QWidget {
  Q_OBJECT
 public:
  /// light_max, deep_min: the case's thresholds (fractions of the thickness 2R).
  ForceGauge(double light_max, double deep_min, QWidget* parent = nullptr);
  void set_contact(const live::ContactInfo& contact);
  const live::ContactInfo& contact() const { return contact_; }
  /// The two lines under the bar, e.g. "7.4 N  medium" and "depth 13.1 mm (32 % of 41 mm)";
  /// in force mode "6.0 N  firmness 28.5 kPa" and "deep: depth 25.1 mm (50 % of 50 mm)".
  /// The share is rounded down, so that it always agrees with the band named.
  QStringList lines() const;
  /// What the gauge warns of, worst first: a device fault, a stalled loop, the press held at
  /// the safety bound; None otherwise.
  enum class Alert { None, Late, Bound, Stalled, Fault };
  Alert alert() const;
  /// The colour of the first line (and the bar's frame) for an alert.
  static QColor alert_colour(Alert alert);
  /// Both lines in one, for messages and tests.
  QString text() const;
  /// Where paintEvent draws the band names and the two lines (widget pixels): they never
  /// overlap, and each line's box has the rows its words take wrapped at the gauge's width
  /// (the gauge asks its layout for more height when they need more than it has).
  /// `marker` is the strip under the bar where the needle shows the press: the needle never
  /// crosses the band names in the bar.
  struct Layout {
    QRectF bar, marker, force_line, depth_line;
  };
  Layout layout() const;
  QSize sizeHint() const override;
  QSize minimumSizeHint() const override;

 protected:
  void paintEvent(QPaintEvent* event) override;
  void resizeEvent(QResizeEvent* event) override;

 private:
  double light_max_, deep_min_;
  QString force_words() const;  // the first line after the newtons
  QString depth_words() const;  // the second line
  void paint_bands(QPainter& p, const Layout& g) const;
  void paint_marker(QPainter& p, const Layout& g) const;
  /// The rows the two lines take now; asks for a new height when that changed.
  void fit_rows();
  double row_height() const;  // px: one row of text and its spacing
  double scale_;  // the bar's full length, as a fraction of the thickness
  int rows_ = 0;  // the rows the two lines took at the last fit_rows
  live::ContactInfo contact_;
};

}  // namespace palpa::ui
