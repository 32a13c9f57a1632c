#pragma once
// The instructor's body controls: the preset (breast, prostate, skin/abdomen patch,
// generic slab), its size in mm and tissue stiffness in N/m, and the stiffness map import
// with the range (N/m) black and white map to. Every change emits params_changed with the
// values in SI units; the window turns it into an undoable edit of the case.
#include <optional>

#include <QGroupBox>

#include "palpa/author/presets.hpp"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QPushButton;

namespace palpa::ui {

class InstructorPresetPanel : public QGroupBox {
  Q_OBJECT
 public:
  explicit InstructorPresetPanel(QWidget* parent = nullptr);

  /// Shows `params`; when the case was not `made_from_preset`, they are the nearest preset's
  /// (CaseDraft::preset_or_nearest) and a note says that changing them replaces its bodies.
  /// Emits nothing.
  void show_params(const author::PresetParams& params, bool made_from_preset);
  /// The parameters the controls show (SI).
  author::PresetParams params() const;
  /// The range of an imported map, black -> min, white -> max, in the unit shown: a
  /// stiffness in N/m, or a modulus in kPa (map_in_kpa).
  double map_k_min() const;
  double map_k_max() const;
  /// Shows the map range as the tissue's modulus in kPa (a case given in Pa) or as a
  /// stiffness in N/m; the values reset to the unit's defaults when the unit changes.
  void set_map_in_kpa(bool kpa);
  bool map_in_kpa() const { return map_in_kpa_; }
  /// A preset's defaults with the tissue in the unit the tissue box shows (File > New
  /// keeps the unit the instructor chose).
  author::PresetParams defaults(author::Preset preset) const;
  /// Marks the body controls as holding a problem (red frame) with `tip` as the reason.
  void set_problem(const QString& tip);

  QComboBox* preset_box() const { return preset_; }
  QDoubleSpinBox* width_box() const { return width_; }
  QDoubleSpinBox* length_box() const { return length_; }
  QDoubleSpinBox* thickness_box() const { return thickness_; }
  /// The tissue's modulus (kPa) or stiffness (N/m), as tissue_box says.
  QDoubleSpinBox* stiffness_box() const { return stiffness_; }
  /// In kPa: the tissue's strain stiffening b.
  QDoubleSpinBox* stiffening_box() const { return stiffening_; }
  /// How the tissue is given: "kpa" (Young's modulus, the calibrated force law) or "nm"
  /// (stiffness per skeleton point, the paper's springs).
  QComboBox* tissue_box() const { return tissue_; }
  QPushButton* import_button() const { return import_; }

 signals:
  void params_changed(const palpa::author::PresetParams& params);
  void import_requested();

 private:
  void set_limits(author::Preset preset);
  bool tissue_in_kpa() const;
  /// The tissue value of p in the shown unit (kPa or N/m), and its label.
  void show_tissue(const author::PresetParams& p);
  void emit_params();

  QComboBox* preset_ = nullptr;
  QDoubleSpinBox* width_ = nullptr;
  QDoubleSpinBox* length_ = nullptr;
  QDoubleSpinBox* thickness_ = nullptr;
  QDoubleSpinBox* stiffness_ = nullptr;
  QDoubleSpinBox* stiffening_ = nullptr;
  QLabel* stiffening_label_ = nullptr;
  QComboBox* tissue_ = nullptr;
  QLabel* stiffness_label_ = nullptr;
  QDoubleSpinBox* map_min_ = nullptr;
  QDoubleSpinBox* map_max_ = nullptr;
  bool map_in_kpa_ = false;
  QPushButton* import_ = nullptr;
  QLabel* note_ = nullptr;
  int rows_ = 0, cols_ = 0;  // grid of the shown parameters (kept through edits)
  bool updating_ = false;
};

}  // namespace palpa::ui
