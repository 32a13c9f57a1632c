#pragma once
// The score card after Finish: pass or fail, the gates and the metrics (score::summary_text),
// and where the session was saved.
#include <QDialog>
#include <QString>

#include "palpa/score/score.hpp"

namespace palpa::ui {

class ScoreCard : public QDialog {
  Q_OBJECT
 public:
  ScoreCard(const score::Score& score, const QString& session_path, QWidget* parent = nullptr);
  /// The headline ("PASSED: 1 of 1 tumours found, 0 false marks") and the full card text.
  const QString& headline() const { return headline_; }
  const QString& text() const { return text_; }

 private:
  QString headline_;
  QString text_;
};

}  // namespace palpa::ui
