#include "palpa/ui/force_gauge.hpp"

#include <algorithm>

#include <QPainter>

namespace palpa::ui {

ForceGauge::ForceGauge(double light_max, double deep_min, QWidget* parent)
    : QWidget(parent), light_max_(light_max), deep_min_(deep_min), scale_(std::max(0.8, deep_min * 1.5)) {
  setMinimumHeight(56);
  setToolTip(tr("Indentation as a share of the local tissue thickness: light, medium and deep pressure "
                "as the score counts them"));
}

void ForceGauge::set_contact(const trainer::ContactInfo& contact) {
  contact_ = contact;
  update();
}

QString ForceGauge::text() const {
  QString s = QString::number(contact_.force, 'f', 1) + " N";
  if (contact_.level == trainer::PressureLevel::None) return s + "  (no contact)";
  s += "  ";
  s += trainer::to_string(contact_.level);
  s += QString("  (%1 % of %2 mm)").arg(contact_.fraction * 100.0, 0, 'f', 0).arg(contact_.thickness * 1e3, 0, 'f', 0);
  return s;
}

void ForceGauge::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  const QRectF bar(4.0, 4.0, width() - 8.0, 22.0);
  const auto x_of = [&](double fraction) { return bar.left() + bar.width() * std::clamp(fraction / scale_, 0.0, 1.0); };
  // Bands: light, medium, deep.
  p.setPen(Qt::NoPen);
  p.setBrush(QColor(120, 190, 120));
  p.drawRect(QRectF(QPointF(bar.left(), bar.top()), QPointF(x_of(light_max_), bar.bottom())));
  p.setBrush(QColor(235, 205, 90));
  p.drawRect(QRectF(QPointF(x_of(light_max_), bar.top()), QPointF(x_of(deep_min_), bar.bottom())));
  p.setBrush(QColor(225, 130, 80));
  p.drawRect(QRectF(QPointF(x_of(deep_min_), bar.top()), QPointF(bar.right(), bar.bottom())));
  // The press so far, as a dark fill, and a needle.
  if (contact_.level != trainer::PressureLevel::None) {
    const double x = x_of(contact_.fraction);
    p.setBrush(QColor(0, 0, 0, 70));
    p.drawRect(QRectF(QPointF(bar.left(), bar.top() + 6.0), QPointF(x, bar.bottom() - 6.0)));
    p.setPen(QPen(Qt::black, 3.0));
    p.drawLine(QPointF(x, bar.top() - 2.0), QPointF(x, bar.bottom() + 2.0));
  }
  p.setPen(Qt::black);
  p.setBrush(Qt::NoBrush);
  p.drawRect(bar);
  p.drawText(QRectF(bar.left(), bar.bottom() + 4.0, bar.width(), 20.0), Qt::AlignLeft | Qt::AlignVCenter, text());
  p.drawText(QRectF(bar.left(), bar.bottom() + 4.0, bar.width(), 20.0), Qt::AlignRight | Qt::AlignVCenter,
             tr("light | medium | deep"));
}

}  // namespace palpa::ui
