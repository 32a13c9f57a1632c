#pragma once
// The instructor's exam controls: the case's description, the scoring thresholds in the
// window's units (coverage and pressure bands in %, force in N, hit margin in mm, duration
// in s) and the exam region, the whole surface or the same part of every body given in per
// cent of its extent along x and y. Each shows the value the case is scored with (its own
// or the default) and emits the edit in SI for the draft.
#include <optional>
#include <string>
#include <vector>

#include <QWidget>

#include "palpa/author/case_draft.hpp"

class QComboBox;
class QDoubleSpinBox;
class QPlainTextEdit;
class QVBoxLayout;

namespace palpa::ui {

class InstructorExamPanel : public QWidget {
  Q_OBJECT
 public:
  explicit InstructorExamPanel(QWidget* parent = nullptr);

  /// Shows the draft's description, thresholds and region. Emits nothing.
  void show_draft(const author::CaseDraft& draft);
  /// Commits the description typed so far (also done when the field loses focus).
  void commit_description();

  QPlainTextEdit* description_edit() const { return description_; }
  /// The box of a scoring key (min_coverage, min_deep_coverage, max_force, hit_margin,
  /// light_max, deep_min, min_duration), or null.
  QDoubleSpinBox* scoring_box(const std::string& key) const;
  /// Whole surface, Part of the body (and, for a region the window does not edit, As written).
  QComboBox* region_box() const { return region_; }
  /// Along x from, to; along y from, to (% of the body's extent).
  QDoubleSpinBox* extent_box(int index) const { return extent_[index]; }

  /// Marks the box of a scoring key holding a problem (empty key: none), or the region.
  void clear_problems();
  void add_scoring_problem(const std::string& key, const QString& reason);
  void add_region_problem(const QString& reason);

 signals:
  void description_changed(const QString& text);
  /// `key` set to `value` in SI (fractions, m, N, s).
  void scoring_changed(const std::string& key, double value);
  void region_changed(const std::optional<palpa::author::ExamExtent>& extent);

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  struct Field {
    std::string key;
    QDoubleSpinBox* box = nullptr;
    double scale = 1.0;  // shown = SI * scale
  };
  void build_scoring(QVBoxLayout* layout);
  void build_region(QVBoxLayout* layout);
  void emit_region();
  std::optional<author::ExamExtent> extent() const;

  QPlainTextEdit* description_ = nullptr;
  QString shown_description_;
  std::vector<Field> fields_;
  QComboBox* region_ = nullptr;
  QDoubleSpinBox* extent_[4] = {};
  bool updating_ = false;
};

}  // namespace palpa::ui
