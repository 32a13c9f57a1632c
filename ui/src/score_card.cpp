#include "palpa/ui/score_card.hpp"

#include <QDialogButtonBox>
#include <QFontDatabase>
#include <QHBoxLayout>
#include <QImage>
#include <QLabel>
#include <QPixmap>
#include <QPlainTextEdit>
#include <QStyle>
#include <QPushButton>
#include <QScrollArea>
#include <QVBoxLayout>
#include <opencv2/core.hpp>

#include "palpa/report/images.hpp"
#include "palpa/ui/window_frame.hpp"

namespace palpa::ui {
namespace {

/// An 8-bit BGR image (the report's figures) as a QImage of its own (a deep copy).
QImage to_qimage(const cv::Mat& bgr) {
  if (bgr.empty() || bgr.type() != CV_8UC3) return {};
  return QImage(bgr.data, bgr.cols, bgr.rows, static_cast<int>(bgr.step), QImage::Format_BGR888).copy();
}

/// A caption over a map scaled to the card's width; when the map cannot be drawn, the
/// reason in its place (the text card stays usable).
QLabel* add_map(QVBoxLayout* column, const QString& caption, cv::Mat (*draw)(const score::Score&),
                const score::Score& score, QWidget* parent) {
  auto* title = new QLabel(caption, parent);
  QFont bold = title->font();
  bold.setBold(true);
  title->setFont(bold);
  column->addWidget(title);
  auto* map = new QLabel(parent);
  QImage q;
  try {
    q = to_qimage(draw(score));
  } catch (const std::exception& e) {
    map->setText(QObject::tr("(map not drawn: %1)").arg(e.what()));
    column->addWidget(map);
    return map;
  }
  if (q.isNull()) {
    map->setText(QObject::tr("(map not drawn)"));
  } else {
    map->setPixmap(QPixmap::fromImage(q.scaledToWidth(ScoreCard::kMapWidth, Qt::SmoothTransformation)));
  }
  column->addWidget(map);
  return map;
}

/// A legend under a map in the card's own font (the figure's legend is drawn for a page and
/// is too small once the map is scaled to the card): coloured squares and their meaning.
QLabel* legend(const QList<QPair<QString, QString>>& entries, QWidget* parent) {
  QString html;
  for (const auto& [colour, text] : entries) {
    html += QString("<span style='color:%1; font-size:large'>&#9632;</span>&nbsp;%2 &nbsp; ").arg(colour, text);
  }
  auto* label = new QLabel(html, parent);
  label->setTextFormat(Qt::RichText);
  label->setWordWrap(true);
  label->setMaximumWidth(ScoreCard::kMapWidth);
  return label;
}

}  // namespace

ScoreCard::ScoreCard(const score::Score& score, const QString& session_path, QWidget* parent) : QDialog(parent) {
  setWindowTitle(tr("Score card"));
  int found = 0;
  for (const auto& t : score.tumours) found += t.found ? 1 : 0;
  headline_ = QString("%1: %2 of %3 tumours found, %4 false marks, score %5 / 100")
                  .arg(score.passed ? "PASSED" : "NOT PASSED")
                  .arg(found)
                  .arg(score.tumours.size())
                  .arg(score.false_positives)
                  .arg(score.score * 100.0, 0, 'f', 1);
  text_ = QString::fromStdString(score::summary_text(score));

  auto* layout = new QVBoxLayout(this);
  auto* title = new QLabel(headline_, this);
  QFont big = title->font();
  big.setPointSizeF(big.pointSizeF() * 1.4);
  big.setBold(true);
  title->setFont(big);
  title->setStyleSheet(score.passed ? "color: #1b7a2a" : "color: #a33");
  layout->addWidget(title);
  // The text and the maps scroll when the screen is too small for them (the maps alone are
  // taller than a 1280 x 800 screen): the headline and Close stay in sight.
  auto* scroll = new QScrollArea(this);
  scroll->setObjectName("scoreCardBody");
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  auto* content = new QWidget(scroll);
  auto* body = new QHBoxLayout(content);
  body->setContentsMargins(0, 0, 0, 0);
  auto* card = new QPlainTextEdit(text_, content);
  card->setReadOnly(true);
  card->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
  card->setMinimumSize(520, 360);
  body->addWidget(card, 1);
  body->addLayout(build_maps(score, content));
  scroll->setWidget(content);
  layout->addWidget(scroll, 1);
  auto* saved = new QLabel(tr("Session saved in %1. The tumours are shown in the view, with lines from your marks.")
                               .arg(session_path),
                           this);
  saved->setWordWrap(true);
  layout->addWidget(saved);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, this);
  close_ = buttons->button(QDialogButtonBox::Close);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  layout->addWidget(buttons);
  // As wide as the text and the maps side by side, as tall as the screen allows.
  const int scrollbar = scroll->style()->pixelMetric(QStyle::PM_ScrollBarExtent);
  const QSize whole = layout->sizeHint() - scroll->sizeHint() + content->sizeHint() + QSize(scrollbar, 0);
  fit_to_screen(*this, whole);
}

// The report's own figures (OpenCV): the card and the exported HTML show the same maps.
QVBoxLayout* ScoreCard::build_maps(const score::Score& score, QWidget* parent) {
  auto* maps = new QVBoxLayout;
  auto* note = new QLabel(tr("Maps %1.").arg(QString::fromLatin1(report::kMapViewNote)), parent);
  note->setObjectName("mapView");
  note->setWordWrap(true);
  note->setMaximumWidth(kMapWidth);
  maps->addWidget(note);
  coverage_ = add_map(maps, tr("Coverage: time spent over each part of the exam region"), &report::coverage_heatmap,
                      score, parent);
  maps->addWidget(legend({{"#440154", tr("brief")}, {"#21918c", tr("longer")}, {"#fde725", tr("longest contact")},
                          {"#c8c8c8", tr("untouched")}},
                         parent));
  pressure_ = add_map(maps, tr("Pressure: deepest level reached (light, medium, deep)"), &report::pressure_map, score,
                      parent);
  maps->addWidget(legend({{"#c8c8c8", tr("untouched")}, {"#c6dbef", tr("light")}, {"#6baed6", tr("medium")},
                          {"#08519c", tr("deep")}},
                         parent));
  maps->addStretch(1);
  return maps;
}

}  // namespace palpa::ui
