#include "palpa/ui/score_card.hpp"

#include <QDialogButtonBox>
#include <QFontDatabase>
#include <QLabel>
#include <QPlainTextEdit>
#include <QVBoxLayout>

namespace palpa::ui {

ScoreCard::ScoreCard(const score::Score& score, const QString& session_path, QWidget* parent) : QDialog(parent) {
  setWindowTitle(tr("Score card"));
  int found = 0;
  for (const auto& t : score.tumours) found += t.found ? 1 : 0;
  headline_ = QString("%1: %2 of %3 tumours found, %4 false marks, score %5 %")
                  .arg(score.passed ? "PASSED" : "NOT PASSED")
                  .arg(found)
                  .arg(score.tumours.size())
                  .arg(score.false_positives)
                  .arg(score.score * 100.0, 0, 'f', 0);
  text_ = QString::fromStdString(score::summary_text(score));

  auto* layout = new QVBoxLayout(this);
  auto* title = new QLabel(headline_, this);
  QFont big = title->font();
  big.setPointSizeF(big.pointSizeF() * 1.4);
  big.setBold(true);
  title->setFont(big);
  title->setStyleSheet(score.passed ? "color: #1b7a2a" : "color: #a33");
  layout->addWidget(title);
  auto* card = new QPlainTextEdit(text_, this);
  card->setReadOnly(true);
  card->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
  card->setMinimumSize(560, 360);
  layout->addWidget(card);
  layout->addWidget(new QLabel(tr("Session saved in %1. The tumours are shown in the view, with lines from your marks.")
                                   .arg(session_path),
                               this));
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, this);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  layout->addWidget(buttons);
}

}  // namespace palpa::ui
