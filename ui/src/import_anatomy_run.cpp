// The Import anatomy dialog's behaviour: which options the chosen file needs, reading a
// volume's labels for the mapping table, the request (mm and kPa to SI), and the import.
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QLabel>
#include <QScrollArea>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>

#include <fmt/format.h>

#include "import_anatomy_dialog.hpp"
#include "import_label_map.hpp"
#include "import_preview.hpp"
#include "palpa/anatomy/import_error.hpp"
#include "palpa/anatomy_io/anatomy_io.hpp"
#include "palpa/io/case_file.hpp"

namespace palpa::ui {
namespace {

struct BusyCursor {
  BusyCursor() { QApplication::setOverrideCursor(Qt::WaitCursor); }
  ~BusyCursor() { QApplication::restoreOverrideCursor(); }
  BusyCursor(const BusyCursor&) = delete;
  BusyCursor& operator=(const BusyCursor&) = delete;
};

std::filesystem::path to_path(const QString& text) { return std::filesystem::path(text.trimmed().toStdString()); }

}  // namespace

void ImportAnatomyDialog::input_changed() {
  const auto kind = anatomy_io::input_kind(to_path(path_->text()));
  volume_box_->setVisible(kind == anatomy_io::InputKind::LabelVolume);
  mesh_box_->setVisible(kind == anatomy_io::InputKind::Mesh);
  show_table_rows();
  forget_import();
}

void ImportAnatomyDialog::show_table_rows() {
  const QString choice = table_choice_->currentData().toString();
  table_file_row_->setVisible(choice == "file");
  if (auto* form = qobject_cast<QFormLayout*>(volume_box_->layout())) {
    if (QWidget* label = form->labelForField(table_file_row_)) label->setVisible(choice == "file");
  }
  map_->setVisible(choice == "map");
  inputs_->updateGeometry();  // the scroll area asks for its content's new height
}

void ImportAnatomyDialog::table_choice_changed() {
  show_table_rows();
  // The volume is read when "Map labels…" is chosen or the path is finished, not per keystroke.
  if (table_choice_->currentData().toString() == "map" && volume_box_->isVisibleTo(this)) read_labels();
  forget_import();
}

bool ImportAnatomyDialog::read_labels() {
  const std::string path = path_->text().trimmed().toStdString();
  if (anatomy_io::input_kind(path) != anatomy_io::InputKind::LabelVolume || path == mapped_path_) return true;
  try {
    BusyCursor busy;
    map_->set_labels(count_labels(anatomy_io::read_label_volume(path)));
  } catch (const std::exception& e) {
    map_->setRowCount(0);
    mapped_path_.clear();
    show_error(QString::fromStdString(e.what()));
    return false;
  }
  mapped_path_ = path;
  error_->clear();
  return true;
}

void ImportAnatomyDialog::forget_import() {
  if (!imported_) return;
  imported_.reset();
  use_button_->setEnabled(false);
  preview_->clear();
}

void ImportAnatomyDialog::show_error(const QString& text) {
  const QString line = text.section('\n', 0, 0).trimmed();
  error_->setText(line);
  error_->setToolTip(line);
}

bool ImportAnatomyDialog::build_volume_request(anatomy_io::ImportRequest& r, std::string& command) {
  const QString choice = table_choice_->currentData().toString();
  if (choice == "map") {
    if (mapped_path_ != r.input.string() || map_->rowCount() == 0) {
      if (read_labels()) show_error(tr("Check the labels listed below, then Import again."));
      return false;
    }
    r.table = map_->table();
    command = "labels mapped by hand: " + map_->describe();
    return true;
  }
  if (choice == "file") {
    if (table_path_->text().trimmed().isEmpty()) {
      show_error(tr("Choose the label table file (.json)."));
      return false;
    }
    r.labels = table_path_->text().trimmed().toStdString();
    command = "--labels " + to_path(table_path_->text()).filename().string();
    return true;
  }
  r.labels = choice.toStdString();
  command = "--labels " + r.labels;
  return true;
}

bool ImportAnatomyDialog::build_mesh_request(anatomy_io::ImportRequest& r, std::string& command) {
  r.modulus = modulus_->value() * 1e3;
  r.metres_per_unit = 1e-3;
  if (support_kind_->currentData().toString() == "plane") {
    r.support_plane = std::array<double, 4>{plane_[0]->value(), plane_[1]->value(), plane_[2]->value(), plane_[3]->value()};
    if (plane_[0]->value() == 0.0 && plane_[1]->value() == 0.0 && plane_[2]->value() == 0.0) {
      show_error(tr("The support plane's normal (nx, ny, nz) must not be zero."));
      return false;
    }
    command = fmt::format("--support-plane \"{:g},{:g},{:g},{:g}\"", plane_[0]->value(), plane_[1]->value(),
                          plane_[2]->value(), plane_[3]->value());
  } else {
    if (support_path_->text().trimmed().isEmpty()) {
      show_error(tr("Choose the support mesh the skin rests on, or a support plane."));
      return false;
    }
    r.support = to_path(support_path_->text());
    command = "--support " + r.support.filename().string();
  }
  command += fmt::format(" --modulus {:g}", r.modulus);
  return true;
}

bool ImportAnatomyDialog::build_request(anatomy_io::ImportRequest& r) {
  if (path_->text().trimmed().isEmpty()) {
    show_error(tr("Choose a label volume or a mesh to import."));
    return false;
  }
  r.input = to_path(path_->text());
  std::string command;
  const auto kind = anatomy_io::input_kind(r.input);
  if (kind == anatomy_io::InputKind::LabelVolume && !build_volume_request(r, command)) return false;
  if (kind == anatomy_io::InputKind::Mesh && !build_mesh_request(r, command)) return false;
  if (!grid_auto_->isChecked()) {
    r.rows = rows_->value();
    r.cols = cols_->value();
    command += fmt::format(" --grid {}x{}", r.rows, r.cols);
  }
  r.command = command + " --exam-region free-surface (instructor window)";
  r.tool = "palpa instructor window";
  return true;
}

bool ImportAnatomyDialog::run_import() {
  forget_import();
  error_->clear();
  anatomy_io::ImportRequest request;
  if (!build_request(request)) return false;
  try {
    BusyCursor busy;
    anatomy_io::ImportedCase imported = anatomy_io::import_anatomy(request);
    preview_->show_import(imported);
    imported_ = std::move(imported);
  } catch (const io::CaseError& e) {
    show_error(QString::fromStdString(e.lines().front()));
  } catch (const std::exception& e) {  // anatomy::ImportError, and whatever else reading throws
    show_error(QString::fromStdString(e.what()));
  }
  if (!imported_) {
    preview_->clear();
    return false;
  }
  use_button_->setEnabled(true);
  return true;
}

}  // namespace palpa::ui
