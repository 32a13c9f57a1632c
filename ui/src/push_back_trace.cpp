#include "palpa/ui/push_back_trace.hpp"

#include <algorithm>
#include <cmath>

#include <QPainter>
#include <QPainterPath>

namespace palpa::ui {

namespace {
constexpr double kShownBump = 0.05;  // below this the label says "steady" (half a person's Weber fraction)
constexpr double kPlotLeast = 40.0;  // px: the plot at the least (a small screen)
constexpr double kPlotHeight = 90.0; // px: the plot when the panel has room
}  // namespace

PushBackTrace::PushBackTrace(QWidget* parent) : QWidget(parent) {
  setObjectName("pushBackTrace");
  setToolTip(tr("How firm the tissue under the finger is while you slide, for the last 3 seconds. The dashed "
                "line is the stroke's usual firmness: a lump passing under the finger is a bump above it. "
                "A stroke starts again when the finger leaves the body or the pressure changes."));
  setMinimumHeight(minimumSizeHint().height());
}

QSize PushBackTrace::sizeHint() const {
  return {280, static_cast<int>(kPlotHeight) + 2 * fontMetrics().lineSpacing() + 8};
}

QSize PushBackTrace::minimumSizeHint() const {
  return {160, static_cast<int>(kPlotLeast) + 2 * fontMetrics().lineSpacing() + 8};
}

void PushBackTrace::feed(double t, const Vec3& finger, double firmness, double setting, const Vec3& skin) {
  const std::size_t before = trace_.points().size();
  trace_.feed(t, finger, firmness, setting, skin);
  if (trace_.points().empty() && before == 0) return;  // nothing shown, nothing to show
  fit_range();
  update();
}

void PushBackTrace::clear() {
  trace_.feed(0.0, Vec3::Zero(), 0.0, 0.0);
  update();
}

void PushBackTrace::fit_range() {
  if (trace_.points().empty()) return;
  const double base = trace_.points().back().baseline * 1e-3;
  double lo = 0.8 * base, hi = 1.4 * base;  // a 20 % bump fills a third of the plot
  for (const auto& p : trace_.points()) {
    lo = std::min(lo, p.firmness * 1e-3);
    hi = std::max(hi, p.firmness * 1e-3);
  }
  low_ = lo;
  high_ = hi > lo ? hi : lo + 1.0;
}

QString PushBackTrace::text() const {
  const auto& points = trace_.points();
  if (points.empty()) return tr("push-back trace: slide the finger over the body, inside its thin rim");
  const double now = points.back().firmness * 1e-3;
  if (trace_.along() < live::StrokeTrace::kSettledAlong) return tr("push-back: %1 kPa, keep sliding").arg(now, 0, 'f', 1);
  const double bump = trace_.contrast() - 1.0;
  if (bump >= kShownBump)
    return tr("push-back: %1 kPa, %2 % firmer than the stroke so far").arg(now, 0, 'f', 1).arg(std::lround(100.0 * bump));
  if (bump <= -kShownBump)
    return tr("push-back: %1 kPa, %2 % softer than the stroke so far").arg(now, 0, 'f', 1).arg(std::lround(-100.0 * bump));
  return tr("push-back: %1 kPa, steady").arg(now, 0, 'f', 1);
}

QRectF PushBackTrace::plot() const {
  const double top = fontMetrics().lineSpacing() * 2.0 + 4.0;
  return {1.0, top, std::max(10.0, width() - 2.0), std::max(10.0, height() - top - 1.0)};
}

void PushBackTrace::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  const QRectF box = plot();
  p.drawText(QRectF(0, 0, width(), box.top() - 2.0), static_cast<int>(Qt::TextWordWrap) | static_cast<int>(Qt::AlignLeft | Qt::AlignTop), text());
  p.fillRect(box, palette().base());
  p.setPen(palette().mid().color());
  p.drawRect(box);
  const auto& points = trace_.points();
  if (points.size() < 2) return;
  const double t1 = points.back().t, t0 = t1 - live::StrokeTrace::kMemory;
  const auto at = [&](double t, double pa) {
    return QPointF(box.left() + box.width() * (t - t0) / live::StrokeTrace::kMemory,
                   box.bottom() - box.height() * (pa * 1e-3 - low_) / (high_ - low_));
  };
  QPainterPath line, base;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto& q = points[k];
    (k == 0 ? line.moveTo(at(q.t, q.firmness)) : line.lineTo(at(q.t, q.firmness)));
    (k == 0 ? base.moveTo(at(q.t, q.baseline)) : base.lineTo(at(q.t, q.baseline)));
  }
  // Where the tissue is firmer than the stroke's baseline, the area between them is filled:
  // a lump is a filled bump.
  QPainterPath above = line;
  for (std::size_t k = points.size(); k-- > 0;) above.lineTo(at(points[k].t, points[k].baseline));
  above.closeSubpath();
  p.save();
  p.setClipRect(box);
  QPainterPath over_baseline = base;  // the part of the plot above the dashed line
  over_baseline.lineTo(at(points.back().t, high_ * 1e3).x(), box.top() - 1.0);
  over_baseline.lineTo(at(points.front().t, high_ * 1e3).x(), box.top() - 1.0);
  over_baseline.closeSubpath();
  p.fillPath(above.intersected(over_baseline), QColor(235, 140, 60, 110));
  p.restore();
  p.setPen(QPen(palette().dark().color(), 1.0, Qt::DashLine));
  p.drawPath(base);
  p.setPen(QPen(QColor(200, 90, 20), 2.0));
  p.drawPath(line);
  QFont small = font();
  small.setPointSizeF(font().pointSizeF() * 0.85);
  p.setFont(small);
  p.setPen(palette().text().color());
  p.drawText(box.adjusted(3, 1, -3, -1), Qt::AlignLeft | Qt::AlignTop, tr("%1 kPa").arg(high_, 0, 'f', 1));
  p.drawText(box.adjusted(3, 1, -3, -1), Qt::AlignLeft | Qt::AlignBottom, tr("%1 kPa").arg(low_, 0, 'f', 1));
  p.drawText(box.adjusted(3, 1, -3, -1), Qt::AlignRight | Qt::AlignBottom, tr("last 3 s"));
}

}  // namespace palpa::ui
