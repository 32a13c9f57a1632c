#include "palpa/ui/instructor_preset_panel.hpp"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QLabel>
#include <QPushButton>
#include <QSignalBlocker>

namespace palpa::ui {
namespace {

constexpr author::Preset kPresets[] = {author::Preset::Breast, author::Preset::Prostate, author::Preset::Patch,
                                       author::Preset::Slab};

QDoubleSpinBox* spin(QWidget* parent, const QString& suffix, int decimals) {
  auto* box = new QDoubleSpinBox(parent);
  box->setSuffix(suffix);
  box->setDecimals(decimals);
  // One edit per finished value, not one per keystroke (each is an undo step).
  box->setKeyboardTracking(false);
  return box;
}

}  // namespace

InstructorPresetPanel::InstructorPresetPanel(QWidget* parent) : QGroupBox(tr("Body"), parent) {
  setObjectName("bodyPanel");
  auto* form = new QFormLayout(this);
  preset_ = new QComboBox(this);
  for (auto p : kPresets) preset_->addItem(tr(author::label(p)), QString(author::to_string(p)));
  form->addRow(tr("Preset"), preset_);
  width_ = spin(this, tr(" mm"), 1);
  width_->setToolTip(tr("Extent along x (the grid rows)"));
  form->addRow(tr("Width"), width_);
  length_ = spin(this, tr(" mm"), 1);
  length_->setToolTip(tr("Extent along y (the grid columns)"));
  form->addRow(tr("Length"), length_);
  thickness_ = spin(this, tr(" mm"), 1);
  thickness_->setToolTip(tr("Tissue thickness at the centre, skin to base"));
  form->addRow(tr("Thickness"), thickness_);
  tissue_ = new QComboBox(this);
  tissue_->addItem(tr("Modulus in kPa"), QString("kpa"));
  tissue_->addItem(tr("Stiffness in N/m (paper)"), QString("nm"));
  tissue_->setToolTip(tr("Give the tissue as its Young's modulus (kPa: forces calibrated against tissue "
                         "mechanics) or as the paper's stiffness per skeleton point (N/m)"));
  form->addRow(tr("Tissue"), tissue_);
  stiffness_ = spin(this, tr(" N/m"), 0);
  stiffness_label_ = new QLabel(tr("Stiffness"), this);
  form->addRow(stiffness_label_, stiffness_);
  // In kPa: how fast the tissue stiffens when pressed (fibroglandular 3.59, fat 0).
  stiffening_ = spin(this, QString(), 2);
  stiffening_->setRange(0.0, 20.0);
  stiffening_->setSingleStep(0.5);
  stiffening_->setToolTip(tr("How fast the tissue stiffens when pressed: its modulus grows as exp(stiffening x "
                             "strain). Fibroglandular 3.59, fat 0 (Krouskop et al. 1998); 0: none"));
  stiffening_label_ = new QLabel(tr("Stiffening"), this);
  form->addRow(stiffening_label_, stiffening_);
  note_ = new QLabel(this);
  note_->setWordWrap(true);
  form->addRow(note_);

  map_min_ = spin(this, tr(" N/m"), 0);
  map_max_ = spin(this, tr(" N/m"), 0);
  for (auto* box : {map_min_, map_max_}) box->setRange(0.0, 1e5);
  map_min_->setValue(60.0);   // 3 kPa fat under a fingertip (docs/case-authoring.md)
  map_max_->setValue(600.0);  // 30 kPa, dense glandular tissue
  map_min_->setToolTip(tr("Stiffness of black pixels"));
  map_max_->setToolTip(tr("Stiffness of white pixels"));
  form->addRow(tr("Map black"), map_min_);
  form->addRow(tr("Map white"), map_max_);
  import_ = new QPushButton(tr("Import stiffness map…"), this);
  form->addRow(import_);

  connect(preset_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this](int index) {
    if (updating_ || index < 0) return;
    const auto p = defaults(kPresets[index]);
    rows_ = p.rows;
    cols_ = p.cols;
    {
      const QSignalBlocker blockers[] = {QSignalBlocker(width_), QSignalBlocker(length_), QSignalBlocker(thickness_),
                                         QSignalBlocker(stiffness_), QSignalBlocker(stiffening_)};
      set_limits(p.preset);
      width_->setValue(p.width * 1e3);
      length_->setValue(p.length * 1e3);
      thickness_->setValue(p.thickness * 1e3);
      show_tissue(p);
    }
    emit_params();
  });
  // Another unit: the preset's default tissue in it (a modulus and a stiffness are not
  // one number in two units: the stiffness also follows the thickness).
  connect(tissue_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this](int index) {
    if (updating_ || index < 0) return;
    {
      const QSignalBlocker blockers[] = {QSignalBlocker(stiffness_), QSignalBlocker(stiffening_)};
      show_tissue(defaults(kPresets[std::max(0, preset_->currentIndex())]));
    }
    emit_params();
  });
  for (auto* box : {width_, length_, thickness_, stiffness_, stiffening_}) {
    connect(box, qOverload<double>(&QDoubleSpinBox::valueChanged), this, [this] { emit_params(); });
  }
  connect(import_, &QPushButton::clicked, this, &InstructorPresetPanel::import_requested);
  show_params(author::preset_defaults_in_kpa(author::Preset::Breast), true);
}

void InstructorPresetPanel::set_limits(author::Preset preset) {
  const auto l = author::preset_limits(preset);
  width_->setRange(l.width[0] * 1e3, l.width[1] * 1e3);
  length_->setRange(l.length[0] * 1e3, l.length[1] * 1e3);
  thickness_->setRange(l.thickness[0] * 1e3, l.thickness[1] * 1e3);
  if (tissue_in_kpa()) {
    stiffness_->setRange(l.modulus[0] * 1e-3, l.modulus[1] * 1e-3);
  } else {
    stiffness_->setRange(l.stiffness[0], l.stiffness[1]);
  }
}

bool InstructorPresetPanel::tissue_in_kpa() const { return tissue_->currentData().toString() == "kpa"; }

author::PresetParams InstructorPresetPanel::defaults(author::Preset preset) const {
  return tissue_in_kpa() ? author::preset_defaults_in_kpa(preset) : author::preset_defaults(preset);
}

void InstructorPresetPanel::show_tissue(const author::PresetParams& p) {
  const bool kpa = p.modulus > 0.0;
  {
    const QSignalBlocker block(tissue_);
    tissue_->setCurrentIndex(tissue_->findData(QString(kpa ? "kpa" : "nm")));
  }
  set_limits(p.preset);
  stiffness_label_->setText(kpa ? tr("Modulus") : tr("Stiffness"));
  stiffness_->setSuffix(kpa ? tr(" kPa") : tr(" N/m"));
  stiffness_->setDecimals(kpa ? 2 : 0);
  stiffness_->setSingleStep(kpa ? 0.25 : 1.0);
  stiffness_->setToolTip(kpa ? tr("Young's modulus of the tissue, uniform; the stiffness a fingertip meets also "
                                  "grows where the tissue is thin over its support")
                             : tr("Tissue stiffness per skeleton point (the breast's glandular centre; its fatty "
                                  "periphery is 0.4 times this)"));
  stiffness_->setValue(kpa ? p.modulus * 1e-3 : p.stiffness);
  stiffening_->setValue(kpa ? p.stiffening : 0.0);
  stiffening_->setVisible(kpa);
  stiffening_label_->setVisible(kpa);
}

void InstructorPresetPanel::show_params(const author::PresetParams& p, bool made_from_preset) {
  updating_ = true;
  const QSignalBlocker blockers[] = {QSignalBlocker(preset_),    QSignalBlocker(width_),     QSignalBlocker(length_),
                                     QSignalBlocker(thickness_), QSignalBlocker(stiffness_), QSignalBlocker(stiffening_)};
  for (int k = 0; k < 4; ++k) {
    if (kPresets[k] == p.preset) preset_->setCurrentIndex(k);
  }
  set_limits(p.preset);
  width_->setValue(p.width * 1e3);
  length_->setValue(p.length * 1e3);
  thickness_->setValue(p.thickness * 1e3);
  show_tissue(p);
  rows_ = p.rows;
  cols_ = p.cols;
  note_->setText(made_from_preset ? QString()
                                  : tr("This case was not made from a preset: these are its first body's size and "
                                       "tissue, and changing them replaces its bodies."));
  updating_ = false;
}

author::PresetParams InstructorPresetPanel::params() const {
  author::PresetParams p = author::preset_defaults(kPresets[std::max(0, preset_->currentIndex())]);
  p.width = width_->value() * 1e-3;
  p.length = length_->value() * 1e-3;
  p.thickness = thickness_->value() * 1e-3;
  if (tissue_in_kpa()) {
    p.modulus = stiffness_->value() * 1e3;
    p.stiffening = stiffening_->value();
  } else {
    p.modulus = 0.0;
    p.stiffness = stiffness_->value();
  }
  if (rows_ > 0) p.rows = rows_;
  if (cols_ > 0) p.cols = cols_;
  return p;
}

void InstructorPresetPanel::set_map_in_kpa(bool kpa) {
  if (kpa == map_in_kpa_) return;
  map_in_kpa_ = kpa;
  const QString unit = kpa ? tr(" kPa") : tr(" N/m");
  const QString what = kpa ? tr("Modulus") : tr("Stiffness");
  for (auto* box : {map_min_, map_max_}) {
    box->setSuffix(unit);
    box->setDecimals(kpa ? 1 : 0);
    box->setRange(0.0, kpa ? 1e4 : 1e5);
  }
  // In kPa: breast fat about 3 kPa to dense fibrous tissue about 30 kPa at small strain
  // (Samani 2007; Krouskop 1998's 5 % pre-compression values); in N/m their flat-punch
  // stiffness (docs/case-authoring.md).
  map_min_->setValue(kpa ? 3.0 : 60.0);
  map_max_->setValue(kpa ? 30.0 : 600.0);
  map_min_->setToolTip(what + tr(" of black pixels"));
  map_max_->setToolTip(what + tr(" of white pixels"));
  // One name for the import, as in the Case menu: the map sets the stiffness in either unit
  // (in kPa it gives the modulus the stiffness comes from).
}

double InstructorPresetPanel::map_k_min() const { return map_min_->value(); }
double InstructorPresetPanel::map_k_max() const { return map_max_->value(); }

void InstructorPresetPanel::set_problem(const QString& tip) {
  setStyleSheet(tip.isEmpty() ? QString() : QString("QGroupBox#bodyPanel { border: 2px solid #d03030; }"));
  setToolTip(tip);
}

void InstructorPresetPanel::emit_params() {
  if (!updating_) emit params_changed(params());
}

}  // namespace palpa::ui
