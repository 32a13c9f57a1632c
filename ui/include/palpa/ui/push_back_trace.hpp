#pragma once
// The push-back trace under the force gauge (docs/perception.md): how firm the tissue
// under the sliding finger is (kPa), for the last three seconds of the stroke, over the
// stroke's baseline (dashed). A lump passing under the finger is a bump above the line, and
// the label says how far above, e.g. "12 % firmer than the stroke so far".
#include <QString>
#include <QWidget>

#include "palpa/live/stroke_trace.hpp"

namespace palpa::ui {

class PushBackTrace : public QWidget {
  Q_OBJECT
 public:
  explicit PushBackTrace(QWidget* parent = nullptr);
  /// One reading (live::StrokeTrace::feed, `skin`: where the finger went into the skin); redraws.
  void feed(double t, const Vec3& finger, double firmness, double setting, const Vec3& skin);
  /// Nothing to show (the exercise ended).
  void clear();
  const live::StrokeTrace& trace() const { return trace_; }
  /// The words over the plot: "push-back: 4.1 kPa, 18 % firmer than the stroke so far",
  /// "push-back: 4.1 kPa, steady", or what to do to get a trace.
  QString text() const;
  /// Where the plot is drawn (widget px) and its kPa range, bottom to top.
  QRectF plot() const;
  double bottom_kpa() const { return low_; }
  double top_kpa() const { return high_; }
  QSize sizeHint() const override;
  QSize minimumSizeHint() const override;

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  /// The plot's kPa range: around the newest baseline, wide enough for every point shown.
  void fit_range();
  live::StrokeTrace trace_;
  double low_ = 0.0, high_ = 1.0;  // kPa
};

}  // namespace palpa::ui
