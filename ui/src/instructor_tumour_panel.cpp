#include "palpa/ui/instructor_tumour_panel.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include <QAbstractItemView>
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QSignalBlocker>
#include <QTableWidget>
#include <QVBoxLayout>

#include "palpa/mat/tissue_materials.hpp"

#include "spin_box.hpp"

namespace palpa::ui {
namespace {

const QColor kProblem(255, 200, 200);
const QColor kWarning(255, 240, 190);

// A new tumour's material: a ~100 kPa region under a fingertip in N/m (flat-punch estimate,
// docs/case-authoring.md), or in kPa the invasive ductal carcinoma of the bundled materials
// (mat/tissue_materials.hpp: Samani's small-strain modulus, Krouskop's stiffening).
constexpr double kDefaultStiffness = 2000.0;  // N/m
constexpr const char* kDefaultMaterial = "carcinoma";

// A randomized tumour's depth range (m) as the table and the rule's note show it: "20-25".
QString depth_range_text(const std::array<double, 2>& range) {
  return QString("%1-%2").arg(range[0] * 1e3, 0, 'f', 1).arg(range[1] * 1e3, 0, 'f', 1);
}

QString material_text(const mat::Tumour& t) {
  if (!(t.modulus > 0.0)) return QString::number(t.stiffness, 'f', 0) + " N/m";
  QString text = QString::number(t.modulus * 1e-3, 'f', 1) + " kPa";
  if (t.stiffening > 0.0) text += ", stiffening " + QString::number(t.stiffening, 'f', 1);
  return text;
}

}  // namespace

// Untitled: its tab says "Tumours" (the room goes to the table).
InstructorTumourPanel::InstructorTumourPanel(QWidget* parent) : QGroupBox(parent) {
  auto* layout = new QVBoxLayout(this);
  auto* help = new QLabel(tr("Click the body to place a tumour (Shift+click moves the selected one)."), this);
  help->setWordWrap(true);
  layout->addWidget(help);
  build_table(layout);
  build_spec_form(layout);
  build_placement_rule(layout);
  remove_ = new QPushButton(tr("Remove tumour"), this);
  layout->addWidget(remove_);
  connect_controls();
  remove_->setEnabled(false);
}

// The placed tumours, one row each.
void InstructorTumourPanel::build_table(QVBoxLayout* layout) {
  table_ = new QTableWidget(0, 4, this);
  // Depth: below the skin, or for a randomized tumour the range its rule can give it.
  table_->setHorizontalHeaderLabels({tr("Depth (mm)"), tr("Radius (mm)"), tr("Material"), tr("Random")});
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  table_->setSelectionMode(QAbstractItemView::SingleSelection);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  // The numbers and "yes" take what their headers need; the material gets the rest (elided,
  // its tooltip has the whole).
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->horizontalHeader()->setSectionResizeMode(2, QHeaderView::Stretch);
  table_->setMinimumHeight(100);
  // It asks for no more than its minimum (not the 192 px of a table's size hint), so that the
  // tab's controls and Remove fit the side panel on a 1280 x 800 screen; it takes any room
  // to spare, and scrolls its rows when they are more than it shows.
  table_->setSizePolicy(table_->sizePolicy().horizontalPolicy(), QSizePolicy::Ignored);
  layout->addWidget(table_, 1);

}

// The selected tumour's depth, radius and tissue (a material from the literature or a
// custom stiffness).
void InstructorTumourPanel::build_spec_form(QVBoxLayout* layout) {
  auto* form = new QFormLayout;
  // Two decimals (10 um) and a low radius floor: a loaded tumour shows as it is written.
  depth_ = spin(this, 0.0, 200.0, 1.0, 2, tr(" mm"));
  depth_->setValue(10.0);
  depth_->setToolTip(tr("Depth of the centre below the picked skin point, in mm (where the case writes the "
                        "tumour; a randomized tumour takes its random depth instead)"));
  radius_ = spin(this, 0.01, 50.0, 0.5, 2, tr(" mm"));
  radius_->setValue(5.0);
  stiffness_ = spin(this, 0.0, 1e5, 100.0, 0, tr(" N/m"));
  stiffness_->setValue(kDefaultStiffness);
  material_label_ = new QLabel(tr("Stiffness"), this);
  // In kPa: a tissue from the literature fills modulus and stiffening; editing either
  // makes it "Custom".
  material_ = new QComboBox(this);
  // The names are long ("Invasive ductal carcinoma, high grade"): the box fits the panel and
  // elides, its list opens as wide as the names.
  material_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  material_->setMinimumContentsLength(14);
  material_->addItem(tr("Custom"), QString());
  for (const auto& m : mat::tissue_materials()) {
    if (m.tumour) material_->addItem(QString::fromUtf8(m.name.data(), static_cast<int>(m.name.size())),
                                     QString::fromUtf8(m.key.data(), static_cast<int>(m.key.size())));
  }
  material_->view()->setMinimumWidth(material_->view()->sizeHintForColumn(0) + 24);
  material_->setToolTip(tr("A tumour tissue from the literature: its small-strain modulus (Samani et al. 2007) "
                           "and how fast it stiffens when compressed (Krouskop et al. 1998)"));
  tissue_label_ = new QLabel(tr("Tissue"), this);
  stiffening_ = spin(this, 0.0, 20.0, 0.5, 2, QString());
  stiffening_->setToolTip(tr("How fast the tumour stiffens when pressed: its modulus grows as exp(stiffening x "
                             "strain). Carcinoma about 11, glandular 3.6, fat 0; 0: none"));
  stiffening_label_ = new QLabel(tr("Stiffening"), this);
  form->addRow(tr("Depth below skin"), depth_);
  form->addRow(tr("Radius"), radius_);
  form->addRow(tissue_label_, material_);
  form->addRow(material_label_, stiffness_);
  form->addRow(stiffening_label_, stiffening_);
  layout->addLayout(form);
  show_material_controls(false);

}

// Randomized placement: the ranges along x, along y and in depth a placed centre may take,
// in per cent: of the body's extent along x and y, of the local thickness in depth.
void InstructorTumourPanel::build_placement_rule(QVBoxLayout* layout) {
  randomize_ = new QCheckBox(tr("Randomize placement per exercise"), this);
  layout->addWidget(randomize_);
  auto* rules = new QGridLayout;
  // The rule's u, v and depth fractions in words: u runs along x and v along y over the
  // body (its skeleton's parameters, about the share of its extent), depth is the share of
  // the local thickness below the skin.
  const char* names[] = {"Along x", "Along y", "Random depth"};
  const double defaults[] = {30, 70, 30, 70, 40, 50};  // default.json's rule, in %
  for (int r = 0; r < 3; ++r) {
    rules->addWidget(new QLabel(tr(names[r]), this), r, 0);
    for (int c = 0; c < 2; ++c) {
      auto* box = spin(this, 0.0, 100.0, 5.0, 0, tr(" %"));
      box->setValue(defaults[2 * r + c]);
      box->setToolTip(r == 0   ? tr("From, to: where along the body's x extent the centre may go (0 % one end, 100 % the other)")
                      : r == 1 ? tr("From, to: where along the body's y extent the centre may go (0 % one end, 100 % the other)")
                               : tr("From, to: depth of the centre as a share of the local thickness (0 % at the skin, "
                                    "50 % mid-depth, 100 % at the base)"));
      rule_[2 * r + c] = box;
      rules->addWidget(box, r, 1 + c);
    }
  }
  layout->addLayout(rules);
  random_depth_ = new QLabel(this);
  random_depth_->setObjectName("randomDepth");
  random_depth_->setWordWrap(true);
  layout->addWidget(random_depth_);
}

void InstructorTumourPanel::connect_controls() {
  connect(table_, &QTableWidget::itemSelectionChanged, this, [this] {
    if (updating_) return;
    show_selected();
    emit selection_changed(selected());
  });
  for (auto* box : {depth_, radius_, stiffness_, stiffening_}) {
    connect(box, qOverload<double>(&QDoubleSpinBox::valueChanged), this, [this, box] {
      if (box == stiffness_ || box == stiffening_) match_material();
      emit_spec(box);
    });
  }
  connect(material_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this] {
    if (updating_) return;
    if (!fill_material(material_->currentData().toString())) return;  // "Custom": keep the values
    emit_spec(nullptr);
  });
  connect(randomize_, &QCheckBox::toggled, this, [this] {
    show_random_depth();
    emit_placement();
  });
  for (auto* box : rule_) {
    connect(box, qOverload<double>(&QDoubleSpinBox::valueChanged), this, [this] {
      show_random_depth();
      emit_placement();
    });
  }
  connect(remove_, &QPushButton::clicked, this, [this] {
    if (const auto k = selected()) emit remove_requested(*k);
  });
}

void InstructorTumourPanel::show_draft(const author::CaseDraft& draft) {
  draft_ = &draft;
  updating_ = true;
  const auto keep = selected();
  const QSignalBlocker block(table_);
  table_->setRowCount(static_cast<int>(draft.tumour_count()));
  ranges_ = draft.random_depth_ranges();
  for (std::size_t k = 0; k < draft.tumour_count(); ++k) {
    const auto t = draft.tumour(k);
    const auto s = draft.spec(k);
    const int row = static_cast<int>(k);
    const auto& range = ranges_[k];
    const QString depth = range ? depth_range_text(*range) : s ? QString::number(s->depth * 1e3, 'f', 2) : QString("?");
    const QString cells[] = {depth,
                             t ? QString::number(t->radius * 1e3, 'f', 2) : QString("?"),
                             t ? material_text(*t) : QString("?"),
                             draft.placement(k) ? tr("yes") : tr("no")};
    for (int c = 0; c < 4; ++c) {
      auto* item = new QTableWidgetItem(cells[c]);
      item->setToolTip(cells[c]);  // whole where the column is too narrow for it
      table_->setItem(row, c, item);
    }
  }
  if (keep && *keep < draft.tumour_count()) {
    table_->selectRow(static_cast<int>(*keep));
  } else {
    table_->clearSelection();
  }
  show_selected();
  updating_ = false;
}

void InstructorTumourPanel::set_material_unit(bool kpa) {
  if (kpa == in_kpa_) return;
  in_kpa_ = kpa;
  const QSignalBlocker block(stiffness_);
  material_label_->setText(kpa ? tr("Modulus") : tr("Stiffness"));
  stiffness_->setSuffix(kpa ? tr(" kPa") : tr(" N/m"));
  stiffness_->setDecimals(kpa ? 2 : 0);
  stiffness_->setRange(0.0, kpa ? 1e4 : 1e5);
  stiffness_->setSingleStep(kpa ? 1.0 : 100.0);
  stiffness_->setToolTip(kpa ? tr("Young's modulus of the tumour at small strain (breast carcinoma: about 10-45 kPa)")
                             : tr("Stiffness per skeleton point the finger meets over the tumour"));
  show_material_controls(kpa);
  if (kpa) {
    fill_material(kDefaultMaterial);
  } else {
    stiffness_->setValue(kDefaultStiffness);
  }
}

void InstructorTumourPanel::show_material_controls(bool kpa) {
  for (QWidget* w : std::initializer_list<QWidget*>{tissue_label_, material_, stiffening_label_, stiffening_}) {
    w->setVisible(kpa);
  }
}

bool InstructorTumourPanel::fill_material(const QString& key) {
  const auto* m = mat::find_tissue_material(key.toStdString());
  if (!m) return false;
  const QSignalBlocker block_modulus(stiffness_), block_stiffening(stiffening_), block_material(material_);
  stiffness_->setValue(m->modulus * 1e-3);
  stiffening_->setValue(m->stiffening);
  material_->setCurrentIndex(std::max(0, material_->findData(key)));
  return true;
}

void InstructorTumourPanel::match_material() {
  const QSignalBlocker block(material_);
  int match = 0;  // "Custom"
  for (int i = 1; i < material_->count(); ++i) {
    const auto* m = mat::find_tissue_material(material_->itemData(i).toString().toStdString());
    if (m && std::abs(m->modulus * 1e-3 - stiffness_->value()) < 0.005 &&
        std::abs(m->stiffening - stiffening_->value()) < 0.005) {
      match = i;
    }
  }
  material_->setCurrentIndex(match);
}

std::optional<std::size_t> InstructorTumourPanel::selected() const {
  const auto rows = table_->selectionModel()->selectedRows();
  if (rows.isEmpty()) return std::nullopt;
  return static_cast<std::size_t>(rows.front().row());
}

void InstructorTumourPanel::select(std::optional<std::size_t> k) {
  if (k && *k < static_cast<std::size_t>(table_->rowCount())) {
    table_->selectRow(static_cast<int>(*k));
  } else {
    table_->clearSelection();
  }
}

void InstructorTumourPanel::show_selected() {
  const bool was = updating_;
  updating_ = true;
  const auto k = selected();
  remove_->setEnabled(k.has_value());
  // The unit follows the selected tumour, or for the next one the case's tissue.
  const auto t = k && draft_ ? draft_->tumour(*k) : std::nullopt;
  set_material_unit(t ? t->modulus > 0.0 : draft_ && draft_->tissue_in_pa());
  if (k && draft_) {
    if (const auto s = draft_->spec(*k)) {
      depth_->setValue(s->depth * 1e3);
      radius_->setValue(s->radius * 1e3);
      stiffness_->setValue(in_kpa_ ? s->modulus * 1e-3 : s->stiffness);
      stiffening_->setValue(in_kpa_ ? s->stiffening : 0.0);
      match_material();
    }
    const auto rule = draft_->placement(*k);
    randomize_->setChecked(rule.has_value());
    if (rule) {
      const double values[] = {rule->u[0], rule->u[1], rule->v[0], rule->v[1], rule->depth[0], rule->depth[1]};
      for (int c = 0; c < 6; ++c) rule_[c]->setValue(values[c] * 100.0);
    }
  }
  show_random_depth();
  updating_ = was;
}

author::TumourSpec InstructorTumourPanel::spec() const {
  if (in_kpa_) {
    // A tissue from the list is written with its exact values, not as the boxes round them.
    if (const auto* m = mat::find_tissue_material(material_->currentData().toString().toStdString())) {
      return {depth_->value() * 1e-3, radius_->value() * 1e-3, 0.0, m->modulus, m->stiffening};
    }
    return {depth_->value() * 1e-3, radius_->value() * 1e-3, 0.0, stiffness_->value() * 1e3, stiffening_->value()};
  }
  return {depth_->value() * 1e-3, radius_->value() * 1e-3, stiffness_->value(), 0.0};
}

std::optional<scripted::Placement> InstructorTumourPanel::placement() const {
  if (!randomize_->isChecked()) return std::nullopt;
  const auto share = [this](int c) { return rule_[c]->value() / 100.0; };
  return scripted::Placement{{share(0), share(1)}, {share(2), share(3)}, {share(4), share(5)}};
}

void InstructorTumourPanel::show_random_depth() {
  const auto k = selected();
  const bool on = randomize_->isChecked();
  for (auto* box : rule_) box->setEnabled(on);
  const auto range = k && *k < ranges_.size() && on ? ranges_[*k] : std::nullopt;
  QString text = tr("Random depth: %1-%2 % of the thickness").arg(rule_[4]->value()).arg(rule_[5]->value());
  if (range) text += tr(" (%1 mm here)").arg(depth_range_text(*range));
  random_depth_->setText(text);
  random_depth_->setVisible(on);
  depth_->setEnabled(!range);  // a randomized tumour's depth is its random depth
}

void InstructorTumourPanel::emit_spec(const QDoubleSpinBox* changed) {
  if (updating_) return;
  const auto k = selected();
  if (!k) return;
  // Only the changed field: the others as the draft holds them, not as the boxes round them.
  author::TumourSpec s = spec();
  if (draft_) {
    author::TumourSpec merged = s;
    if (const auto current = draft_->spec(*k)) {
      merged = *current;
    } else if (const auto t = draft_->tumour(*k)) {
      merged.radius = t->radius;
      merged.stiffness = t->stiffness;
      merged.modulus = t->modulus;
      merged.stiffening = t->stiffening;
    }
    if (changed == depth_) merged.depth = s.depth;
    if (changed == radius_) merged.radius = s.radius;
    if (changed == stiffness_ || changed == nullptr) {  // nullptr: a tissue was picked
      merged.stiffness = s.stiffness;
      merged.modulus = s.modulus;
    }
    if (changed == stiffening_ || changed == nullptr) merged.stiffening = s.stiffening;
    s = merged;
  }
  emit spec_changed(*k, s);
}

void InstructorTumourPanel::emit_placement() {
  if (updating_) return;
  if (const auto k = selected()) emit placement_changed(*k, placement());
}

void InstructorTumourPanel::clear_problems() {
  for (int r = 0; r < table_->rowCount(); ++r) {
    for (int c = 0; c < table_->columnCount(); ++c) {
      if (auto* item = table_->item(r, c)) {
        item->setBackground(QBrush());
        item->setToolTip(item->text());
      }
    }
  }
  for (auto* box : {depth_, radius_, stiffness_, stiffening_}) box->setStyleSheet(QString());
  for (auto* box : rule_) box->setStyleSheet(QString());
}

void InstructorTumourPanel::add_problem(std::size_t k, author::ProblemField field, const QString& reason) {
  using author::ProblemField;
  const int row = static_cast<int>(k);
  if (row >= table_->rowCount()) return;
  // The cell of the field at fault, or the whole row.
  const int column = field == ProblemField::Depth       ? 0
                     : field == ProblemField::Radius    ? 1
                     : field == ProblemField::Material  ? 2
                     : field == ProblemField::Placement ? 3
                                                        : -1;
  for (int c = 0; c < table_->columnCount(); ++c) {
    if (auto* item = table_->item(row, c); item && (column < 0 || c == column)) {
      item->setBackground(kProblem);
      item->setToolTip(reason);
    }
  }
  if (selected() != k) return;
  const QString red = "background: #ffc8c8;";
  if (field == ProblemField::Depth) depth_->setStyleSheet(red);
  if (field == ProblemField::Radius) radius_->setStyleSheet(red);
  if (field == ProblemField::Material) {
    stiffness_->setStyleSheet(red);
    stiffening_->setStyleSheet(red);
  }
  if (field == ProblemField::Placement) {
    for (auto* box : rule_) box->setStyleSheet(red);
  }
}

void InstructorTumourPanel::add_warning(std::size_t k, const QString& text) {
  const int row = static_cast<int>(k);
  if (row >= table_->rowCount()) return;
  for (int c = 0; c < table_->columnCount(); ++c) {
    auto* item = table_->item(row, c);
    if (!item || item->background().color() == kProblem) continue;
    item->setBackground(kWarning);
    item->setToolTip(text);
  }
}

}  // namespace palpa::ui
