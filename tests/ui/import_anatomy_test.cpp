// Import anatomy… in the instructor window (its Case menu; File > Import anatomy… is
// tested from the application's windows in app_windows_test.cpp), driven as a person does: the menu
// action, the path typed into the dialog, the label table chosen with the keyboard, the
// dialog's buttons clicked. A dome of tissue (label 1) on a support (3) with a lesion ball
// (4), 2 mm voxels (tests/core/anatomy/analytic_bodies.hpp): the generic table and the same
// labels mapped by hand each give one body and one tumour at the ball; saved, the case
// loads and keeps its provenance and exam region. A skin mesh on a support mesh takes the
// tissue's modulus typed in kPa. A text file named .nrrd shows one line
// in the dialog; Cancel, and a failed import, leave the draft as it was.
#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QDialog>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QMenu>
#include <QMenuBar>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QtTest>
#include <fstream>

#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkRenderer.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkScalarBarActor.h>

#include "../../ui/src/import_label_map.hpp"
#include "../../ui/src/import_preview.hpp"
#include "../core/anatomy/analytic_bodies.hpp"
#include "../core/anatomy/analytic_meshes.hpp"
#include "palpa/anatomy_io/anatomy_io.hpp"
#include "palpa/author/case_draft.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/ui/instructor_window.hpp"
#include "palpa/ui/trainee_window.hpp"
#include "fits_screen.hpp"

namespace {

using palpa::ui::InstructorWindow;

QAction* menu_action(InstructorWindow& window, const QString& text) {
  for (auto* menu : window.menuBar()->findChildren<QMenu*>()) {
    for (auto* action : menu->actions()) {
      if (action->text().remove('&') == text) return action;
    }
  }
  return nullptr;
}

// The Import anatomy dialog the window shows after its menu action is triggered.
QDialog* open_import(InstructorWindow& window) {
  QAction* action = menu_action(window, QString::fromUtf8("Import anatomy…"));
  if (!action) return nullptr;
  action->trigger();
  for (int tries = 0; tries < 100; ++tries) {
    for (auto* w : QApplication::topLevelWidgets()) {
      auto* dialog = qobject_cast<QDialog*>(w);
      if (dialog && dialog->objectName() == "importAnatomyDialog" && dialog->isVisible()) {
        QApplication::setActiveWindow(dialog);  // Xvfb has no window manager to activate it
        return dialog;
      }
    }
    QTest::qWait(20);
  }
  return nullptr;
}

QPushButton* button(QDialog* dialog, const QString& text) {
  for (auto* b : dialog->findChildren<QPushButton*>()) {
    if (b->text() == text) return b;
  }
  return nullptr;
}

void type_line(QDialog* dialog, const char* name, const QString& text) {
  auto* edit = dialog->findChild<QLineEdit*>(name);
  QVERIFY(edit);
  edit->setFocus();
  QTest::keyClick(edit, Qt::Key_A, Qt::ControlModifier);
  QTest::keyClicks(edit, text);
  QTest::keyClick(edit, Qt::Key_Tab);  // editingFinished, as leaving the field
}

// Moves a closed combo box `steps` items down with the arrow key.
void arrow_down(QComboBox* box, int steps) {
  box->setFocus();
  for (int k = 0; k < steps; ++k) QTest::keyClick(box, Qt::Key_Down);
}

void click(QPushButton* b) {
  QVERIFY(b && b->isEnabled());
  QTest::mouseClick(b, Qt::LeftButton);
}

/// The dome with its lesion ball, written as a label volume in `dir`.
QString write_dome(const QTemporaryDir& dir) {
  const QString path = dir.filePath("dome.nrrd");
  palpa::anatomy_io::write_label_volume(path.toStdString(),
                                        palpa::anatomy::testing::voxelize(palpa::anatomy::testing::dome_on_plane(), 2e-3));
  return path;
}

/// `mesh` turned a quarter round the x axis: what faced +z faces +y (a chest wall in RAS
/// coordinates faces the breast's front, +y).
palpa::anatomy::TriangleMesh facing_y(palpa::anatomy::TriangleMesh mesh) {
  for (auto& p : mesh.points) p = {p[0], p[2], -p[1]};
  return mesh;
}

std::string read_text(const QString& path) {
  std::ifstream in(path.toStdString());
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

class ImportAnatomyTest : public QObject {
  Q_OBJECT

  // One body, one tumour within one voxel (2 mm) of the ball's centre, in kPa.
  static void check_draft(const InstructorWindow& window) {
    const auto& doc = window.draft().document();
    QCOMPARE(doc["bodies"].size(), std::size_t{1});
    QCOMPARE(window.draft().tumour_count(), std::size_t{1});
    const auto ball = *palpa::anatomy::testing::dome_on_plane().lesion;
    const auto t = *window.draft().tumour(0);
    const double off = (palpa::Vec3(t.center[0], t.center[1], t.center[2]) - ball.centre).norm();
    QVERIFY2(off < 2e-3, qPrintable(QString::number(off * 1e3) + " mm"));
    QVERIFY(window.draft().tissue_in_pa());
    QVERIFY(doc.contains("provenance") && doc.contains("exam_region"));
    QVERIFY(window.draft().validate().empty());
  }

  // The preview: the top contour coloured by its fit error (mm) under its legend, one
  // lesion drawn, and the summary in mm and kPa.
  static void check_preview(QDialog* dialog) {
    auto* preview = dialog->findChild<palpa::ui::ImportPreview*>();
    QVERIFY(preview && preview->top());
    vtkDataArray* errors = preview->top()->GetPointData()->GetScalars();
    QVERIFY(errors && QString(errors->GetName()) == "fit error (mm)");
    double range[2];
    errors->GetRange(range);
    QVERIFY2(range[0] >= 0.0 && range[1] < 3.0, qPrintable(QString("%1 %2").arg(range[0]).arg(range[1])));
    QCOMPARE(QString(preview->legend()->GetTitle()), QString("fit error (mm)"));
    QCOMPARE(preview->lesion_actors(), 1);
    const QString summary = dialog->findChild<QPlainTextEdit*>("importSummary")->toPlainText();
    QVERIFY2(summary.contains("Grid: ") && summary.contains("Tumours: 1") && summary.contains(" kPa") &&
                 summary.contains("top (skin): max ") && !summary.contains("N/m"),
             qPrintable(summary));
  }

 private slots:
  // Generic table; then the title edited and the case saved: it loads and keeps "provenance".
  void labelVolumeWithTheGenericTable() {
    QTemporaryDir dir;
    const QString volume = write_dome(dir);
    InstructorWindow window{palpa::author::CaseDraft()};
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QDialog* dialog = open_import(window);
    QVERIFY(dialog);
    type_line(dialog, "importPath", volume);
    arrow_down(dialog->findChild<QComboBox*>("labelTable"), 1);  // VICTRE -> generic
    QCOMPARE(dialog->findChild<QComboBox*>("labelTable")->currentData().toString(), QString("generic"));
    click(button(dialog, "Import"));
    QVERIFY2(dialog->findChild<QLabel*>("importError")->text().isEmpty(),
             qPrintable(dialog->findChild<QLabel*>("importError")->text()));
    check_preview(dialog);
    click(button(dialog, "Use this case"));
    QTRY_VERIFY(!dialog->isVisible());
    check_draft(window);
    QVERIFY2(window.message().startsWith("Imported dome.nrrd"), qPrintable(window.message()));

    auto* title = window.title_edit();
    title->setFocus();
    QTest::keyClick(title, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(title, "Dome with a lump");
    QTest::keyClick(title, Qt::Key_Return);
    const QString saved = dir.filePath("dome-case.json");
    window.set_save_path_chooser([saved] { return saved; });
    menu_action(window, "Save As...")->trigger();
    const palpa::io::CaseFile file = palpa::io::load_case(saved.toStdString());  // throws when invalid
    QCOMPARE(file.title, std::string("Dome with a lump"));
    QCOMPARE(file.tumours.size(), std::size_t{1});
    const auto doc = nlohmann::json::parse(read_text(saved));
    QVERIFY(doc.contains("provenance") && doc.contains("exam_region"));
    QCOMPARE(doc["provenance"]["source"].get<std::string>(), std::string("dome.nrrd"));
    QCOMPARE(doc["provenance"]["labels"].get<std::string>(), std::string("generic"));
    QCOMPARE(doc["provenance"]["tool"].get<std::string>(), std::string("palpa instructor window"));
  }

  // "Map labels…" lists labels 0, 1, 3 and 4 with their voxels; 3 set to support and 4 to
  // a lesion of 60 kPa with the keyboard give the same case, the tumour at 60 kPa.
  void labelsMappedByHand() {
    QTemporaryDir dir;
    const QString volume = write_dome(dir);
    InstructorWindow window{palpa::author::CaseDraft()};
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QDialog* dialog = open_import(window);
    QVERIFY(dialog);
    type_line(dialog, "importPath", volume);
    arrow_down(dialog->findChild<QComboBox*>("labelTable"), 3);  // -> Map labels…
    auto* map = dialog->findChild<QTableWidget*>("labelMap");
    QVERIFY(map && map->isVisible());
    QCOMPARE(map->rowCount(), 4);
    QStringList labels;
    for (int r = 0; r < 4; ++r) labels << map->item(r, 0)->text();
    QCOMPARE(labels, (QStringList{"0", "1", "3", "4"}));
    QVERIFY(map->item(1, 1)->text().toLongLong() > 1000);  // voxels of tissue
    arrow_down(qobject_cast<QComboBox*>(map->cellWidget(2, 2)), 2);  // tissue -> support
    arrow_down(qobject_cast<QComboBox*>(map->cellWidget(3, 2)), 3);  // tissue -> lesion
    QCOMPARE(qobject_cast<QComboBox*>(map->cellWidget(3, 2))->currentText(), QString("lesion"));
    auto* modulus = qobject_cast<QDoubleSpinBox*>(map->cellWidget(3, 4));
    QVERIFY(modulus->isEnabled() && !qobject_cast<QDoubleSpinBox*>(map->cellWidget(2, 4))->isEnabled());
    modulus->setFocus();
    QTest::keyClick(modulus, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(modulus, "60");
    QTest::keyClick(modulus, Qt::Key_Tab);
    QCOMPARE(modulus->value(), 60.0);
    click(button(dialog, "Import"));
    QVERIFY2(dialog->findChild<QLabel*>("importError")->text().isEmpty(),
             qPrintable(dialog->findChild<QLabel*>("importError")->text()));
    check_preview(dialog);
    click(button(dialog, "Use this case"));
    QTRY_VERIFY(!dialog->isVisible());
    check_draft(window);
    QCOMPARE(window.draft().tumour(0)->modulus, 60e3);
    const auto& provenance = window.draft().document()["provenance"];
    QCOMPARE(provenance["labels"].get<std::string>(), std::string("labels mapped by hand"));
    QVERIFY(provenance["options"].get<std::string>().find("4 lesion \"label 4\" 60 kPa") != std::string::npos);
  }

  // A skin mesh on a support mesh (mm, as 3D Slicer writes them) with the tissue typed in
  // kPa: one body of that modulus, no tumours, the support mesh named in the provenance.
  void skinMeshOnASupportMesh() {
    QTemporaryDir dir;
    const auto dome = palpa::anatomy::testing::dome_on_plane();
    const QString skin = dir.filePath("skin.stl"), support = dir.filePath("support.stl");
    palpa::anatomy_io::write_mesh(skin.toStdString(), palpa::anatomy::testing::skin_mesh(dome, 2e-3));
    palpa::anatomy_io::write_mesh(support.toStdString(), palpa::anatomy::testing::support_mesh(dome));
    InstructorWindow window{palpa::author::CaseDraft()};
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QDialog* dialog = open_import(window);
    QVERIFY(dialog);
    type_line(dialog, "importPath", skin);
    QVERIFY(dialog->findChild<QComboBox*>("supportKind")->isVisible());
    type_line(dialog, "supportPath", support);
    auto* modulus = dialog->findChild<QDoubleSpinBox*>("tissueModulus");
    modulus->setFocus();
    QTest::keyClick(modulus, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(modulus, "5");
    QTest::keyClick(modulus, Qt::Key_Tab);
    click(button(dialog, "Import"));
    QVERIFY2(dialog->findChild<QLabel*>("importError")->text().isEmpty(),
             qPrintable(dialog->findChild<QLabel*>("importError")->text()));
    click(button(dialog, "Use this case"));
    QTRY_VERIFY(!dialog->isVisible());
    const auto& doc = window.draft().document();
    QCOMPARE(doc["bodies"].size(), std::size_t{1});
    QCOMPARE(window.draft().tumour_count(), std::size_t{0});
    for (const auto& e : doc["bodies"][0]["modulus"]) QCOMPARE(e.get<double>(), 5000.0);
    QCOMPARE(doc["provenance"]["support_source"].get<std::string>(), std::string("support.stl"));
    QVERIFY(window.draft().validate().empty());
  }

  // The dialog fits a 1280 x 800 screen under a title bar and a panel (it opened 1100 x 820),
  // its buttons inside: empty, with the label mapping table (its tallest inputs) and with
  // an import previewed.
  void theDialogFitsTheScreen() {
    QTemporaryDir dir;
    InstructorWindow window{palpa::author::CaseDraft()};
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QDialog* dialog = open_import(window);
    QVERIFY(dialog);
    QVERIFY(QTest::qWaitForWindowExposed(dialog));
    const QList<QWidget*> buttons{button(dialog, "Import"), button(dialog, "Use this case"), button(dialog, "Cancel")};
    palpa::ui::testing::check_fits_screen(*dialog, buttons);
    type_line(dialog, "importPath", write_dome(dir));
    auto* table = dialog->findChild<QComboBox*>("labelTable");
    arrow_down(table, 3);  // -> Map labels…
    QTRY_VERIFY(dialog->findChild<QTableWidget*>("labelMap")->isVisible());
    palpa::ui::testing::check_fits_screen(*dialog, buttons);
    table->setFocus();
    QTest::keyClick(table, Qt::Key_Up);
    QTest::keyClick(table, Qt::Key_Up);  // -> generic
    click(button(dialog, "Import"));
    QVERIFY(button(dialog, "Use this case")->isEnabled());
    palpa::ui::testing::check_fits_screen(*dialog, buttons);
    click(button(dialog, "Cancel"));
    QTRY_VERIFY(!dialog->isVisible());
  }

  // Skin and support meshes whose support faces +y (as the VICTRE breast's chest wall):
  // after "Use this case" the view looks down the body's press axis, at its free side, not
  // at the back of the support.
  void anImportedBodyIsSeenFromItsFreeSide() {
    QTemporaryDir dir;
    const auto dome = palpa::anatomy::testing::dome_on_plane();
    const QString skin = dir.filePath("skin.stl"), support = dir.filePath("support.stl");
    palpa::anatomy_io::write_mesh(skin.toStdString(), facing_y(palpa::anatomy::testing::skin_mesh(dome, 2e-3)));
    palpa::anatomy_io::write_mesh(support.toStdString(), facing_y(palpa::anatomy::testing::support_mesh(dome)));
    InstructorWindow window{palpa::author::CaseDraft()};
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QDialog* dialog = open_import(window);
    QVERIFY(dialog);
    type_line(dialog, "importPath", skin);
    type_line(dialog, "supportPath", support);
    click(button(dialog, "Import"));
    QVERIFY2(dialog->findChild<QLabel*>("importError")->text().isEmpty(),
             qPrintable(dialog->findChild<QLabel*>("importError")->text()));
    click(button(dialog, "Use this case"));
    QTRY_VERIFY(!dialog->isVisible());
    const auto scene = palpa::scene::Scene::build(window.draft().valid_case(), "imported");
    const palpa::Vec3 up = scene.body(0).press_axis.up;
    QVERIFY2(up.y() > 0.95, qPrintable(QString("%1 %2 %3").arg(up.x()).arg(up.y()).arg(up.z())));
    double d[3];
    window.renderer()->GetActiveCamera()->GetDirectionOfProjection(d);
    const double along = palpa::Vec3(d[0], d[1], d[2]).dot(up);
    QVERIFY2(along < -0.95, qPrintable(QString::number(along)));
  }

  // A mapping of many labels is recorded whole entries at a time, within what a case's
  // provenance keeps (1024 characters).
  void aLongMappingStaysWithinTheProvenanceLimit() {
    palpa::ui::LabelMapTable map;
    std::map<int, std::size_t> counts;
    for (int label = 0; label < 300; ++label) counts[label] = 10;
    map.set_labels(counts);
    QCOMPARE(map.rowCount(), 300);
    const std::string text = map.describe();
    QVERIFY2(text.size() <= 900 && text.size() > 800, text.c_str());
    QVERIFY(text.rfind("; ...") == text.size() - 5);
    QCOMPARE(map.table().labels.size(), std::size_t{300});
  }

  // A text file named .nrrd: one line in the dialog, nothing to use, the draft as it was.
  void unreadableFileShowsOneLine() {
    QTemporaryDir dir;
    const QString bad = dir.filePath("notes.nrrd");
    std::ofstream(bad.toStdString()) << "these are my notes, not a volume\n";
    InstructorWindow window{palpa::author::CaseDraft()};
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    const nlohmann::json before = window.draft().document();
    QDialog* dialog = open_import(window);
    QVERIFY(dialog);
    type_line(dialog, "importPath", bad);
    arrow_down(dialog->findChild<QComboBox*>("labelTable"), 1);
    click(button(dialog, "Import"));
    const QString error = dialog->findChild<QLabel*>("importError")->text();
    QVERIFY(!error.isEmpty());
    QVERIFY2(!error.contains('\n') && error.contains("notes.nrrd"), qPrintable(error));
    QVERIFY(dialog->isVisible());
    QVERIFY(!button(dialog, "Use this case")->isEnabled());
    click(button(dialog, "Cancel"));
    QTRY_VERIFY(!dialog->isVisible());
    QVERIFY(window.draft().document() == before);
    QVERIFY(!window.draft().dirty());
  }

  // Cancel after a successful import (previewed): the draft is as it was.
  void cancelChangesNothing() {
    QTemporaryDir dir;
    const QString volume = write_dome(dir);
    InstructorWindow window{palpa::author::CaseDraft()};
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    const nlohmann::json before = window.draft().document();
    QDialog* dialog = open_import(window);
    QVERIFY(dialog);
    type_line(dialog, "importPath", volume);
    arrow_down(dialog->findChild<QComboBox*>("labelTable"), 1);
    click(button(dialog, "Import"));
    QVERIFY(button(dialog, "Use this case")->isEnabled());
    click(button(dialog, "Cancel"));
    QTRY_VERIFY(!dialog->isVisible());
    QVERIFY(window.draft().document() == before);
    QVERIFY(!window.draft().dirty());
    QCOMPARE(window.draft().tumour_count(), std::size_t{0});
  }
};

/// The tests, for the instructor tests' main (tests/ui/instructor_window_test.cpp).
QObject* make_import_anatomy_test() { return new ImportAnatomyTest; }

#include "import_anatomy_test.moc"
