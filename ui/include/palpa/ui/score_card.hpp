#pragma once
// The score card after Finish: pass or fail, the gates and the metrics (score::summary_text)
// beside the session's coverage heatmap and pressure map (the report's images, which reveal
// the tumours with lines from the marks), and where the session was saved. The text and the
// maps scroll when the screen is smaller than they are; the headline and Close stay in sight.
#include <QDialog>
#include <QString>

class QLabel;
class QPushButton;
class QVBoxLayout;

#include "palpa/score/score.hpp"

namespace palpa::ui {

class ScoreCard : public QDialog {
  Q_OBJECT
 public:
  ScoreCard(const score::Score& score, const QString& session_path, QWidget* parent = nullptr);
  /// The headline ("PASSED: 1 of 1 tumours found, 0 false marks") and the full card text.
  const QString& headline() const { return headline_; }
  const QString& text() const { return text_; }
  /// The maps as shown (pixmaps, scaled to kMapWidth).
  QLabel* coverage_map() const { return coverage_; }
  QLabel* pressure_map() const { return pressure_; }
  /// The Close button: in sight on any screen the card fits (the text and maps scroll).
  QPushButton* close_button() const { return close_; }

  static constexpr int kMapWidth = 520;  ///< px: the figures' own legends stay legible

 private:
  QVBoxLayout* build_maps(const score::Score& score, QWidget* parent);

  QLabel* coverage_ = nullptr;
  QPushButton* close_ = nullptr;
  QLabel* pressure_ = nullptr;
  QString headline_;
  QString text_;
};

}  // namespace palpa::ui
