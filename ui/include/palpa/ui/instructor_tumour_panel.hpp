#pragma once
// The instructor's tumour controls: the case's tumours in a table (one row each), the
// depth below the skin (mm), radius (mm) and stiffness (N/m) or Young's modulus (kPa, in
// a case whose tissue is given in Pa) of the selected one (or of the next one a click
// places, when none is selected), and its randomization rule: the (u, v) rectangle and
// the depth fraction range a seeded exercise draws its centre from.
#include <array>
#include <optional>
#include <vector>

#include <QGroupBox>

#include "palpa/author/case_draft.hpp"
#include "palpa/author/problem_text.hpp"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QVBoxLayout;
class QTableWidget;

namespace palpa::ui {

class InstructorTumourPanel : public QGroupBox {
  Q_OBJECT
 public:
  explicit InstructorTumourPanel(QWidget* parent = nullptr);

  /// Fills the table from the draft and shows the selected tumour's values. Emits nothing.
  void show_draft(const author::CaseDraft& draft);
  /// The selected tumour's row, if any.
  std::optional<std::size_t> selected() const;
  void select(std::optional<std::size_t> k);
  /// Depth, radius and stiffness or modulus in the spin boxes (SI).
  author::TumourSpec spec() const;
  /// The material box shows a modulus in kPa (else a stiffness in N/m).
  bool material_in_kpa() const { return in_kpa_; }
  /// The rule the controls show, or nothing when randomization is off.
  std::optional<scripted::Placement> placement() const;
  /// Highlights the cell of the field at fault (red; the whole row for the tumour as a
  /// whole) with the reason as its tooltip, and the field's control when tumour k is the
  /// selected one: the radius box for a radius that reaches beyond the skin, not the depth.
  void clear_problems();
  void add_problem(std::size_t k, author::ProblemField field, const QString& reason);
  /// Marks tumour k's row (pale yellow, unless it holds a problem) with a warning.
  void add_warning(std::size_t k, const QString& text);

  QTableWidget* table() const { return table_; }
  QDoubleSpinBox* depth_box() const { return depth_; }
  QDoubleSpinBox* radius_box() const { return radius_; }
  QDoubleSpinBox* stiffness_box() const { return stiffness_; }
  /// In kPa: the tumour tissue picked from the literature ("Custom" when edited by hand), and
  /// its strain stiffening b.
  QComboBox* material_box() const { return material_; }
  QDoubleSpinBox* stiffening_box() const { return stiffening_; }
  QCheckBox* randomize_box() const { return randomize_; }
  /// u low, u high, v low, v high, depth low, depth high: in per cent (of the body's extent
  /// along x and y, of the local thickness in depth).
  QDoubleSpinBox* rule_box(int index) const { return rule_[index]; }
  /// "Random depth: 40-50 % of the thickness (20.0-25.0 mm here)" for the selected tumour.
  QLabel* random_depth_label() const { return random_depth_; }
  QPushButton* remove_button() const { return remove_; }

 signals:
  void selection_changed(std::optional<std::size_t> k);
  /// The selected tumour's spec: the draft's, with the one field the instructor changed.
  void spec_changed(std::size_t k, const palpa::author::TumourSpec& spec);
  void placement_changed(std::size_t k, const std::optional<palpa::scripted::Placement>& rule);
  void remove_requested(std::size_t k);

 private:
  void build_table(QVBoxLayout* layout);
  void build_spec_form(QVBoxLayout* layout);
  void build_placement_rule(QVBoxLayout* layout);
  void connect_controls();
  void show_selected();
  /// Emits the selected tumour's spec with only `changed`'s field from the boxes.
  void emit_spec(const QDoubleSpinBox* changed);
  void emit_placement();
  /// The random depth note and which depth control applies (the rule's or the fixed depth).
  void show_random_depth();
  /// Shows the material box in kPa (a modulus) or N/m (a stiffness); resets its value to
  /// the unit's default when the unit changes.
  void set_material_unit(bool kpa);
  void show_material_controls(bool kpa);
  /// Puts the tissue `key`'s modulus and stiffening in the boxes (emits nothing); false for
  /// no such tissue ("Custom").
  bool fill_material(const QString& key);
  /// Shows the tissue whose values the boxes hold, or "Custom".
  void match_material();

  const author::CaseDraft* draft_ = nullptr;
  QTableWidget* table_ = nullptr;
  QDoubleSpinBox* depth_ = nullptr;
  QDoubleSpinBox* radius_ = nullptr;
  QDoubleSpinBox* stiffness_ = nullptr;  // stiffness (N/m) or modulus (kPa): in_kpa_
  QLabel* material_label_ = nullptr;
  QComboBox* material_ = nullptr;
  QLabel* tissue_label_ = nullptr;
  QDoubleSpinBox* stiffening_ = nullptr;
  QLabel* stiffening_label_ = nullptr;
  bool in_kpa_ = false;
  QCheckBox* randomize_ = nullptr;
  QDoubleSpinBox* rule_[6] = {};
  QLabel* random_depth_ = nullptr;
  std::vector<std::optional<std::array<double, 2>>> ranges_;  // each tumour's random depth range (m)
  QPushButton* remove_ = nullptr;
  bool updating_ = false;
};

}  // namespace palpa::ui
