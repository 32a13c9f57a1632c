#include "palpa/ui/instructor_exam_panel.hpp"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QEvent>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QLabel>
#include <QPlainTextEdit>
#include <QSignalBlocker>
#include <QVBoxLayout>

#include "spin_box.hpp"

namespace palpa::ui {
namespace {

const QString kRed = "background: #ffc8c8;";

// The scoring keys the window edits, with their unit (docs/case-format.md, "scoring").
struct ScoringRow {
  const char* key;
  const char* label;
  const char* tip;
  double lo, hi, step;  // shown
  int decimals;
  const char* suffix;
  double scale;  // shown = SI * scale
};
const ScoringRow kScoringRows[] = {
    {"min_coverage", "Minimum coverage", "Share of the exam region the finger pad must cover to pass", 0, 100, 5, 0,
     " %", 100.0},
    {"min_deep_coverage", "Minimum deep coverage", "Share of the exam region that must be pressed at deep pressure",
     0, 100, 5, 0, " %", 100.0},
    {"max_force", "Maximum force", "A press above this force fails the exam (safety)", 0.1, 1000, 1, 1, " N", 1.0},
    {"hit_margin", "Hit margin", "A mark counts as finding a tumour within its radius plus this distance", 0.1, 1000,
     1, 1, " mm", 1000.0},
    {"light_max", "Light pressure up to", "Indentation below this share of the local thickness is light pressure", 0,
     100, 5, 0, " %", 100.0},
    {"deep_min", "Deep pressure from", "Indentation from this share of the local thickness on is deep pressure", 0,
     100, 5, 0, " %", 100.0},
    {"min_duration", "Minimum duration", "Exams shorter than this are flagged as short", 0, 86400, 10, 0, " s", 1.0},
};

}  // namespace

InstructorExamPanel::InstructorExamPanel(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(new QLabel(tr("Description"), this));
  description_ = new QPlainTextEdit(this);
  description_->setObjectName("caseDescription");
  description_->setPlaceholderText(tr("What the case is about (optional)"));
  description_->setFixedHeight(90);
  description_->installEventFilter(this);
  layout->addWidget(description_);
  build_scoring(layout);
  build_region(layout);
  layout->addStretch(1);
}

void InstructorExamPanel::build_scoring(QVBoxLayout* layout) {
  auto* group = new QGroupBox(tr("Scoring"), this);
  auto* form = new QFormLayout(group);
  for (const auto& row : kScoringRows) {
    auto* box = spin(group, row.lo, row.hi, row.step, row.decimals, tr(row.suffix));
    box->setToolTip(tr(row.tip));
    box->setObjectName(QString("scoring_") + row.key);
    form->addRow(tr(row.label), box);
    fields_.push_back({row.key, box, row.scale});
    connect(box, qOverload<double>(&QDoubleSpinBox::valueChanged), this, [this, key = std::string(row.key), box, row] {
      if (!updating_) emit scoring_changed(key, box->value() / row.scale);
    });
  }
  layout->addWidget(group);
}

void InstructorExamPanel::build_region(QVBoxLayout* layout) {
  auto* group = new QGroupBox(tr("Exam region"), this);
  auto* grid = new QGridLayout(group);
  region_ = new QComboBox(group);
  region_->addItem(tr("Whole surface"));
  region_->addItem(tr("Part of the body"));
  region_->setToolTip(tr("What coverage is measured over: the whole skin, or the same part of every body"));
  grid->addWidget(region_, 0, 0, 1, 3);
  const char* names[] = {"Along x", "Along y"};
  for (int r = 0; r < 2; ++r) {
    grid->addWidget(new QLabel(tr(names[r]), group), r + 1, 0);
    for (int c = 0; c < 2; ++c) {
      auto* box = spin(group, 0.0, 100.0, 5.0, 0, tr(" %"));
      box->setValue(c == 0 ? 0.0 : 100.0);
      box->setToolTip(tr("From, to: share of the body's extent along %1 (0 % one end, 100 % the other)")
                          .arg(r == 0 ? "x" : "y"));
      extent_[2 * r + c] = box;
      grid->addWidget(box, r + 1, 1 + c);
      connect(box, qOverload<double>(&QDoubleSpinBox::valueChanged), this, [this] { emit_region(); });
    }
  }
  connect(region_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this] { emit_region(); });
  layout->addWidget(group);
}

std::optional<author::ExamExtent> InstructorExamPanel::extent() const {
  if (region_->currentIndex() != 1) return std::nullopt;
  const auto share = [this](int c) { return extent_[c]->value() / 100.0; };
  return author::ExamExtent{{share(0), share(1)}, {share(2), share(3)}};
}

void InstructorExamPanel::emit_region() {
  for (auto* box : extent_) box->setEnabled(region_->currentIndex() == 1);
  if (updating_ || region_->currentIndex() > 1) return;  // "As written": nothing to set
  emit region_changed(extent());
}

QDoubleSpinBox* InstructorExamPanel::scoring_box(const std::string& key) const {
  for (const auto& f : fields_) {
    if (f.key == key) return f.box;
  }
  return nullptr;
}

void InstructorExamPanel::show_draft(const author::CaseDraft& draft) {
  updating_ = true;
  shown_description_ = QString::fromStdString(draft.description());
  if (!description_->hasFocus() && description_->toPlainText() != shown_description_) {
    description_->setPlainText(shown_description_);
  }
  const nlohmann::json t = io::to_json(draft.thresholds());
  for (const auto& f : fields_) {
    const QSignalBlocker block(f.box);
    if (t.contains(f.key) && t[f.key].is_number()) f.box->setValue(t[f.key].get<double>() * f.scale);
  }
  const auto kind = draft.exam_region_kind();
  const QSignalBlocker block(region_);
  while (region_->count() > 2) region_->removeItem(2);
  if (kind == author::CaseDraft::RegionKind::Custom) region_->addItem(tr("As written in the case"));
  region_->setCurrentIndex(kind == author::CaseDraft::RegionKind::Whole ? 0 : kind == author::CaseDraft::RegionKind::Extent ? 1 : 2);
  if (const auto e = draft.exam_extent()) {
    const double values[] = {e->u[0], e->u[1], e->v[0], e->v[1]};
    for (int c = 0; c < 4; ++c) {
      const QSignalBlocker b(extent_[c]);
      extent_[c]->setValue(values[c] * 100.0);
    }
  }
  for (auto* box : extent_) box->setEnabled(region_->currentIndex() == 1);
  updating_ = false;
}

void InstructorExamPanel::commit_description() {
  const QString text = description_->toPlainText();
  if (text != shown_description_) {
    shown_description_ = text;
    emit description_changed(text);
  }
}

bool InstructorExamPanel::eventFilter(QObject* watched, QEvent* event) {
  if (watched == description_ && event->type() == QEvent::FocusOut) commit_description();
  return QWidget::eventFilter(watched, event);
}

void InstructorExamPanel::clear_problems() {
  for (std::size_t i = 0; i < fields_.size(); ++i) {
    fields_[i].box->setStyleSheet(QString());
    fields_[i].box->setToolTip(tr(kScoringRows[i].tip));
  }
  region_->setStyleSheet(QString());
  description_->setStyleSheet(QString());
}

void InstructorExamPanel::add_scoring_problem(const std::string& key, const QString& reason) {
  for (const auto& f : fields_) {
    if (f.key == key) {
      f.box->setStyleSheet(kRed);
      f.box->setToolTip(reason);
    }
  }
}

void InstructorExamPanel::add_region_problem(const QString& reason) {
  region_->setStyleSheet(kRed);
  region_->setToolTip(reason);
}

}  // namespace palpa::ui
