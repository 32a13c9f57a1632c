#include "palpa/ui/force_gauge.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <QFontMetrics>
#include <QPainter>
#include <QResizeEvent>

#include "palpa/live/press_control.hpp"

namespace palpa::ui {

namespace {

constexpr double kMarkerHeight = 7.0;  // px: the needle's strip under the bar
constexpr double kRimThickness = 1e-3; // m: thinner than this, a share of it means nothing
constexpr int kReservedRows = 3;        // the two lines' rows the gauge always has room for:
                                        // an alert's words take two at the trainee's panel width

QFont bold_of(QFont font) {
  font.setBold(true);
  return font;
}

/// Rows `text` takes wrapped at word boundaries into `width` px.
int rows_of(const QString& text, const QFont& font, double width) {
  if (text.isEmpty()) return 1;
  const QFontMetrics fm(font);
  const QRect r = fm.boundingRect(QRect(0, 0, std::max(1, static_cast<int>(width)), 1 << 20), Qt::TextWordWrap, text);
  return std::max(1, (r.height() + fm.lineSpacing() - 1) / fm.lineSpacing());
}

}  // namespace

ForceGauge::ForceGauge(double light_max, double deep_min, QWidget* parent)
    : QWidget(parent), light_max_(light_max), deep_min_(deep_min), scale_(std::max(0.8, deep_min * 1.5)) {
  setMinimumHeight(minimumSizeHint().height());
  setToolTip(tr("Indentation as a share of the local tissue thickness: light, medium and deep pressure "
                "as the score counts them. Presses stop at 90 % of the case's safety limit."));
}

void ForceGauge::set_contact(const live::ContactInfo& contact) {
  contact_ = contact;
  fit_rows();
  update();
}

void ForceGauge::fit_rows() {
  const Layout g = layout();
  const int rows = static_cast<int>(std::lround((g.depth_line.bottom() - g.force_line.top()) / row_height()));
  if (rows == rows_) return;
  rows_ = rows;
  // A wrapped line needs more rows than the gauge had (or fewer): the panel makes room.
  setMinimumHeight(minimumSizeHint().height());
}

double ForceGauge::row_height() const {
  return std::max(fontMetrics().lineSpacing(), QFontMetrics(bold_of(font())).lineSpacing()) + 2.0;
}

void ForceGauge::resizeEvent(QResizeEvent* event) {
  QWidget::resizeEvent(event);
  fit_rows();
}

ForceGauge::Alert ForceGauge::alert() const {
  if (contact_.loop == live::LoopState::Fault) return Alert::Fault;
  if (contact_.loop == live::LoopState::Stalled) return Alert::Stalled;
  if (contact_.at_force_bound) return Alert::Bound;
  return contact_.frame_gap > live::kLateFrame ? Alert::Late : Alert::None;
}

QColor ForceGauge::alert_colour(Alert alert) {
  switch (alert) {
    case Alert::Fault: return {200, 0, 0};
    case Alert::Stalled: return {170, 100, 0};
    case Alert::Bound: return {200, 70, 0};
    case Alert::Late: return {120, 90, 160};
    case Alert::None: break;
  }
  return Qt::black;
}

QString ForceGauge::force_words() const {
  switch (alert()) {
    case Alert::Fault: return tr("device fault: the force is ramped off");
    case Alert::Stalled: return tr("haptic loop stalled: the force is held");
    case Alert::Bound:
      return tr("held at %1 N: the safety limit is %2 N")
          .arg(contact_.force_bound, 0, 'f', 0)
          .arg(contact_.safety_limit, 0, 'f', 0);
    case Alert::Late:
      return tr("computer busy: the window is %1 ms late").arg(contact_.frame_gap * 1e3, 0, 'f', 0);
    case Alert::None: break;
  }
  if (contact_.level == live::PressureLevel::None) return tr("no contact");
  if (contact_.force_mode) {
    // The tissue's firmness in kPa, as a hand judges it: not the column's N/mm, which grows
    // as the tissue thins under the finger (docs/user-guide.md, "Force mode").
    if (contact_.firmness > 0.0 && contact_.thickness < live::kThinTissue) {
      return tr("firmness %1 kPa (thin tissue)").arg(contact_.firmness * 1e-3, 0, 'f', 1);
    }
    if (contact_.firmness > 0.0) return tr("firmness %1 kPa").arg(contact_.firmness * 1e-3, 0, 'f', 1);
    return tr("stiffness %1 N/mm").arg(contact_.stiffness * 1e-3, 0, 'f', 2);
  }
  return live::to_string(contact_.level);
}

QString ForceGauge::depth_words() const {
  if (contact_.level == live::PressureLevel::None) return {};
  const QString depth = tr("depth %1 mm").arg(contact_.depth * 1e3, 0, 'f', 1);
  QString line = depth;
  if (contact_.thickness < kRimThickness) {
    line = tr("%1 at the rim").arg(depth);
  } else {
    // Rounded down: 49.96 % is medium for the score and reads "49 %", never "50 % medium".
    const double percent = std::floor(contact_.fraction * 100.0 + 1e-9);
    line = tr("%1 (%2 % of %3 mm)").arg(depth).arg(percent, 0, 'f', 0).arg(contact_.thickness * 1e3, 0, 'f', 0);
  }
  // In force mode the first line has the stiffness: the band goes here.
  if (contact_.force_mode || alert() != Alert::None) line = QString(live::to_string(contact_.level)) + ": " + line;
  return line;
}

QStringList ForceGauge::lines() const {
  return {QString::number(contact_.force, 'f', 1) + " N  " + force_words(), depth_words()};
}

QString ForceGauge::text() const {
  const auto l = lines();
  return l[1].isEmpty() ? l[0] : l[0] + "  " + l[1];
}

QSize ForceGauge::minimumSizeHint() const {
  const double line = row_height();
  const int rows = std::max(kReservedRows, rows_);
  return {160, static_cast<int>(std::ceil(4 + std::max(18.0, line) + kMarkerHeight + 2 + rows * line + 4))};
}

QSize ForceGauge::sizeHint() const { return {260, minimumSizeHint().height()}; }

ForceGauge::Layout ForceGauge::layout() const {
  const double line = row_height();
  Layout g;
  g.bar = QRectF(4.0, 4.0, width() - 8.0, std::max(18.0, line));
  g.marker = QRectF(g.bar.left(), g.bar.bottom(), g.bar.width(), kMarkerHeight);
  const auto l = lines();
  const double w = g.bar.width();
  g.force_line = QRectF(g.bar.left(), g.marker.bottom() + 2.0, w, rows_of(l[0], bold_of(font()), w) * line);
  g.depth_line = QRectF(g.bar.left(), g.force_line.bottom(), w, rows_of(l[1], font(), w) * line);
  return g;
}

void ForceGauge::paint_bands(QPainter& p, const Layout& g) const {
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
  // The frame says an alert in its colour.
  p.setPen(QPen(alert_colour(alert()), alert() == Alert::None ? 1.0 : 2.0));
  p.setBrush(Qt::NoBrush);
  p.drawRect(bar);
}

// The press so far: a dark fill in the strip under the bar and a needle pointing up at the
// bar's edge, clear of the band names.
void ForceGauge::paint_marker(QPainter& p, const Layout& g) const {
  if (contact_.level == live::PressureLevel::None) return;
  const QRectF& m = g.marker;
  const double x = m.left() + m.width() * std::clamp(contact_.fraction / scale_, 0.0, 1.0);
  p.setPen(Qt::NoPen);
  p.setBrush(QColor(0, 0, 0, 70));
  p.drawRect(QRectF(QPointF(m.left(), m.top() + 1.0), QPointF(x, m.bottom() - 1.0)));
  p.setBrush(alert() == Alert::None ? QColor(Qt::black) : alert_colour(alert()));
  const std::array<QPointF, 3> needle{QPointF(x, m.top()), QPointF(x - 4.0, m.bottom()), QPointF(x + 4.0, m.bottom())};
  p.drawPolygon(needle.data(), static_cast<int>(needle.size()));
}

void ForceGauge::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  const Layout g = layout();
  paint_bands(p, g);
  paint_marker(p, g);
  // Whole words wrapped over the rows the layout gave each line: nothing is cut off.
  const auto l = lines();
  p.setFont(bold_of(font()));
  p.setPen(alert_colour(alert()));
  p.drawText(g.force_line, Qt::AlignLeft | Qt::AlignVCenter | Qt::TextWordWrap, l[0]);
  p.setFont(font());
  p.setPen(Qt::black);
  p.drawText(g.depth_line, Qt::AlignLeft | Qt::AlignVCenter | Qt::TextWordWrap, l[1]);
}

}  // namespace palpa::ui
