#include "palpa/ui/force_gauge.hpp"

#include <algorithm>
#include <array>

#include <QPainter>

namespace palpa::ui {

ForceGauge::ForceGauge(double light_max, double deep_min, QWidget* parent)
    : QWidget(parent), light_max_(light_max), deep_min_(deep_min), scale_(std::max(0.8, deep_min * 1.5)) {
  setMinimumHeight(minimumSizeHint().height());
  setToolTip(tr("Indentation as a share of the local tissue thickness: light, medium and deep pressure "
                "as the score counts them"));
}

void ForceGauge::set_contact(const live::ContactInfo& contact) {
  contact_ = contact;
  update();
}

QStringList ForceGauge::lines() const {
  const QString force = QString::number(contact_.force, 'f', 1) + " N";
  if (contact_.level == live::PressureLevel::None) return {force + "  " + tr("no contact"), QString()};
  return {force + "  " + live::to_string(contact_.level),
          tr("depth %1 mm (%2 % of %3 mm)")
              .arg(contact_.depth * 1e3, 0, 'f', 1)
              .arg(contact_.fraction * 100.0, 0, 'f', 0)
              .arg(contact_.thickness * 1e3, 0, 'f', 0)};
}

QString ForceGauge::text() const {
  const auto l = lines();
  return l[1].isEmpty() ? l[0] : l[0] + "  " + l[1];
}

QSize ForceGauge::minimumSizeHint() const {
  const int line = fontMetrics().height() + 2;
  return {160, 4 + std::max(18, line + 2) + 4 + 2 * line + 4};
}

QSize ForceGauge::sizeHint() const { return {260, minimumSizeHint().height()}; }

ForceGauge::Layout ForceGauge::layout() const {
  const double line = fontMetrics().height() + 2.0;
  Layout g;
  g.bar = QRectF(4.0, 4.0, width() - 8.0, std::max(18.0, line + 2.0));
  g.force_line = QRectF(g.bar.left(), g.bar.bottom() + 4.0, g.bar.width(), line);
  g.depth_line = QRectF(g.bar.left(), g.force_line.bottom(), g.bar.width(), line);
  return g;
}

void ForceGauge::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  const Layout g = layout();
  const QRectF& bar = g.bar;
  const auto x_of = [&](double fraction) { return bar.left() + bar.width() * std::clamp(fraction / scale_, 0.0, 1.0); };
  // Bands: light, medium, deep, each named inside its own stretch of the bar.
  const std::array<double, 4> edges{0.0, light_max_, deep_min_, scale_};
  const std::array<QColor, 3> colours{QColor(120, 190, 120), QColor(235, 205, 90), QColor(225, 130, 80)};
  const std::array<QString, 3> names{tr("light"), tr("medium"), tr("deep")};
  for (std::size_t k = 0; k < 3; ++k) {
    const QRectF band(QPointF(x_of(edges[k]), bar.top()), QPointF(x_of(edges[k + 1]), bar.bottom()));
    p.setPen(Qt::NoPen);
    p.setBrush(colours[k]);
    p.drawRect(band);
    p.setPen(QColor(40, 40, 40));
    const int room = static_cast<int>(band.width()) - 4;
    if (room > 0) p.drawText(band, Qt::AlignCenter, fontMetrics().elidedText(names[k], Qt::ElideRight, room));
  }
  // The press so far, as a dark fill, and a needle.
  if (contact_.level != live::PressureLevel::None) {
    const double x = x_of(contact_.fraction);
    p.setPen(Qt::NoPen);
    p.setBrush(QColor(0, 0, 0, 70));
    p.drawRect(QRectF(QPointF(bar.left(), bar.top() + bar.height() * 0.3), QPointF(x, bar.bottom() - bar.height() * 0.3)));
    p.setPen(QPen(Qt::black, 3.0));
    p.drawLine(QPointF(x, bar.top() - 2.0), QPointF(x, bar.bottom() + 2.0));
  }
  p.setPen(Qt::black);
  p.setBrush(Qt::NoBrush);
  p.drawRect(bar);
  const auto l = lines();
  const int room = static_cast<int>(g.force_line.width());
  QFont bold = font();
  bold.setBold(true);
  p.setFont(bold);
  p.drawText(g.force_line, Qt::AlignLeft | Qt::AlignVCenter, QFontMetrics(bold).elidedText(l[0], Qt::ElideRight, room));
  p.setFont(font());
  p.drawText(g.depth_line, Qt::AlignLeft | Qt::AlignVCenter, fontMetrics().elidedText(l[1], Qt::ElideRight, room));
}

}  // namespace palpa::ui
