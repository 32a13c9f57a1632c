// The instructor's authoring window under Xvfb: it opens on a new breast; the preset
// controls change the drawn body; a click on the body places a tumour under it at the set
// depth; undo/redo (actions and keys); save -> open round-trips the case; a bad case shows
// its problem at the field; a grayscale image sets the stiffness; "Try it" opens a trainee
// window recording a session; palpa --mode instructor --screenshot draws the body. Also:
// values typed but not committed (Save, Undo), Save As next to an existing file, Undo
// keys from side-panel editors, the wheel over unfocused boxes, a one-field tumour edit,
// the owner's device for "Try it", closing the window finishes the Try-it sessions.
#include <QAbstractSpinBox>
#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QImage>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QProcess>
#include <QRegularExpression>
#include <QPushButton>
#include <QScrollArea>
#include <QScrollBar>
#include <QSurfaceFormat>
#include <QTabBar>
#include <QTabWidget>
#include <QTableWidget>
#include <QPlainTextEdit>
#include <QHeaderView>
#include <QFontMetrics>
#include <QStyle>
#include <QTemporaryDir>
#include <QTimer>
#include <QToolBar>
#include <QVTKOpenGLNativeWidget.h>
#include <QWindow>
#include <QtTest>
#include <array>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkRenderer.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include "palpa/author/case_draft.hpp"
#include "palpa/mat/tissue_materials.hpp"
#include "palpa/engine/device.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/io/thresholds.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/ui/instructor_exam_panel.hpp"
#include "palpa/ui/instructor_preset_panel.hpp"
#include "palpa/ui/instructor_scene.hpp"
#include "palpa/ui/instructor_tumour_panel.hpp"
#include "palpa/ui/instructor_window.hpp"
#include "palpa/ui/trainee_window.hpp"
#include "palpa/ui/vtk_view.hpp"
#include "fits_screen.hpp"

namespace {

using palpa::author::Preset;
using palpa::ui::InstructorWindow;

const std::string kDefaultCase = PALPA_SOURCE_DIR "/data/cases/default.json";

/// Counts pixels of the skin colour the bodies are drawn in (as tests/ui/trainee_window_test.cpp).
int skin_pixels(const QImage& image) {
  int count = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const QColor c = image.pixelColor(x, y);
      if (c.red() > 90 && c.red() - c.blue() > 35 && c.green() > c.blue()) ++count;
    }
  }
  return count;
}

struct Run {
  int code = -1;
  QString out, err;
};

Run run_palpa(const QStringList& arguments) {
  QProcess p;
  p.start(PALPA_GUI_EXE, arguments);
  p.waitForFinished(60000);
  return {p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1, QString::fromUtf8(p.readAllStandardOutput()),
          QString::fromUtf8(p.readAllStandardError())};
}

void show(InstructorWindow& window) {
  window.show();
  QVERIFY(QTest::qWaitForWindowExposed(&window));
  QTest::qWait(50);
}

// A problem (not a warning) about this JSON pointer is listed.
bool has_problem(const InstructorWindow& window, const QString& where) {
  for (int k = 0; k < window.problems()->count(); ++k) {
    const auto* item = window.problems()->item(k);
    if (item->data(Qt::UserRole).toString() == where && !item->data(InstructorWindow::kWarningRole).toBool()) return true;
  }
  return false;
}

// The listed texts, problems and warnings.
QStringList problem_texts(const InstructorWindow& window) {
  QStringList out;
  for (int k = 0; k < window.problems()->count(); ++k) out << window.problems()->item(k)->text();
  return out;
}

// "12.0-15.0" within 0.15 mm of lo-hi.
bool near_range(const QString& text, double lo, double hi) {
  const QStringList ends = text.split('-');
  return ends.size() == 2 && std::abs(ends[0].toDouble() - lo) < 0.15 && std::abs(ends[1].toDouble() - hi) < 0.15;
}

// Whether a spin box is marked as holding a problem.
bool marked(const QWidget* box) { return box->styleSheet().contains("#ffc8c8"); }

/// A 64 x 32 grayscale ramp, black at the left to white at the right.
QImage ramp_along_x() {
  QImage ramp(64, 32, QImage::Format_Grayscale8);
  for (int y = 0; y < ramp.height(); ++y) {
    for (int x = 0; x < ramp.width(); ++x) {
      const int v = static_cast<int>(std::lround(x * 255.0 / 63.0));
      ramp.setPixelColor(x, y, QColor(v, v, v));
    }
  }
  return ramp;
}

// Brings the side panel's tab holding `w` to the front as a person does: a click on its tab.
void show_tab_of(QWidget* w) {
  for (QWidget* p = w; p; p = p->parentWidget()) {
    auto* tabs = qobject_cast<QTabWidget*>(p);
    if (!tabs) continue;
    for (int i = 0; i < tabs->count(); ++i) {
      if (tabs->widget(i) == w || tabs->widget(i)->isAncestorOf(w)) {
        if (tabs->currentIndex() != i) QTest::mouseClick(tabs->tabBar(), Qt::LeftButton, Qt::NoModifier, tabs->tabBar()->tabRect(i).center());
        return;
      }
    }
  }
}

// Types `text` into a spin box as a person does: its tab, focus, select all, type, Return.
void type_into(QAbstractSpinBox* box, const QString& text) {
  show_tab_of(box);
  box->setFocus();
  QTest::keyClick(box, Qt::Key_A, Qt::ControlModifier);
  QTest::keyClicks(box, text);
  QTest::keyClick(box, Qt::Key_Return);
}

void write_text(const QString& path, const std::string& text) { std::ofstream(path.toStdString()) << text; }

std::string read_text(const QString& path) {
  std::ifstream in(path.toStdString());
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Answers the next message box (from inside its exec loop) with `button` and keeps its
/// text in `*text`. Delete the returned timer when no box is expected any more.
QTimer* answer_next_box(QMessageBox::StandardButton button, QString* text) {
  auto* timer = new QTimer(qApp);
  timer->setInterval(10);
  QObject::connect(timer, &QTimer::timeout, [timer, button, text] {
    for (auto* w : QApplication::topLevelWidgets()) {
      auto* box = qobject_cast<QMessageBox*>(w);
      if (box && box->isVisible() && box->button(button)) {
        *text = box->text();
        timer->stop();
        box->button(button)->click();
        return;
      }
    }
  });
  timer->start();
  return timer;
}

/// A probe standing still above the body: the device the application would hand over.
class FakeProbe final : public palpa::engine::Device {
 public:
  FakeProbe() {
    caps_.name = "Fake probe";
    caps_.max_force = 5.0;
    caps_.force_output = true;
  }
  const palpa::engine::DeviceCapabilities& capabilities() const override { return caps_; }
  palpa::engine::DeviceStatus read(double, palpa::engine::DevicePose& pose) noexcept override {
    pose.position = palpa::Vec3(0.0, 0.0, 0.1);
    return palpa::engine::DeviceStatus::Ok;
  }
  palpa::engine::DeviceStatus write_force(const palpa::Vec3&) noexcept override {
    return palpa::engine::DeviceStatus::Ok;
  }

 private:
  palpa::engine::DeviceCapabilities caps_;
};

std::size_t files_in(const QString& dir) {
  std::size_t n = 0;
  std::error_code ec;
  for (auto it = std::filesystem::directory_iterator(dir.toStdString(), ec); !ec && it != std::filesystem::directory_iterator();
       it.increment(ec)) {
    ++n;
  }
  return n;
}

void wheel(QWidget* widget, int notches) {
  const QPoint at = widget->rect().center();
  QWheelEvent e(QPointF(at), QPointF(widget->mapToGlobal(at)), QPoint(), QPoint(0, 120 * notches), Qt::NoButton,
                Qt::NoModifier, Qt::NoScrollPhase, false);
  QApplication::sendEvent(widget, &e);
}

}  // namespace

class InstructorWindowTest : public QObject {
  Q_OBJECT
 private slots:
  void opensOnANewValidBreast() {
    InstructorWindow window{palpa::author::CaseDraft()};
    show(window);
    QVERIFY(window.scene().has_bodies());
    QCOMPARE(window.problems()->count(), 1);
    QVERIFY(window.problems()->item(0)->text().startsWith("No problems"));
    QCOMPARE(window.preset_panel()->preset_box()->currentData().toString(), QString("breast"));
    QVERIFY(!window.undo_action()->isEnabled());
    QVERIFY(!window.draft().dirty());
  }

  // The drawn body follows the controls: width 140 -> 100 mm narrows it along x; the slab
  // preset makes it 30 mm thick (top at z = T, bottom at 0).
  void presetControlsChangeTheDrawnBody() {
    InstructorWindow window{palpa::author::CaseDraft()};
    show(window);
    const auto before = window.scene().bounds();
    QVERIFY(std::abs((before[1] - before[0]) - 0.14) < 0.14 * 0.02);
    window.preset_panel()->width_box()->setValue(100.0);
    const auto narrow = window.scene().bounds();
    QVERIFY2(std::abs((narrow[1] - narrow[0]) - 0.10) < 0.10 * 0.02, qPrintable(QString::number(narrow[1] - narrow[0])));
    QVERIFY(std::abs((narrow[3] - narrow[2]) - (before[3] - before[2])) < 1e-6);  // length unchanged
    QCOMPARE(window.draft().preset()->width, 0.1);
    QVERIFY(window.draft().dirty());
    const int slab = window.preset_panel()->preset_box()->findData(QString("slab"));
    window.preset_panel()->preset_box()->setCurrentIndex(slab);
    const auto flat = window.scene().bounds();
    QVERIFY2(std::abs((flat[5] - flat[4]) - 0.03) < 5e-4, qPrintable(QString::number(flat[5] - flat[4])));
    QVERIFY(std::abs((flat[1] - flat[0]) - 0.12) < 0.12 * 0.02);
    QCOMPARE(window.draft().document()["bodies"][0]["id"].get<std::string>(), std::string("slab"));
  }

  // A scripted click over the slab's centre places a tumour straight under it, at the depth
  // set in the panel below the top (z = thickness there); undo and redo by action and key.
  void clickPlacesATumourAtTheSetDepthAndUndoRedo() {
    InstructorWindow window{palpa::author::CaseDraft(palpa::author::preset_defaults(Preset::Slab))};
    show(window);
    window.tumour_panel()->depth_box()->setValue(12.0);
    window.tumour_panel()->radius_box()->setValue(4.0);
    const double top = 0.03;
    const QPoint at = window.to_view(palpa::Vec3(0.0, 0.0, top));
    QTest::mouseClick(window.view()->input(), Qt::LeftButton, Qt::NoModifier, at);
    QCOMPARE(window.draft().tumour_count(), std::size_t{1});
    const auto t = *window.draft().tumour(0);
    // One pixel is about 0.15 mm at this zoom.
    QVERIFY2(std::abs(t.center[0]) < 1e-3 && std::abs(t.center[1]) < 1e-3,
             qPrintable(QString("%1 %2").arg(t.center[0]).arg(t.center[1])));
    QVERIFY2(std::abs(t.center[2] - (top - 0.012)) < 2e-4, qPrintable(QString::number(t.center[2])));
    QCOMPARE(t.radius, 0.004);
    QCOMPARE(window.scene().tumour_count(), std::size_t{1});
    QCOMPARE(window.tumour_panel()->selected(), std::optional<std::size_t>(0));
    QVERIFY(has_problem(window, "No problems") || window.problems()->item(0)->text().startsWith("No problems"));

    // Off the body: nothing placed.
    QTest::mouseClick(window.view()->input(), Qt::LeftButton, Qt::NoModifier, QPoint(3, 3));
    QCOMPARE(window.draft().tumour_count(), std::size_t{1});

    // Editing the selected tumour's depth is one more undo step.
    window.tumour_panel()->depth_box()->setValue(15.0);
    QVERIFY(std::abs(window.draft().tumour(0)->center[2] - (top - 0.015)) < 2e-4);
    window.undo_action()->trigger();
    QVERIFY(std::abs(window.draft().tumour(0)->center[2] - (top - 0.012)) < 2e-4);
    window.undo_action()->trigger();
    QCOMPARE(window.draft().tumour_count(), std::size_t{0});
    QCOMPARE(window.scene().tumour_count(), std::size_t{0});
    QVERIFY(window.redo_action()->isEnabled());
    // Ctrl+Shift+Z redoes, Ctrl+Z undoes, in the active window (Xvfb has no window manager
    // to activate it).
    QApplication::setActiveWindow(&window);
    QTest::keyClick(&window, Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
    QCOMPARE(window.draft().tumour_count(), std::size_t{1});
    QTest::keyClick(&window, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(window.draft().tumour_count(), std::size_t{0});
  }

  void saveThenOpenRoundTripsTheCase() {
    QTemporaryDir dir;
    InstructorWindow window{palpa::author::CaseDraft(palpa::author::preset_defaults(Preset::Prostate))};
    show(window);
    window.title_edit()->setText("Prostate, one nodule");
    emit window.title_edit()->editingFinished();
    window.tumour_panel()->depth_box()->setValue(8.0);
    window.tumour_panel()->radius_box()->setValue(2.5);
    window.tumour_panel()->stiffness_box()->setValue(1500.0);
    QVERIFY(window.click_at(window.to_view(palpa::Vec3(0.0, 0.0, 0.03))));
    window.tumour_panel()->randomize_box()->setChecked(true);
    window.tumour_panel()->rule_box(4)->setValue(45.0);  // random depth from 45 % of the thickness
    QVERIFY(window.draft().placement(0).has_value());
    QCOMPARE(window.draft().placement(0)->depth[0], 0.45);
    const QString path = dir.filePath("prostate.json");
    QVERIFY2(window.save_as(path), qPrintable(window.message()));
    QVERIFY(!window.draft().dirty());
    QVERIFY(window.windowTitle().contains("prostate.json"));

    InstructorWindow again{palpa::author::CaseDraft()};
    QVERIFY(again.open_case(path));
    QCOMPARE(again.draft().document(), window.draft().document());
    QCOMPARE(again.title_edit()->text(), QString("Prostate, one nodule"));
    QCOMPARE(again.tumour_panel()->table()->rowCount(), 1);
    QCOMPARE(again.preset_panel()->preset_box()->currentData().toString(), QString("prostate"));
    // palpa-cli's reader agrees.
    const auto file = palpa::io::load_case(path.toStdString());
    QCOMPARE(file.tumours.size(), std::size_t{1});
    QCOMPARE(file.tumours[0].stiffness, 1500.0);
  }

  // A case whose tumour has radius 0 opens with the problem listed at /tumors/0/radius, the
  // tumour's radius cell highlighted; it cannot be saved or tried.
  void badCaseShowsItsProblemAtTheField() {
    QTemporaryDir dir;
    auto doc = palpa::io::to_json(palpa::io::load_case(kDefaultCase));
    doc["tumors"][0]["radius"] = 0.0;
    const QString bad = dir.filePath("bad.json");
    write_text(bad, doc.dump(2));
    InstructorWindow window{palpa::author::CaseDraft()};
    show(window);
    QVERIFY(window.open_case(bad));
    QVERIFY(has_problem(window, "/tumors/0/radius"));
    auto* cell = window.tumour_panel()->table()->item(0, 1);
    QVERIFY(cell != nullptr);
    QCOMPARE(cell->background().color(), QColor(255, 200, 200));
    QVERIFY(window.tumour_panel()->table()->item(0, 0)->background().style() == Qt::NoBrush);
    // Choosing the problem selects the tumour, whose radius box is then marked too.
    QVERIFY2(problem_texts(window).contains("Tumour 1, radius: 0 mm is outside (0, 1000] mm"),
             qPrintable(problem_texts(window).join("\n")));
    for (int k = 0; k < window.problems()->count(); ++k) {
      if (window.problems()->item(k)->data(Qt::UserRole).toString() == "/tumors/0/radius") window.problems()->setCurrentRow(k);
    }
    QCOMPARE(window.tumour_panel()->selected(), std::optional<std::size_t>(0));
    QVERIFY(!window.tumour_panel()->radius_box()->styleSheet().isEmpty());
    QVERIFY(window.tumour_panel()->stiffness_box()->styleSheet().isEmpty());
    QVERIFY(window.scene().has_bodies());  // the body is still drawn
    QVERIFY(!window.save_as(dir.filePath("out.json")));
    QVERIFY(!QFile::exists(dir.filePath("out.json")));
    QVERIFY(window.try_it() == nullptr);

    // Not JSON: one line naming the file and position; the current case stays.
    const QString broken = dir.filePath("broken.json");
    write_text(broken, "{ \"format\": ");
    QVERIFY(!window.open_case(broken));
    QVERIFY2(window.message().startsWith(broken + ": line "), qPrintable(window.message()));
    QCOMPARE(window.draft().source(), bad.toStdString());
    QVERIFY(has_problem(window, "/tumors/0/radius"));  // the current case's problems stay listed

    // A title too long is marked with its reason, and unmarked once fixed.
    window.title_edit()->setText(QString(static_cast<int>(palpa::io::CaseLimits::kMaxTitleLength) + 1, 'x'));
    emit window.title_edit()->editingFinished();
    QVERIFY(has_problem(window, "/title"));
    QVERIFY(!window.title_edit()->toolTip().isEmpty());
    window.title_edit()->setText("Short");
    emit window.title_edit()->editingFinished();
    QVERIFY(!has_problem(window, "/title"));
    QVERIFY(window.title_edit()->toolTip().isEmpty());
    QVERIFY(window.title_edit()->styleSheet().isEmpty());
  }

  // Bad values typed into the selected tumour's boxes: the problem names the table's row
  // and the field in mm, and exactly that field's box is marked. On the 30 mm slab (top at
  // z = 30 mm, base at 0) a 20 mm radius 12 mm deep reaches 20 - 12 = 8 mm above the top;
  // 40 mm deep puts the centre 10 mm under the base, the 4 mm tumour 14 mm beyond it.
  void typedBadValuesNameTheRowAndMarkTheirBox() {
    InstructorWindow window{palpa::author::CaseDraft(palpa::author::preset_defaults(Preset::Slab))};
    show(window);
    auto* panel = window.tumour_panel();
    type_into(panel->depth_box(), "12");
    type_into(panel->radius_box(), "4");
    QVERIFY(window.click_at(window.to_view(palpa::Vec3(-0.03, 0.0, 0.03))));
    QVERIFY(window.click_at(window.to_view(palpa::Vec3(0.0, 0.0, 0.03))));
    QCOMPARE(panel->selected(), std::optional<std::size_t>(1));
    QVERIFY(window.draft().validate().empty());

    type_into(panel->radius_box(), "20");
    QCOMPARE(window.draft().tumour(1)->radius, 0.020);
    QCOMPARE(window.problems()->count(), 1);
    const QString text = window.problems()->item(0)->text();
    const QRegularExpression reach("^Tumour 2, radius: 20 mm reaches ([0-9.]+) mm beyond the skin$");
    const auto m = reach.match(text);
    QVERIFY2(m.hasMatch(), qPrintable(text));
    QVERIFY2(std::abs(m.captured(1).toDouble() - 8.0) < 0.05, qPrintable(text));
    QVERIFY(marked(panel->radius_box()));
    QVERIFY(!marked(panel->depth_box()));
    QVERIFY(!marked(panel->stiffness_box()));
    QCOMPARE(panel->table()->item(1, 1)->background().color(), QColor(255, 200, 200));
    QVERIFY(panel->table()->item(1, 0)->background().style() == Qt::NoBrush);
    QVERIFY(panel->table()->item(0, 1)->background().style() == Qt::NoBrush);  // row 1 is fine

    type_into(panel->radius_box(), "4");
    QVERIFY(window.draft().validate().empty());
    type_into(panel->depth_box(), "40");
    QCOMPARE(window.problems()->count(), 1);
    const QString deep = window.problems()->item(0)->text();
    const QRegularExpression outside(
        "^Tumour 2, depth: its centre is outside the body \\(the tumour reaches ([0-9.]+) mm beyond the surface\\)$");
    const auto d = outside.match(deep);
    QVERIFY2(d.hasMatch(), qPrintable(deep));
    // The centre is 10 mm under the base, the sphere's far side 14 mm.
    QVERIFY2(d.captured(1).toDouble() >= 9.95 && d.captured(1).toDouble() <= 14.05, qPrintable(deep));
    QVERIFY(marked(panel->depth_box()));
    QVERIFY(!marked(panel->radius_box()));
    for (const QString& t : problem_texts(window)) QVERIFY2(!t.contains("/tumors") && !t.contains(" m "), qPrintable(t));
  }

  // Two depths, two names: "Depth below skin" (mm) and "Random depth" (% of the thickness,
  // with the mm it gives here). On the 30 mm slab a 40-50 % rule is 12-15 mm, and the table
  // shows that range for the randomized tumour, not the depth it was placed at.
  void randomDepthIsNamedApartAndShownInMm() {
    InstructorWindow window{palpa::author::CaseDraft(palpa::author::preset_defaults(Preset::Slab))};
    show(window);
    auto* panel = window.tumour_panel();
    QStringList labels;
    for (auto* l : panel->findChildren<QLabel*>()) labels << l->text();
    QVERIFY2(labels.contains("Depth below skin") && labels.contains("Random depth") && !labels.contains("Depth"),
             qPrintable(labels.join("|")));
    type_into(panel->depth_box(), "8");
    QVERIFY(window.click_at(window.to_view(palpa::Vec3(0.0, 0.0, 0.03))));
    QCOMPARE(panel->table()->item(0, 0)->text(), QString("8.00"));
    panel->randomize_box()->click();
    QVERIFY(window.draft().placement(0).has_value());
    QCOMPARE(window.draft().placement(0)->depth, (std::array<double, 2>{0.4, 0.5}));
    // The fitted slab is 30 mm thick to within 0.3 mm.
    QVERIFY2(near_range(panel->table()->item(0, 0)->text(), 12.0, 15.0), qPrintable(panel->table()->item(0, 0)->text()));
    const QString note = panel->random_depth_label()->text();
    QVERIFY2(note.startsWith("Random depth: 40-50 % of the thickness (") && note.endsWith(" mm here)"), qPrintable(note));
    QVERIFY2(near_range(note.section('(', 1).section(' ', 0, 0), 12.0, 15.0), qPrintable(note));
    QVERIFY(!panel->depth_box()->isEnabled());
    type_into(panel->rule_box(5), "60");
    QCOMPARE(window.draft().placement(0)->depth[1], 0.6);
    QVERIFY2(near_range(panel->table()->item(0, 0)->text(), 12.0, 18.0), qPrintable(panel->table()->item(0, 0)->text()));
    panel->randomize_box()->click();  // off: the depth it is written at again
    QVERIFY(!window.draft().placement(0).has_value());
    QCOMPARE(panel->table()->item(0, 0)->text(), QString("8.00"));
    QVERIFY(panel->depth_box()->isEnabled());
  }

  // A fibroadenoma at its 6.48 kPa, placed 10 mm deep with a 5 mm radius (the panel's
  // defaults) on the breast of 3.25 kPa fat, raises the force at deep pressure by a few per
  // cent: the case is valid (it saves) and a warning gives the number. The scripted expert
  // misses that tumour (core.AuthorPalpability runs it); at 9 mm it finds it, and the
  // warning goes.
  void aTumourLikelyNotPalpableIsWarnedWithItsNumber() {
    QTemporaryDir dir;
    InstructorWindow window{palpa::author::CaseDraft(palpa::author::preset_defaults_in_kpa(Preset::Breast))};
    show(window);
    auto* tissue = window.tumour_panel()->material_box();
    show_tab_of(tissue);
    tissue->setFocus();
    QTest::keyClick(tissue, Qt::Key_Up);  // from the carcinoma to the fibroadenoma
    QCOMPARE(tissue->currentData().toString(), QString("fibroadenoma"));
    const auto top = window.scene().pick(palpa::Vec3(0.03, 0.0, 1.0), palpa::Vec3(0.0, 0.0, -1.0));
    QVERIFY(top.has_value());
    QTest::mouseClick(window.view()->input(), Qt::LeftButton, Qt::NoModifier, window.to_view(top->point));
    QCOMPARE(window.draft().tumour_count(), std::size_t{1});
    QCOMPARE(window.draft().tumour(0)->modulus, 6480.0);
    QVERIFY(window.draft().validate().empty());
    const QStringList texts = problem_texts(window);
    QCOMPARE(texts.size(), 2);
    QCOMPARE(texts[0], QString("No problems: the case is valid (1 warning(s) below)."));
    const QRegularExpression warning(
        "^Tumour 1 may not be palpable: at deep pressure it raises the force by ([0-9]+) % \\(the scripted expert "
        "needs about 25 %\\)$");
    const auto m = warning.match(texts[1]);
    QVERIFY2(m.hasMatch(), qPrintable(texts[1]));
    QVERIFY2(m.captured(1).toInt() < 25, qPrintable(texts[1]));
    QVERIFY(window.problems()->item(1)->data(InstructorWindow::kWarningRole).toBool());
    QVERIFY(!has_problem(window, "/tumors/0"));
    QCOMPARE(window.tumour_panel()->table()->item(0, 2)->background().color(), QColor(255, 240, 190));
    QVERIFY2(window.save_as(dir.filePath("warned.json")), qPrintable(window.message()));  // valid all the same

    type_into(window.tumour_panel()->radius_box(), "9");
    QCOMPARE(window.draft().tumour(0)->radius, 0.009);
    QCOMPARE(problem_texts(window), QStringList{"No problems: the case is valid."});
  }

  // The description, the scoring thresholds in %, N, mm and s, and the exam region (part of
  // the body, in % along x and y) typed in, saved, and read back: the file holds them in SI
  // under "description", "scoring" and "exam_region" (docs/case-format.md), palpa-cli's
  // reader takes them, and another window shows the same.
  void examSettingsAreTypedSavedAndReloaded() {
    QTemporaryDir dir;
    InstructorWindow window{palpa::author::CaseDraft(palpa::author::preset_defaults_in_kpa(Preset::Breast))};
    show(window);
    QApplication::setActiveWindow(&window);  // focus moves as on a desktop (Xvfb has no window manager)
    auto* exam = window.exam_panel();
    show_tab_of(exam->description_edit());
    exam->description_edit()->setFocus();
    QTest::keyClicks(exam->description_edit(), "Two lumps, one benign.");
    const std::pair<const char*, const char*> typed[] = {{"min_coverage", "85"}, {"min_deep_coverage", "70"},
                                                         {"max_force", "12.5"},  {"hit_margin", "8"},
                                                         {"light_max", "25"},    {"deep_min", "55"},
                                                         {"min_duration", "90"}};
    for (const auto& [key, text] : typed) type_into(exam->scoring_box(key), text);
    QCOMPARE(window.draft().description(), std::string("Two lumps, one benign."));  // committed on leaving it
    auto* region = exam->region_box();
    QCOMPARE(region->currentText(), QString("Whole surface"));
    QVERIFY(!exam->extent_box(0)->isEnabled());
    region->setFocus();
    QTest::keyClick(region, Qt::Key_Down);
    QCOMPARE(region->currentText(), QString("Part of the body"));
    const char* extents[] = {"10", "60", "20", "80"};
    for (int c = 0; c < 4; ++c) type_into(exam->extent_box(c), extents[c]);

    const QString path = dir.filePath("exam.json");
    QVERIFY2(window.save_as(path), qPrintable(window.message()));
    const auto doc = nlohmann::json::parse(read_text(path));
    QCOMPARE(doc["description"], nlohmann::json("Two lumps, one benign."));
    const nlohmann::json expected = {{"min_coverage", 0.85}, {"min_deep_coverage", 0.70}, {"max_force", 12.5},
                                     {"hit_margin", 0.008},  {"light_max", 0.25},         {"deep_min", 0.55},
                                     {"min_duration", 90.0}};
    for (const auto& [key, value] : expected.items()) {
      QVERIFY2(doc["scoring"].contains(key), key.c_str());
      QVERIFY2(std::abs(doc["scoring"][key].get<double>() - value.get<double>()) < 1e-12,
               qPrintable(QString::fromStdString(key + ": " + doc["scoring"][key].dump())));
    }
    QCOMPARE(doc["exam_region"], nlohmann::json::parse(R"([{"body": "breast", "u": [0.1, 0.6], "v": [0.2, 0.8]}])"));
    std::vector<palpa::io::Problem> problems;
    const auto t = palpa::io::thresholds_from_case(palpa::io::load_case(path.toStdString()).document, problems);
    QVERIFY(problems.empty());
    QCOMPARE(t.hit_margin, 0.008);
    QCOMPARE(t.exam_region.size(), std::size_t{1});

    InstructorWindow again{palpa::author::CaseDraft()};
    QVERIFY(again.open_case(path));
    QCOMPARE(again.draft().document(), window.draft().document());
    QCOMPARE(again.exam_panel()->description_edit()->toPlainText(), QString("Two lumps, one benign."));
    QCOMPARE(again.exam_panel()->scoring_box("hit_margin")->value(), 8.0);
    QCOMPARE(again.exam_panel()->scoring_box("min_coverage")->value(), 85.0);
    QCOMPARE(again.exam_panel()->region_box()->currentText(), QString("Part of the body"));
    QCOMPARE(again.exam_panel()->extent_box(3)->value(), 80.0);

    // Bands that overlap: named in the window's words, the box at fault marked, not saved.
    type_into(exam->scoring_box("light_max"), "60");
    QVERIFY2(problem_texts(window).contains("Scoring, deep pressure from: light pressure up to 60 % must be below deep "
                                            "pressure from 55 % (light < medium < deep pressure)"),
             qPrintable(problem_texts(window).join("\n")));
    QVERIFY(marked(exam->scoring_box("deep_min")));
    QVERIFY(!marked(exam->scoring_box("max_force")));
    QVERIFY(!window.save());
  }

  // At 1280 x 800 every tab of the side panel fits without scrolling it, and every column
  // header of the tumour table is wide enough for its text.
  void everyColumnReadsAt1280x800WithoutScrolling() {
    InstructorWindow window{palpa::author::CaseDraft(palpa::author::preset_defaults_in_kpa(Preset::Breast))};
    window.resize(1280, 800);
    show(window);
    QCOMPARE(window.size(), QSize(1280, 800));
    const auto top = window.scene().pick(palpa::Vec3(0.0, 0.0, 1.0), palpa::Vec3(0.0, 0.0, -1.0));
    QVERIFY(top.has_value());
    QTest::mouseClick(window.view()->input(), Qt::LeftButton, Qt::NoModifier, window.to_view(top->point));
    window.tumour_panel()->randomize_box()->click();
    QTest::qWait(50);
    auto* scroll = window.findChild<QScrollArea*>("sidePanel");
    QVERIFY(scroll);
    auto* tabs = window.side_tabs();
    for (int i = 0; i < tabs->count(); ++i) {
      QTest::mouseClick(tabs->tabBar(), Qt::LeftButton, Qt::NoModifier, tabs->tabBar()->tabRect(i).center());
      QCOMPARE(tabs->currentIndex(), i);
      QTest::qWait(50);
      QVERIFY2(scroll->verticalScrollBar()->maximum() == 0,
               qPrintable(QString("%1: %2 px to scroll").arg(tabs->tabText(i)).arg(scroll->verticalScrollBar()->maximum())));
    }
    auto* header = window.tumour_panel()->table()->horizontalHeader();
    const int margin = 2 * header->style()->pixelMetric(QStyle::PM_HeaderMargin, nullptr, header);
    const QFontMetrics metrics(header->font());
    for (int c = 0; c < header->count(); ++c) {
      const QString text = window.tumour_panel()->table()->horizontalHeaderItem(c)->text();
      const int needs = metrics.horizontalAdvance(text) + margin;
      QVERIFY2(needs <= header->sectionSize(c),
               qPrintable(QString("%1 needs %2 px, has %3").arg(text).arg(needs).arg(header->sectionSize(c))));
    }
    QCOMPARE(window.tumour_panel()->table()->horizontalHeaderItem(2)->text(), QString("Material"));
  }

  // A preset in kPa: the breast of 3.25 kPa fat (Samani 2007), written by its modulus;
  // another preset takes its own literature modulus, a typed modulus is written in Pa,
  // switching the tissue to N/m gives the preset's paper stiffness instead, and File > New
  // keeps the unit chosen.
  void presetsInKpaAndTheTissueUnitCanBeSwitched() {
    InstructorWindow window{palpa::author::CaseDraft(palpa::author::preset_defaults_in_kpa(Preset::Breast))};
    show(window);
    auto* panel = window.preset_panel();
    QCOMPARE(panel->tissue_box()->currentData().toString(), QString("kpa"));
    QCOMPARE(panel->stiffness_box()->suffix(), QString(" kPa"));
    QCOMPARE(panel->stiffness_box()->value(), 3.25);
    const auto& breast = window.draft().document()["bodies"][0];
    QCOMPARE(breast["modulus"][0].get<double>(), 3250.0);
    QVERIFY(!breast.contains("stiffness"));
    QCOMPARE(window.tumour_panel()->stiffness_box()->suffix(), QString(" kPa"));

    panel->preset_box()->setCurrentIndex(panel->preset_box()->findData(QString("slab")));
    QCOMPARE(window.draft().document()["bodies"][0]["modulus"][0].get<double>(), 7000.0);
    QCOMPARE(panel->stiffness_box()->value(), 7.0);
    auto* modulus = panel->stiffness_box();
    type_into(modulus, "12.5");
    QCOMPARE(window.draft().document()["bodies"][0]["modulus"][0].get<double>(), 12500.0);
    QCOMPARE(window.draft().preset()->modulus, 12500.0);
    QVERIFY(window.draft().validate().empty());
    // Strain stiffening, typed in: written beside the modulus and kept in the preset.
    auto* stiffening = panel->stiffening_box();
    QVERIFY(stiffening->isVisible());
    QCOMPARE(stiffening->value(), 0.0);
    type_into(stiffening, "3.59");
    QCOMPARE(window.draft().document()["bodies"][0]["stiffening"].get<double>(), 3.59);
    QCOMPARE(window.draft().preset()->stiffening, 3.59);
    QCOMPARE(window.draft().document()["bodies"][0]["modulus"][0].get<double>(), 12500.0);
    QVERIFY(window.draft().validate().empty());

    panel->tissue_box()->setCurrentIndex(panel->tissue_box()->findData(QString("nm")));
    const auto& slab = window.draft().document()["bodies"][0];
    QVERIFY(!slab.contains("modulus"));
    QVERIFY(!slab.contains("stiffening"));
    QVERIFY(!stiffening->isVisible());
    QCOMPARE(slab["stiffness"][0].get<double>(), palpa::author::preset_defaults(Preset::Slab).stiffness);
    QCOMPARE(panel->stiffness_box()->suffix(), QString(" N/m"));
    QCOMPARE(window.tumour_panel()->stiffness_box()->suffix(), QString(" N/m"));
    // Undo goes back to the slab in kPa, and the controls follow.
    window.undo_action()->trigger();
    QCOMPARE(window.draft().document()["bodies"][0]["modulus"][0].get<double>(), 12500.0);
    QCOMPARE(stiffening->value(), 3.59);
    QCOMPARE(panel->tissue_box()->currentData().toString(), QString("kpa"));
    QCOMPARE(panel->stiffness_box()->value(), 12.5);
    // File > New in the unit chosen: a prostate of 21 kPa (Gerling 2009).
    window.new_case(Preset::Prostate);
    QCOMPARE(window.draft().document()["bodies"][0]["modulus"][0].get<double>(), 21000.0);
    // A new window starts in kPa, as the bundled default case is (docs/user-guide.md).
    InstructorWindow fresh{palpa::author::CaseDraft()};
    QCOMPARE(fresh.preset_panel()->tissue_box()->currentData().toString(), QString("kpa"));
    QCOMPARE(fresh.draft().document()["bodies"][0]["modulus"][0].get<double>(), 3250.0);
  }

  // A case whose tissue is given in Pa is edited in kPa: a tumour placed by a click is
  // written by its modulus and stiffening (the panel's invasive carcinoma, 19.44 kPa and
  // 11.07; then fibroadenoma picked with the keyboard; then 35 kPa and a stiffening of 3
  // typed in, which makes the tissue "Custom"), the overlay's legend
  // reads the tissue's 5 kPa, and a grayscale map sets the modulus between the panel's
  // black and white kPa. Nothing of it turns the case into N/m.
  // The bundled default case was not made from a preset: the body controls start from its
  // own tissue (3.24 kPa, stiffening 3.59), not the preset's; and at 1280 x 800 every
  // control of the side panel lies inside it (none cut off at the right).
  void aCaseNotFromAPresetShowsItsOwnTissueAndThePanelFits() {
    InstructorWindow window{palpa::author::CaseDraft()};  // its size on a 1280 x 800 screen
    show(window);
    QVERIFY2(window.open_case(QString::fromStdString(kDefaultCase)), qPrintable(window.message()));
    QTest::qWait(50);
    auto* panel = window.preset_panel();
    QCOMPARE(panel->stiffness_box()->value(), 3.24);
    QCOMPARE(panel->stiffening_box()->value(), 3.59);
    QCOMPARE(panel->width_box()->value(), 140.0);
    auto* scroll = window.findChild<QScrollArea*>("sidePanel");
    QVERIFY(scroll != nullptr);
    const int right = scroll->viewport()->width();
    for (auto* w : scroll->widget()->findChildren<QWidget*>()) {
      if (!w->isVisible() || qobject_cast<QScrollBar*>(w) || !w->parentWidget()->isVisible()) continue;
      const int edge = w->mapTo(scroll->viewport(), QPoint(w->width(), 0)).x();
      QVERIFY2(edge <= right, qPrintable(QString("%1 %2 ends at %3, the panel at %4")
                                             .arg(w->metaObject()->className(), w->objectName())
                                             .arg(edge)
                                             .arg(right)));
    }
  }

  void aCaseInKpaIsEditedInKpa() {
    QTemporaryDir dir;
    auto doc = palpa::author::CaseDraft(palpa::author::preset_defaults(Preset::Slab)).document();
    auto& body = doc["bodies"][0];
    body.erase("stiffness");
    body["modulus"] = std::vector<double>(body["radius"].size(), 5000.0);
    doc.erase("preset");
    const QString path = dir.filePath("slab_kpa.json");
    write_text(path, doc.dump(2));
    InstructorWindow window{palpa::author::CaseDraft()};
    show(window);
    QVERIFY2(window.open_case(path), qPrintable(window.message()));
    auto* material = window.tumour_panel()->stiffness_box();
    QCOMPARE(material->suffix(), QString(" kPa"));
    QCOMPARE(material->value(), 19.44);
    auto* tissue = window.tumour_panel()->material_box();
    auto* stiffening = window.tumour_panel()->stiffening_box();
    show_tab_of(tissue);
    QVERIFY(tissue->isVisible() && stiffening->isVisible());
    QCOMPARE(tissue->currentData().toString(), QString("carcinoma"));
    QCOMPARE(stiffening->value(), 11.07);

    const QPoint at = window.to_view(palpa::Vec3(0.0, 0.0, 0.03));
    QTest::mouseClick(window.view()->input(), Qt::LeftButton, Qt::NoModifier, at);
    QCOMPARE(window.draft().tumour_count(), std::size_t{1});
    const auto& t = window.draft().document()["tumors"][0];
    QCOMPARE(t["modulus"].get<double>(), 19440.0);
    QCOMPARE(t["stiffening"].get<double>(), palpa::mat::find_tissue_material("carcinoma")->stiffening);
    QVERIFY(!t.contains("stiffness"));
    QVERIFY(window.draft().validate().empty());
    QCOMPARE(window.tumour_panel()->table()->item(0, 2)->text(), QString("19.4 kPa, stiffening 11.1"));

    // The tissue box, by keyboard: up one entry from the carcinoma is the fibroadenoma.
    QCOMPARE(window.tumour_panel()->selected(), std::optional<std::size_t>(0));
    tissue->setFocus();
    QTest::keyClick(tissue, Qt::Key_Up);
    QCOMPARE(tissue->currentData().toString(), QString("fibroadenoma"));
    QCOMPARE(window.draft().document()["tumors"][0]["modulus"].get<double>(), 6480.0);
    QVERIFY(!window.draft().document()["tumors"][0].contains("stiffening"));  // none measured
    QCOMPARE(material->value(), 6.48);

    // 35 typed into the selected tumour's modulus box, then a stiffening of 3.
    type_into(material, "35");
    QCOMPARE(window.draft().document()["tumors"][0]["modulus"].get<double>(), 35e3);
    QCOMPARE(tissue->currentData().toString(), QString());  // "Custom"
    type_into(stiffening, "3");
    QCOMPARE(window.draft().document()["tumors"][0]["stiffening"].get<double>(), 3.0);
    QCOMPARE(window.draft().document()["tumors"][0]["modulus"].get<double>(), 35e3);
    QVERIFY(window.draft().validate().empty());
    QCOMPARE(window.draft().document()["bodies"][0]["modulus"][0].get<double>(), 5000.0);

    window.set_stiffness_overlay(true);
    QVERIFY(window.scene().overlay_in_kpa());
    const auto range = window.scene().stiffness_range();
    QVERIFY2(std::abs(range[0] - 5.0) < 0.25 && std::abs(range[1] - 5.0) < 0.25,
             qPrintable(QString("%1 %2").arg(range[0]).arg(range[1])));
    QCOMPARE(window.scene().legend_labels(), std::vector<std::string>{"5 kPa"});  // uniform: its one value

    // A ramp along x (the grid rows) from 4 to 24 kPa: skeleton row i gets 4 + 20 i / 10 kPa.
    const QString png = dir.filePath("ramp.png");
    QVERIFY(ramp_along_x().save(png));
    QDoubleSpinBox* black = nullptr;
    QDoubleSpinBox* white = nullptr;
    for (auto* b : window.preset_panel()->findChildren<QDoubleSpinBox*>()) {
      if (b->toolTip() == "Modulus of black pixels") black = b;
      if (b->toolTip() == "Modulus of white pixels") white = b;
    }
    QVERIFY(black && white);
    QCOMPARE(black->suffix(), QString(" kPa"));
    black->setValue(4.0);
    white->setValue(24.0);
    QVERIFY2(window.import_stiffness_map(png), qPrintable(window.message()));
    QVERIFY(window.message().contains("kPa"));
    const auto& edited = window.draft().document()["bodies"][0];
    QVERIFY(!edited.contains("stiffness"));
    for (int i = 0; i < 11; ++i) {
      const double expected = 4000.0 + 20000.0 * i / 10.0;
      const double got = edited["modulus"][static_cast<std::size_t>(i * 11 + 5)].get<double>();
      QVERIFY2(std::abs(got - expected) < 100.0, qPrintable(QString("row %1: %2 vs %3").arg(i).arg(got).arg(expected)));
    }
    const auto spread = window.scene().stiffness_range();
    QVERIFY2(spread[0] > 3.0 && spread[0] < 5.0 && spread[1] > 23.0 && spread[1] < 25.0,
             qPrintable(QString("%1 %2").arg(spread[0]).arg(spread[1])));
    const auto labels = window.scene().legend_labels();  // a range now: five ticks from low to high
    QCOMPARE(labels.size(), std::size_t{5});
    QCOMPARE(labels.front(), QString::number(spread[0], 'f', 1).toStdString());
    QCOMPARE(labels.back(), QString::number(spread[1], 'f', 1).toStdString());
  }

  // The new breast of 3.25 kPa fat is uniform: the overlay's legend reads exactly that. The
  // map import has one name, in the Case menu and on the Body panel's button.
  void uniformLegendAndOneImportName() {
    InstructorWindow window{palpa::author::CaseDraft(palpa::author::preset_defaults_in_kpa(Preset::Breast))};
    show(window);
    QCOMPARE(window.draft().document()["bodies"][0]["modulus"][0].get<double>(), 3250.0);
    window.set_stiffness_overlay(true);
    QCOMPARE(window.scene().legend_labels(), std::vector<std::string>{"3.25 kPa"});
    QStringList names;
    for (auto* menu : window.menuBar()->findChildren<QMenu*>()) {
      for (auto* action : menu->actions()) {
        if (action->text().contains("map", Qt::CaseInsensitive)) names << action->text().remove('&');
      }
    }
    QCOMPARE(names, QStringList{QString::fromUtf8("Import stiffness map…")});
    QCOMPARE(window.preset_panel()->import_button()->text(), QString::fromUtf8("Import stiffness map…"));
  }

  // A 64 x 32 grayscale ramp, black at the left to white at the right (along x, the grid
  // rows): with black = 100 and white = 500 N/m, skeleton row i of the 11 x 11 slab gets
  // 100 + 400 i / 10 (to the 8-bit quantization).
  void stiffnessImageSetsTheStiffness() {
    QTemporaryDir dir;
    const QString png = dir.filePath("ramp.png");
    QVERIFY(ramp_along_x().save(png));
    InstructorWindow window{palpa::author::CaseDraft(palpa::author::preset_defaults(Preset::Slab))};
    show(window);
    // The map's range: black and white stiffness.
    auto boxes = window.preset_panel()->findChildren<QDoubleSpinBox*>();
    QDoubleSpinBox* black = nullptr;
    QDoubleSpinBox* white = nullptr;
    for (auto* b : boxes) {
      if (b->toolTip() == "Stiffness of black pixels") black = b;
      if (b->toolTip() == "Stiffness of white pixels") white = b;
    }
    QVERIFY(black && white);
    black->setValue(100.0);
    white->setValue(500.0);
    QVERIFY2(window.import_stiffness_map(png), qPrintable(window.message()));
    const auto k = window.draft().document()["bodies"][0]["stiffness"];
    for (int i = 0; i < 11; ++i) {
      for (int j = 0; j < 11; ++j) {
        const double expected = 100.0 + 400.0 * i / 10.0;
        const double got = k[static_cast<std::size_t>(i * 11 + j)].get<double>();
        QVERIFY2(std::abs(got - expected) < 2.0, qPrintable(QString("%1,%2: %3 vs %4").arg(i).arg(j).arg(got).arg(expected)));
      }
    }
    // The overlay is on and spans the new range; the top surface carries the stiffness.
    QVERIFY(window.scene().stiffness_overlay());
    const auto range = window.scene().stiffness_range();
    QVERIFY2(std::abs(range[0] - 100.0) < 3.0 && std::abs(range[1] - 500.0) < 3.0,
             qPrintable(QString("%1 %2").arg(range[0]).arg(range[1])));
    QVERIFY(window.scene().top(0)->GetPointData()->GetScalars() != nullptr);

    // A ramp along y, black at the image's bottom row to white at its top (seen from above,
    // y grows up the image): skeleton column j gets 100 + 400 j / 10, whatever the row.
    QImage up(32, 64, QImage::Format_Grayscale8);
    for (int y = 0; y < up.height(); ++y) {
      const int v = static_cast<int>(std::lround((up.height() - 1 - y) * 255.0 / (up.height() - 1)));
      for (int x = 0; x < up.width(); ++x) up.setPixelColor(x, y, QColor(v, v, v));
    }
    const QString up_png = dir.filePath("up.png");
    QVERIFY(up.save(up_png));
    QVERIFY2(window.import_stiffness_map(up_png), qPrintable(window.message()));
    const auto kv = window.draft().document()["bodies"][0]["stiffness"];
    for (int i = 0; i < 11; ++i) {
      for (int j = 0; j < 11; ++j) {
        const double expected = 100.0 + 400.0 * j / 10.0;
        const double got = kv[static_cast<std::size_t>(i * 11 + j)].get<double>();
        QVERIFY2(std::abs(got - expected) < 2.0, qPrintable(QString("%1,%2: %3 vs %4").arg(i).arg(j).arg(got).arg(expected)));
      }
    }
    QVERIFY(window.undo_action()->isEnabled());
    window.undo_action()->trigger();  // back to the x ramp for what follows

    // An unreadable image: a clear message, the case unchanged.
    const auto doc = window.draft().document();
    const QString fake = dir.filePath("fake.png");
    write_text(fake, "not an image");
    QVERIFY(!window.import_stiffness_map(fake));
    QVERIFY2(window.message().startsWith(fake + ": "), qPrintable(window.message()));
    QCOMPARE(window.draft().document(), doc);
    QVERIFY(!window.import_stiffness_map(dir.filePath("missing.png")));
  }

  void tryItOpensTheCaseInATraineeWindow() {
    QTemporaryDir dir;
    InstructorWindow window{palpa::author::CaseDraft(palpa::author::preset_defaults(Preset::Slab))};
    window.set_sessions_dir(dir.filePath("sessions").toStdString());
    show(window);
    QVERIFY(window.click_at(window.to_view(palpa::Vec3(0.01, 0.0, 0.03))));
    auto* trainee = window.try_it();
    QVERIFY2(trainee != nullptr, qPrintable(window.message()));
    QVERIFY(QTest::qWaitForWindowExposed(trainee));
    QVERIFY(trainee->exercise().started());
    QCOMPARE(trainee->exercise().placed_case().tumours.size(), std::size_t{1});
    QCOMPARE(trainee->exercise().placed_case().tumours[0].center, window.draft().tumour(0)->center);
    QVERIFY(std::filesystem::exists(trainee->exercise().session_path()));
    QCOMPARE(QString::fromStdString(trainee->exercise().session_path().parent_path().string()), dir.filePath("sessions"));
    trainee->setProperty(palpa::ui::TraineeWindow::kCloseWithoutAsking, true);  // no question to answer
    trainee->close();  // finishes the session; the window deletes itself
    QTRY_VERIFY(window.try_window() == nullptr);
  }

  // The window fits a 1280 x 800 screen under a title bar and a panel (it was resized to
  // exactly 1280 x 800, no room for either); the Tumours tab (clicked) shows all its
  // controls, Remove tumour too, without scrolling the side panel.
  void fitsTheScreen() {
    InstructorWindow window{palpa::author::CaseDraft()};
    show(window);
    auto* side = window.findChild<QScrollArea*>("sidePanel");
    palpa::ui::testing::check_fits_screen(window, {side, window.problems()});
    show_tab_of(window.tumour_panel());
    QTest::qWait(20);
    auto* remove = window.tumour_panel()->remove_button();
    const QRect shown(remove->mapTo(side->viewport(), QPoint(0, 0)), remove->size());
    QVERIFY2(!side->verticalScrollBar()->isVisible() && side->viewport()->rect().contains(shown),
             qPrintable(QString("Remove tumour ends at y %1, the panel is %2 high").arg(shown.bottom()).arg(side->viewport()->height())));
  }

  // Ctrl+W closes the window with no window manager (no active window, so no shortcut
  // fires), sent to the window and to its view.
  void ctrlWClosesTheWindow() {
    for (const bool to_view : {false, true}) {
      InstructorWindow window{palpa::author::CaseDraft()};
      show(window);
      QVERIFY(!window.isActiveWindow());
      if (to_view) {
        QTest::keyClick(window.view()->input(), Qt::Key_W, Qt::ControlModifier);
      } else {
        QTest::keyClick(&window, Qt::Key_W, Qt::ControlModifier);
      }
      QTRY_VERIFY(!window.isVisible());
    }
  }

  // "Try it" (its toolbar button clicked) opens a trainee window that takes the keys at
  // once, without a click, also with no window manager: Up, sent where the display sends
  // keys (the focus window), makes the pressure deeper there.
  void tryItTakesTheKeysAtOnce() {
    QTemporaryDir dir;
    InstructorWindow window{palpa::author::CaseDraft(palpa::author::preset_defaults(Preset::Slab))};
    window.set_sessions_dir(dir.filePath("sessions").toStdString());
    show(window);
    auto* bar = window.findChild<QToolBar*>("instructorToolbar");
    QAction* try_action = nullptr;
    for (auto* a : bar->actions()) try_action = a->text().remove('&') == "Try it" ? a : try_action;
    QVERIFY(try_action);
    QTest::mouseClick(bar->widgetForAction(try_action), Qt::LeftButton);
    auto* trainee = window.try_window();
    QVERIFY2(trainee, qPrintable(window.message()));
    QTRY_VERIFY(trainee->isActiveWindow());
    QTRY_COMPARE(QGuiApplication::focusWindow(), trainee->windowHandle());
    const int step = trainee->pressure().step_in_level();
    QTest::keyClick(QGuiApplication::focusWindow(), Qt::Key_Up);
    QCOMPARE(trainee->pressure().step_in_level(), step + 1);
    // Ctrl+W closes it the same way (the press alone: the window it closed is gone when the
    // key comes up).
    trainee->setProperty(palpa::ui::TraineeWindow::kCloseWithoutAsking, true);
    QTest::keyPress(QGuiApplication::focusWindow(), Qt::Key_W, Qt::ControlModifier);
    QTRY_VERIFY(window.try_window() == nullptr);
  }

  // A body whose support faces +y (the imported VICTRE breast) is seen from its free side,
  // down its press axis, not from behind the chest wall; so is the bundled breast (+z).
  void aBodyOnASupportIsSeenFromItsFreeSide() {
    for (const char* name : {"victre-breast.json", "default.json"}) {
      InstructorWindow window{palpa::author::CaseDraft()};
      show(window);
      QVERIFY2(window.open_case(QString(PALPA_SOURCE_DIR "/data/cases/") + name), qPrintable(window.message()));
      const auto file = palpa::io::load_case(std::string(PALPA_SOURCE_DIR "/data/cases/") + name);
      const palpa::Vec3 up = palpa::scene::Scene::build(file, name).body(0).press_axis.up;
      double d[3];
      window.renderer()->GetActiveCamera()->GetDirectionOfProjection(d);
      const double along = palpa::Vec3(d[0], d[1], d[2]).dot(up);
      qInfo("%s: view direction . press axis = %.3f", name, along);
      QVERIFY2(along < -0.95, qPrintable(QString::number(along)));
      QTest::qWait(100);
      const QImage frame = window.view()->frame();
      QVERIFY2(skin_pixels(frame) > frame.width() * frame.height() / 10, qPrintable(QString::number(skin_pixels(frame))));
    }
  }

  // A title typed without leaving the field is what Ctrl+S saves; typed and then undone,
  // the typed title is the step undone and the field shows the title before it.
  void typedButUncommittedTitleIsSavedAndUndone() {
    QTemporaryDir dir;
    InstructorWindow window{palpa::author::CaseDraft(palpa::author::preset_defaults(Preset::Slab))};
    show(window);
    const QString path = dir.filePath("typed.json");
    QVERIFY2(window.save_as(path), qPrintable(window.message()));
    QApplication::setActiveWindow(&window);
    auto* title = window.title_edit();
    title->setFocus();
    QVERIFY(title->hasFocus());
    title->selectAll();
    QTest::keyClicks(title, "Typed title");
    QCOMPARE(window.draft().title(), std::string("New slab case"));  // not committed yet
    QTest::keyClick(title, Qt::Key_S, Qt::ControlModifier);
    QCOMPARE(palpa::author::CaseDraft::load(path.toStdString()).title(), std::string("Typed title"));
    QVERIFY(!window.draft().dirty());
    QVERIFY(title->hasFocus());  // the field keeps the focus

    title->selectAll();
    QTest::keyClicks(title, "Second title");
    window.undo_action()->trigger();
    QCOMPARE(window.draft().title(), std::string("Typed title"));
    QCOMPARE(title->text(), QString("Typed title"));
    window.undo_action()->trigger();
    QCOMPARE(window.draft().title(), std::string("New slab case"));
    QCOMPARE(title->text(), QString("New slab case"));
    // New drops a typed title with the old case, not onto the new one.
    title->selectAll();
    QTest::keyClicks(title, "Left behind");
    window.new_case(Preset::Prostate);
    QCOMPARE(title->text(), QString("New prostate case"));
    title->clearFocus();
    QCOMPARE(window.draft().title(), std::string("New prostate case"));
    QVERIFY(!window.draft().can_undo());
  }

  // Destroyed (not closed) while a title is being typed: the field's focus-out on the way
  // out must not edit the half-destroyed window.
  void destroyedWhileTypingIsSafe() {
    auto window = std::make_unique<InstructorWindow>(palpa::author::CaseDraft());
    show(*window);
    QApplication::setActiveWindow(window.get());
    window->title_edit()->setFocus();
    QVERIFY(window->title_edit()->hasFocus());
    QTest::keyClicks(window->title_edit(), " edited");
    window.reset();
  }

  // Save As to a name without ".json" next to NAME.json: asked before replacing it.
  void saveAsAsksBeforeReplacingTheJsonFile() {
    QTemporaryDir dir;
    const QString existing = dir.filePath("existing.json");
    write_text(existing, "precious");
    InstructorWindow window{palpa::author::CaseDraft(palpa::author::preset_defaults(Preset::Slab))};
    show(window);
    window.set_save_path_chooser([&] { return dir.filePath("existing"); });
    QString asked;
    auto* timer = answer_next_box(QMessageBox::No, &asked);
    QVERIFY(!window.save_as_dialog());
    delete timer;
    QVERIFY2(asked.contains("existing.json"), qPrintable(asked));
    QCOMPARE(read_text(existing), std::string("precious"));
    QVERIFY(window.draft().path().empty());

    asked.clear();
    timer = answer_next_box(QMessageBox::Yes, &asked);
    QVERIFY2(window.save_as_dialog(), qPrintable(window.message()));
    delete timer;
    QVERIFY(!asked.isEmpty());
    QCOMPARE(QString::fromStdString(window.draft().path().string()), existing);
    QCOMPARE(palpa::io::load_case(existing.toStdString()).tumours.size(), std::size_t{0});

    // A name that is free: no question.
    window.set_save_path_chooser([&] { return dir.filePath("fresh"); });
    asked.clear();
    timer = answer_next_box(QMessageBox::No, &asked);
    QVERIFY(window.save_as_dialog());
    delete timer;
    QVERIFY(asked.isEmpty());
    QVERIFY(QFile::exists(dir.filePath("fresh.json")));
  }

  // Ctrl+Z and Ctrl+Shift+Z undo and redo the case while a side-panel box or the title has
  // the focus (those editors claim the keys for their own text otherwise).
  void undoKeysReachTheCaseFromSidePanelEditors() {
    InstructorWindow window{palpa::author::CaseDraft(palpa::author::preset_defaults(Preset::Slab))};
    show(window);
    QVERIFY(window.click_at(window.to_view(palpa::Vec3(0.0, 0.0, 0.03))));
    QApplication::setActiveWindow(&window);
    auto* depth = window.tumour_panel()->depth_box();
    depth->setFocus();
    QVERIFY(depth->hasFocus());
    QTest::keyClick(depth, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(window.draft().tumour_count(), std::size_t{0});
    QTest::keyClick(depth, Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
    QCOMPARE(window.draft().tumour_count(), std::size_t{1});
    window.title_edit()->setFocus();
    QTest::keyClick(window.title_edit(), Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(window.draft().tumour_count(), std::size_t{0});
  }

  // The wheel over a box without focus scrolls the panel and leaves its value alone.
  void wheelChangesOnlyAFocusedBox() {
    InstructorWindow window{palpa::author::CaseDraft(palpa::author::preset_defaults(Preset::Slab))};
    show(window);
    QApplication::setActiveWindow(&window);
    auto* width = window.preset_panel()->width_box();
    window.title_edit()->setFocus();
    const double before = width->value();
    wheel(width, 1);
    QCOMPARE(width->value(), before);
    QVERIFY(!window.draft().dirty());
    width->setFocus();
    QVERIFY(width->hasFocus());
    wheel(width, 1);
    QCOMPARE(width->value(), before + width->singleStep());
    QVERIFY(window.draft().dirty());
  }

  // A tumour written elsewhere (12.34 mm deep, radius 0.3 mm): changing only its stiffness
  // leaves its centre and radius bit-identical; changing its radius leaves the centre.
  void tumourEditChangesOnlyTheEditedField() {
    auto doc = palpa::author::CaseDraft(palpa::author::preset_defaults(Preset::Slab)).document();
    const std::array<double, 3> centre{0.0123, -0.0071, 0.03 - 0.01234};
    doc["tumors"] = nlohmann::json::array(
        {{{"body", "slab"}, {"center", centre}, {"radius", 0.0003}, {"stiffness", 2000.0}}});
    InstructorWindow window{palpa::author::CaseDraft::from_document(doc, "written elsewhere")};
    show(window);
    window.tumour_panel()->select(0);
    QCOMPARE(window.tumour_panel()->selected(), std::optional<std::size_t>(0));
    QVERIFY2(std::abs(window.tumour_panel()->depth_box()->value() - 12.34) < 0.011,
             qPrintable(QString::number(window.tumour_panel()->depth_box()->value())));
    window.tumour_panel()->stiffness_box()->setValue(2500.0);
    auto t = *window.draft().tumour(0);
    QCOMPARE(t.stiffness, 2500.0);
    QVERIFY(t.center == centre);
    QVERIFY(t.radius == 0.0003);
    window.tumour_panel()->radius_box()->setValue(4.0);
    t = *window.draft().tumour(0);
    QVERIFY(t.center == centre);
    QCOMPARE(t.radius, 0.004);
    QCOMPARE(t.stiffness, 2500.0);
  }

  // "Try it" palpates with the device its owner hands over; one that cannot be opened
  // says why in one line and opens no trainee window.
  void tryItUsesTheOwnersDevice() {
    QTemporaryDir dir;
    const QString sessions = dir.filePath("sessions");
    InstructorWindow window{palpa::author::CaseDraft(palpa::author::preset_defaults(Preset::Slab))};
    window.set_sessions_dir(sessions.toStdString());
    show(window);
    QVERIFY(window.click_at(window.to_view(palpa::Vec3(0.01, 0.0, 0.03))));
    int opened = 0;
    window.set_device_opener([&opened] {
      ++opened;
      return std::make_shared<FakeProbe>();
    });
    auto* trainee = window.try_it();
    QVERIFY2(trainee != nullptr, qPrintable(window.message()));
    QCOMPARE(opened, 1);
    QCOMPARE(trainee->exercise().device_name(), std::string("Fake probe"));
    trainee->setProperty(palpa::ui::TraineeWindow::kCloseWithoutAsking, true);
    trainee->close();
    QTRY_VERIFY(window.try_window() == nullptr);

    const std::size_t files = files_in(sessions);
    window.set_device_opener([]() -> std::shared_ptr<palpa::engine::Device> {
      throw std::runtime_error("Fake probe: not attached\n(details)");
    });
    QVERIFY(window.try_it() == nullptr);
    QCOMPARE(window.message(), QString("Fake probe: not attached"));
    QVERIFY(window.try_window() == nullptr);
    QCOMPARE(files_in(sessions), files);  // no session started
  }

  // Closing the instructor window closes its Try-it windows, whose sessions then end.
  void closingFinishesTheTryItSessions() {
    QTemporaryDir dir;
    auto window = std::make_unique<InstructorWindow>(palpa::author::CaseDraft(palpa::author::preset_defaults(Preset::Slab)));
    window->set_sessions_dir(dir.filePath("sessions").toStdString());
    show(*window);
    QVERIFY(window->click_at(window->to_view(palpa::Vec3(0.0, 0.0, 0.03))));
    QVERIFY(window->save_as(dir.filePath("tried.json")));  // clean: closing asks nothing
    auto* trainee = window->try_it();
    QVERIFY2(trainee != nullptr, qPrintable(window->message()));
    const auto session_path = trainee->exercise().session_path();
    QVERIFY(window->close());
    const auto session = palpa::session::read_session(session_path, {false});
    QVERIFY(session.complete);
    QVERIFY(!session.events.empty());
    QCOMPARE(session.events.back().kind, palpa::session::EventKind::End);
    QTRY_VERIFY(window->try_window() == nullptr);
    window.reset();
  }

  void screenshotShowsTheBody() {
    QTemporaryDir dir;
    const QString png = dir.filePath("instructor.png");
    const Run r = run_palpa({"--mode", "instructor", "--screenshot", png});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QImage image(png);
    QVERIFY(!image.isNull());
    QCOMPARE(image.size(), QSize(1272, 696));  // a 1280 x 800 screen less a title bar and a panel
    const int skin = skin_pixels(image);
    QVERIFY2(skin > image.width() * image.height() / 10, qPrintable(QString::number(skin)));

    const Run edit = run_palpa({"--mode", "instructor", "--case", QString::fromStdString(kDefaultCase), "--screenshot",
                                dir.filePath("default.png")});
    QVERIFY2(edit.code == 0, qPrintable(edit.err));
    QVERIFY(skin_pixels(QImage(dir.filePath("default.png"))) > image.width() * image.height() / 10);

    const QString broken = dir.filePath("broken.json");
    write_text(broken, "{ \"format\": ");
    const Run bad = run_palpa({"--mode", "instructor", "--case", broken});
    QCOMPARE(bad.code, 2);
    QCOMPARE(bad.err.trimmed().split('\n').size(), 1);
    QVERIFY2(bad.err.startsWith(broken + ": line "), qPrintable(bad.err));
    const Run session = run_palpa({"--mode", "instructor", "--session", dir.filePath("x.palpa")});
    QCOMPARE(session.code, 2);
  }
};

QObject* make_import_anatomy_test();  // tests/ui/import_anatomy_test.cpp

// Whether a test function named on the command line is one of `test`'s: QTest refuses a
// name its class lacks, so a class runs when it has a named function or none is named.
static bool names_one_of(const QObject& test, int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    const QByteArray name = QByteArray(argv[k]).split(':').front();
    if (test.metaObject()->indexOfMethod(name + "()") >= 0) return true;
  }
  return false;
}

int main(int argc, char** argv) {
  // VTK's OpenGL wants its surface format on every Qt GL surface: before QApplication.
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  InstructorWindowTest test;
  const std::unique_ptr<QObject> import_test(make_import_anatomy_test());
  const bool here = names_one_of(test, argc, argv), there = names_one_of(*import_test, argc, argv);
  int failed = here || !there ? QTest::qExec(&test, argc, argv) : 0;
  if (there || !here) failed += QTest::qExec(import_test.get(), argc, argv);
  return failed;
}

#include "instructor_window_test.moc"
