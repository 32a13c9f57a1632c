#pragma once
// The instructor's Import anatomy dialog (docs/user-guide.md, "Importing anatomy"): a
// label volume with its label table (built-in, a file, or mapped by hand), or a mesh on a
// support mesh or plane with its tissue's modulus; the grid; Import runs
// anatomy_io::import_anatomy and previews the fitted body, its fit error and the lesions;
// "Use this case" accepts the dialog with the case, Cancel rejects it. Problems show as one
// line in the dialog. The GUI speaks mm and kPa; the request is in SI.
#include <array>
#include <optional>
#include <string>

#include <QDialog>

#include "palpa/anatomy_io/import_request.hpp"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QGroupBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QScrollArea;
class QSpinBox;

namespace palpa::ui {

class ImportPreview;
class LabelMapTable;

class ImportAnatomyDialog : public QDialog {
  Q_OBJECT
 public:
  explicit ImportAnatomyDialog(QWidget* parent = nullptr);
  ~ImportAnatomyDialog() override;

  /// The last successful import (what "Use this case" hands over); null when there is none.
  const anatomy_io::ImportedCase* imported() const { return imported_ ? &*imported_ : nullptr; }
  /// Imports with the options shown; false with the reason on the error line.
  bool run_import();

 private:
  QWidget* build_file_row();
  QGroupBox* build_volume_box();
  QGroupBox* build_mesh_box();
  QWidget* build_grid_row();
  QWidget* build_buttons();
  /// A line edit with a Browse… button filling it from a file dialog.
  QWidget* path_row(QLineEdit*& edit, const QString& name, const QString& title, const QString& filter);
  void input_changed();
  void table_choice_changed();
  /// The table file's row or the mapping table, as the label table choice asks.
  void show_table_rows();
  /// Reads the volume once and lists its labels in the mapping table; false on error.
  bool read_labels();
  /// The request from the controls; false with the reason on the error line.
  bool build_request(anatomy_io::ImportRequest& request);
  bool build_volume_request(anatomy_io::ImportRequest& request, std::string& command);
  bool build_mesh_request(anatomy_io::ImportRequest& request, std::string& command);
  void forget_import();
  void show_error(const QString& text);

  QLineEdit* path_ = nullptr;
  QGroupBox* volume_box_ = nullptr;
  QGroupBox* mesh_box_ = nullptr;
  QComboBox* table_choice_ = nullptr;
  QWidget* table_file_row_ = nullptr;
  QLineEdit* table_path_ = nullptr;
  LabelMapTable* map_ = nullptr;
  QComboBox* support_kind_ = nullptr;
  QWidget* support_file_row_ = nullptr;
  QLineEdit* support_path_ = nullptr;
  QWidget* plane_row_ = nullptr;
  std::array<QDoubleSpinBox*, 4> plane_{};
  QDoubleSpinBox* modulus_ = nullptr;
  QCheckBox* grid_auto_ = nullptr;
  QSpinBox* rows_ = nullptr;
  QSpinBox* cols_ = nullptr;
  QScrollArea* inputs_ = nullptr;  ///< the inputs above the preview, scrolling on a small screen
  QLabel* error_ = nullptr;
  QPushButton* import_button_ = nullptr;
  QPushButton* use_button_ = nullptr;
  ImportPreview* preview_ = nullptr;
  std::optional<anatomy_io::ImportedCase> imported_;
  std::string mapped_path_;  // the volume whose labels the mapping table lists
};

}  // namespace palpa::ui
