#include "import_anatomy_dialog.hpp"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QScrollArea>
#include <QSpinBox>
#include <QStyle>
#include <QVBoxLayout>

#include "import_label_map.hpp"
#include "import_preview.hpp"
#include "palpa/anatomy/import_error.hpp"
#include "palpa/anatomy_io/anatomy_io.hpp"
#include "palpa/ui/window_frame.hpp"
#include "spin_box.hpp"

namespace palpa::ui {
namespace {

const char* const kInputFilter =
    "Label volumes and meshes (*.nii *.nii.gz *.nrrd *.nhdr *.mhd *.mha *.vti *.stl *.obj *.ply);;"
    "Label volumes (*.nii *.nii.gz *.nrrd *.nhdr *.mhd *.mha *.vti);;Meshes (*.stl *.obj *.ply);;All files (*)";

/// A scroll area that asks for its content's height as it is now (a label table shown, a
/// box hidden): QScrollArea keeps the size hint its content had the first time.
class InputsArea : public QScrollArea {
 public:
  using QScrollArea::QScrollArea;
  QSize sizeHint() const override {
    if (!widget()) return QScrollArea::sizeHint();
    const int bar = style()->pixelMetric(QStyle::PM_ScrollBarExtent);
    return widget()->sizeHint() + QSize(bar + 2 * frameWidth(), 2 * frameWidth());
  }
};

}  // namespace

ImportAnatomyDialog::ImportAnatomyDialog(QWidget* parent) : QDialog(parent) {
  setObjectName("importAnatomyDialog");
  setWindowTitle(tr("Import anatomy"));
  auto* layout = new QVBoxLayout(this);
  // The inputs scroll when the screen is too small for them and the preview; the error
  // line, the preview and the buttons stay in sight.
  auto* inputs = inputs_ = new InputsArea(this);
  inputs->setObjectName("importInputs");
  inputs->setWidgetResizable(true);
  inputs->setFrameShape(QFrame::NoFrame);
  auto* form = new QWidget(inputs);
  auto* form_layout = new QVBoxLayout(form);
  form_layout->setContentsMargins(0, 0, 0, 0);
  form_layout->addWidget(build_file_row());
  form_layout->addWidget(volume_box_ = build_volume_box());
  form_layout->addWidget(mesh_box_ = build_mesh_box());
  form_layout->addWidget(build_grid_row());
  form_layout->addStretch(1);
  inputs->setWidget(form);
  layout->addWidget(inputs);
  error_ = new QLabel(this);
  error_->setObjectName("importError");
  error_->setStyleSheet("color: #c00000;");
  error_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  layout->addWidget(error_);
  preview_ = new ImportPreview(this);
  layout->addWidget(preview_, 1);
  layout->addWidget(build_buttons());
  input_changed();
  fit_to_screen(*this, {1100, 696});  // a 1280 x 800 screen under a title bar and a panel
}

ImportAnatomyDialog::~ImportAnatomyDialog() = default;

QWidget* ImportAnatomyDialog::path_row(QLineEdit*& edit, const QString& name, const QString& title,
                                       const QString& filter) {
  auto* row = new QWidget(this);
  auto* layout = new QHBoxLayout(row);
  layout->setContentsMargins(0, 0, 0, 0);
  edit = new QLineEdit(row);
  edit->setObjectName(name);
  auto* browse = new QPushButton(tr("Browse…"), row);
  browse->setAutoDefault(false);
  layout->addWidget(edit, 1);
  layout->addWidget(browse);
  QLineEdit* target = edit;
  connect(browse, &QPushButton::clicked, this, [this, target, title, filter] {
    const QString path = QFileDialog::getOpenFileName(this, title, target->text(), filter);
    if (!path.isEmpty()) {
      target->setText(path);
      emit target->editingFinished();
    }
  });
  return row;
}

QWidget* ImportAnatomyDialog::build_file_row() {
  auto* box = new QWidget(this);
  auto* form = new QFormLayout(box);
  form->setContentsMargins(0, 0, 0, 0);
  form->addRow(tr("File:"), path_row(path_, "importPath", tr("Import anatomy"), tr(kInputFilter)));
  connect(path_, &QLineEdit::textChanged, this, &ImportAnatomyDialog::input_changed);
  connect(path_, &QLineEdit::editingFinished, this, [this] {
    if (table_choice_->currentData().toString() == "map") read_labels();
  });
  return box;
}

QGroupBox* ImportAnatomyDialog::build_volume_box() {
  auto* box = new QGroupBox(tr("Label volume"), this);
  auto* form = new QFormLayout(box);
  table_choice_ = new QComboBox(box);
  table_choice_->setObjectName("labelTable");
  table_choice_->addItem(tr("Built-in VICTRE"), "victre");
  table_choice_->addItem(tr("Built-in generic"), "generic");
  table_choice_->addItem(tr("Label table file (.json)"), "file");
  table_choice_->addItem(tr("Map labels…"), "map");
  form->addRow(tr("Labels:"), table_choice_);
  table_file_row_ = path_row(table_path_, "labelTablePath", tr("Label table"), tr("Label tables (*.json)"));
  form->addRow(tr("Table file:"), table_file_row_);
  map_ = new LabelMapTable(box);
  map_->setObjectName("labelMap");
  map_->setMinimumHeight(150);
  form->addRow(map_);
  connect(table_choice_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          &ImportAnatomyDialog::table_choice_changed);
  return box;
}

QGroupBox* ImportAnatomyDialog::build_mesh_box() {
  auto* box = new QGroupBox(tr("Mesh (coordinates in mm)"), this);
  auto* form = new QFormLayout(box);
  support_kind_ = new QComboBox(box);
  support_kind_->setObjectName("supportKind");
  support_kind_->addItem(tr("Support mesh file"), "mesh");
  support_kind_->addItem(tr("Support plane"), "plane");
  form->addRow(tr("Rests on:"), support_kind_);
  support_file_row_ = path_row(support_path_, "supportPath", tr("Support mesh"), tr("Meshes (*.stl *.obj *.ply)"));
  form->addRow(tr("Support mesh:"), support_file_row_);
  plane_row_ = new QWidget(box);
  auto* plane = new QHBoxLayout(plane_row_);
  plane->setContentsMargins(0, 0, 0, 0);
  const std::array<const char*, 4> names = {"planeNx", "planeNy", "planeNz", "planeD"};
  const std::array<double, 4> start = {0.0, 0.0, 1.0, 0.0};
  const std::array<const char*, 4> labels = {"nx", "ny", "nz", "d"};
  for (std::size_t k = 0; k < 4; ++k) {
    plane_[k] = k < 3 ? spin(plane_row_, -1.0, 1.0, 0.1, 3, QString()) : spin(plane_row_, -1e4, 1e4, 1.0, 2, tr(" mm"));
    plane_[k]->setObjectName(names[k]);
    plane_[k]->setValue(start[k]);
    plane->addWidget(new QLabel(QString::fromLatin1(labels[k]), plane_row_));
    plane->addWidget(plane_[k]);
  }
  form->addRow(tr("Plane nx x + ny y + nz z + d = 0:"), plane_row_);
  modulus_ = spin(box, 0.01, 1e6, 0.5, 2, tr(" kPa"));
  modulus_->setObjectName("tissueModulus");
  modulus_->setValue(anatomy::builtin_label_table("generic").labels.at(1).modulus / 1e3);
  form->addRow(tr("Tissue's Young's modulus:"), modulus_);
  connect(support_kind_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this] {
    const bool on_plane = support_kind_->currentData().toString() == "plane";
    support_file_row_->setEnabled(!on_plane);
    plane_row_->setEnabled(on_plane);
  });
  plane_row_->setEnabled(false);
  return box;
}

QWidget* ImportAnatomyDialog::build_grid_row() {
  auto* row = new QWidget(this);
  auto* layout = new QHBoxLayout(row);
  layout->setContentsMargins(0, 0, 0, 0);
  grid_auto_ = new QCheckBox(tr("Grid chosen automatically"), row);
  grid_auto_->setObjectName("gridAuto");
  grid_auto_->setChecked(true);
  rows_ = new QSpinBox(row);
  cols_ = new QSpinBox(row);
  rows_->setObjectName("gridRows");
  cols_->setObjectName("gridCols");
  for (auto* box : {rows_, cols_}) {
    box->setRange(5, 256);
    box->setValue(33);
    box->setEnabled(false);
  }
  layout->addWidget(grid_auto_);
  layout->addWidget(new QLabel(tr("or skeleton points:"), row));
  layout->addWidget(rows_);
  layout->addWidget(new QLabel(QStringLiteral("×"), row));
  layout->addWidget(cols_);
  layout->addStretch(1);
  connect(grid_auto_, &QCheckBox::toggled, this, [this](bool automatic) {
    rows_->setEnabled(!automatic);
    cols_->setEnabled(!automatic);
  });
  return row;
}

QWidget* ImportAnatomyDialog::build_buttons() {
  auto* row = new QWidget(this);
  auto* layout = new QHBoxLayout(row);
  layout->setContentsMargins(0, 0, 0, 0);
  import_button_ = new QPushButton(tr("Import"), row);
  use_button_ = new QPushButton(tr("Use this case"), row);
  auto* cancel = new QPushButton(tr("Cancel"), row);
  import_button_->setDefault(true);
  use_button_->setAutoDefault(false);
  cancel->setAutoDefault(false);
  use_button_->setEnabled(false);
  layout->addStretch(1);
  layout->addWidget(import_button_);
  layout->addWidget(use_button_);
  layout->addWidget(cancel);
  connect(import_button_, &QPushButton::clicked, this, [this] { run_import(); });
  connect(use_button_, &QPushButton::clicked, this, &QDialog::accept);
  connect(cancel, &QPushButton::clicked, this, &QDialog::reject);
  return row;
}

}  // namespace palpa::ui
