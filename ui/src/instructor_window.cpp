#include "palpa/ui/instructor_window.hpp"

#include <algorithm>
#include <cmath>

#include <QAbstractSpinBox>
#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QComboBox>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QKeyEvent>
#include <QKeySequence>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QMenuBar>
#include <QMouseEvent>
#include <QScrollArea>
#include <QStatusBar>
#include <QTabWidget>
#include <QToolBar>
#include <QVBoxLayout>
#include <QWindow>
#include <vtkCamera.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

#include "palpa/author/palpability.hpp"
#include "palpa/ui/instructor_exam_panel.hpp"
#include "palpa/ui/instructor_preset_panel.hpp"
#include "palpa/ui/instructor_scene.hpp"
#include "palpa/ui/instructor_tumour_panel.hpp"
#include "palpa/ui/trainee_window.hpp"
#include "palpa/ui/body_view.hpp"
#include "palpa/ui/vtk_view.hpp"
#include "palpa/ui/window_frame.hpp"

namespace palpa::ui {
namespace {

constexpr int kClickSlop = 4;  // px: a press and release closer than this is a click, not a drag

}  // namespace

InstructorWindow::InstructorWindow(author::CaseDraft draft, QWidget* parent)
    : QMainWindow(parent), draft_(std::move(draft)) {
  // A 1280 x 800 screen under a title bar and a desktop panel (smaller screens: less).
  fit_to_screen(*this, {1272, 696});
  auto* central = new QWidget(this);
  auto* layout = new QHBoxLayout(central);
  view_ = new VtkView(central);
  // Clicks on the body place tumours; drags still turn the view (the filter passes them on).
  view_->input()->installEventFilter(this);
  // The problems under the view, always in sight.
  auto* left = new QVBoxLayout;
  left->addWidget(view_, 1);
  auto* problems_box = new QGroupBox(tr("Problems"), central);
  auto* problems_layout = new QVBoxLayout(problems_box);
  problems_ = new QListWidget(problems_box);
  problems_->setWordWrap(true);
  problems_layout->addWidget(problems_);
  problems_box->setFixedHeight(130);
  left->addWidget(problems_box);
  layout->addLayout(left, 1);

  layout->addWidget(build_side(central));
  setCentralWidget(central);

  build_view();
  build_actions();
  guard_editors();
  connect_panels();
  refresh();
  frame_camera();
  close_on_ctrl_w(*this, view_->input());
}

QWidget* InstructorWindow::build_side(QWidget* parent) {
  auto* side = new QWidget;
  auto* side_layout = new QVBoxLayout(side);
  auto* title_row = new QHBoxLayout;
  title_row->addWidget(new QLabel(tr("Title"), side));
  title_ = new QLineEdit(side);
  title_->setObjectName("caseTitle");
  title_row->addWidget(title_);
  side_layout->addLayout(title_row);
  // Tabs, so that each part fits the panel at 1280 x 800 without scrolling it.
  tabs_ = new QTabWidget(side);
  tabs_->setObjectName("sideTabs");
  auto* body_page = new QWidget(tabs_);
  auto* body_layout = new QVBoxLayout(body_page);
  preset_panel_ = new InstructorPresetPanel(body_page);
  body_layout->addWidget(preset_panel_);
  body_layout->addStretch(1);
  tabs_->addTab(body_page, tr("Body"));
  tumour_panel_ = new InstructorTumourPanel(tabs_);
  tabs_->addTab(tumour_panel_, tr("Tumours"));
  exam_panel_ = new InstructorExamPanel(tabs_);
  tabs_->addTab(exam_panel_, tr("Exam"));
  side_layout->addWidget(tabs_, 1);
  auto* scroll = new QScrollArea(parent);
  scroll->setObjectName("sidePanel");
  scroll->setWidget(side);
  scroll->setWidgetResizable(true);
  scroll->setFixedWidth(400);
  scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  return scroll;
}

void InstructorWindow::connect_panels() {
  connect(title_, &QLineEdit::editingFinished, this, [this] {
    title_->setModified(false);  // committed: refresh() shows the draft's title again
    const std::string text = title_->text().toStdString();
    if (text != draft_.title()) edit([this, text] { draft_.set_title(text); });
  });
  connect(preset_panel_, &InstructorPresetPanel::params_changed, this,
          [this](const author::PresetParams& p) { edit([this, p] { draft_.apply_preset(p); }); });
  connect(preset_panel_, &InstructorPresetPanel::import_requested, this, &InstructorWindow::import_dialog);
  connect(tumour_panel_, &InstructorTumourPanel::selection_changed, this, [this](std::optional<std::size_t>) { refresh(); });
  connect(tumour_panel_, &InstructorTumourPanel::spec_changed, this,
          [this](std::size_t k, const author::TumourSpec& s) { edit([this, k, s] { draft_.edit_tumour(k, s); }); });
  connect(tumour_panel_, &InstructorTumourPanel::placement_changed, this,
          [this](std::size_t k, const std::optional<scripted::Placement>& rule) {
            edit([this, k, rule] { draft_.set_placement(k, rule); });
          });
  connect(tumour_panel_, &InstructorTumourPanel::remove_requested, this, [this](std::size_t k) {
    edit([this, k] { draft_.remove_tumour(k); });
  });
  // A problem in the list selects what it is about.
  connect(problems_, &QListWidget::currentRowChanged, this, [this](int row) {
    if (row < 0) return;
    const QString where = problems_->item(row)->data(Qt::UserRole).toString();
    if (where.startsWith("/tumors/")) {
      bool ok = false;
      const int k = where.section('/', 2, 2).toInt(&ok);
      if (ok) {
        tumour_panel_->select(static_cast<std::size_t>(k));
        tabs_->setCurrentWidget(tumour_panel_);
      }
    } else if (where.startsWith("/title")) {
      title_->setFocus();
    } else if (where.startsWith("/scoring") || where.startsWith("/exam_region") || where.startsWith("/description")) {
      tabs_->setCurrentWidget(exam_panel_);
    } else if (where.startsWith("/bodies") || where.startsWith("/preset")) {
      tabs_->setCurrentIndex(0);
    }
  });
  connect(exam_panel_, &InstructorExamPanel::description_changed, this, [this](const QString& text) {
    const std::string d = text.toStdString();
    if (d != draft_.description()) edit([this, d] { draft_.set_description(d); });
  });
  connect(exam_panel_, &InstructorExamPanel::scoring_changed, this, [this](const std::string& key, double value) {
    edit([this, key, value] { draft_.set_scoring(key, value); });
  });
  connect(exam_panel_, &InstructorExamPanel::region_changed, this,
          [this](const std::optional<author::ExamExtent>& extent) { edit([this, extent] { draft_.set_exam_region(extent); }); });
}

InstructorWindow::~InstructorWindow() {
  // QWidget's destructor takes the focus from a child editor, which then commits
  // (editingFinished) into this half-destroyed window: no more of those.
  for (auto* child : findChildren<QObject*>()) child->disconnect(this);
  // Closed first, so that their sessions finish (a close accepted by closeEvent did it).
  for (auto& w : try_windows_) {
    if (!w) continue;
    w->setProperty(TraineeWindow::kCloseWithoutAsking, true);  // the instructor closed the case
    w->close();
    delete w.data();
  }
}

void InstructorWindow::guard_editors() {
  for (auto* w : findChildren<QWidget*>()) {
    const bool choice = qobject_cast<QAbstractSpinBox*>(w) || qobject_cast<QComboBox*>(w);
    if (choice) w->setFocusPolicy(Qt::StrongFocus);  // not WheelFocus: the wheel scrolls the panel
    if (choice || qobject_cast<QLineEdit*>(w)) w->installEventFilter(this);
  }
}

bool InstructorWindow::filter_editor_event(QWidget* editor, QEvent* event) {
  if (event->type() == QEvent::ShortcutOverride) {
    // A line edit or spin box claims Ctrl+Z for its own text: let the case's undo win.
    auto* key = static_cast<QKeyEvent*>(event);
    const int mods = static_cast<int>(key->modifiers() & (Qt::ShiftModifier | Qt::ControlModifier |
                                                          Qt::AltModifier | Qt::MetaModifier));
    const QKeySequence pressed(key->key() | mods);
    if (undo_->shortcuts().contains(pressed) || redo_->shortcuts().contains(pressed)) {
      event->ignore();
      return true;
    }
  } else if (event->type() == QEvent::Wheel && !editor->hasFocus() &&
             (qobject_cast<QAbstractSpinBox*>(editor) || qobject_cast<QComboBox*>(editor))) {
    event->ignore();  // on to the scroll area
    return true;
  }
  return false;
}

void InstructorWindow::commit_pending() {
  exam_panel_->commit_description();  // also when focus events do not come (an inactive window)
  QWidget* focus = QApplication::focusWidget();
  if (!focus || !isAncestorOf(focus)) return;
  // Leaving the editor commits it (keyboard tracking is off); focus comes back after.
  const QPointer<QWidget> keep(focus);
  focus->clearFocus();
  if (keep && keep->isVisible()) keep->setFocus(Qt::OtherFocusReason);
}

void InstructorWindow::build_view() {
  render_window_ = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  render_window_->SetNumberOfLayers(2);
  renderer_ = add_body_renderer(*view_, render_window_);
  // Tumours in a layer over the bodies, with the same camera: seen through the skin.
  overlay_renderer_ = vtkSmartPointer<vtkRenderer>::New();
  overlay_renderer_->SetLayer(1);
  overlay_renderer_->InteractiveOff();
  overlay_renderer_->SetActiveCamera(renderer_->GetActiveCamera());
  render_window_->AddRenderer(overlay_renderer_);
  scene_ = std::make_unique<InstructorScene>(renderer_, overlay_renderer_);
}

void InstructorWindow::build_actions() {
  // "Case": the application's own File menu (ui::ModeMenu, added by app/gui) opens other
  // windows; this one edits the case in this window.
  auto* file = menuBar()->addMenu(tr("&Case"));
  auto* new_menu = file->addMenu(tr("&New"));
  for (auto p : {author::Preset::Breast, author::Preset::Prostate, author::Preset::Patch, author::Preset::Slab}) {
    new_menu->addAction(tr(author::label(p)), this, [this, p] {
      if (confirm_discard()) new_case(p);
    });
  }
  auto* open = file->addAction(tr("&Open..."), this, &InstructorWindow::open_dialog);
  open->setShortcut(QKeySequence::Open);
  auto* save_action = file->addAction(tr("&Save"), this, [this] {
    if (draft_.path().empty()) {
      save_as_dialog();
    } else {
      save();
    }
  });
  save_action->setShortcut(QKeySequence::Save);
  auto* save_as_action = file->addAction(tr("Save &As..."), this, &InstructorWindow::save_as_dialog);
  save_as_action->setShortcut(QKeySequence::SaveAs);
  file->addSeparator();

  auto* edit_menu = menuBar()->addMenu(tr("&Edit"));
  undo_ = edit_menu->addAction(tr("&Undo"), this, &InstructorWindow::undo);
  undo_->setShortcut(QKeySequence(QStringLiteral("Ctrl+Z")));
  redo_ = edit_menu->addAction(tr("&Redo"), this, &InstructorWindow::redo);
  redo_->setShortcut(QKeySequence(QStringLiteral("Ctrl+Shift+Z")));

  auto* view_menu = menuBar()->addMenu(tr("&View"));
  overlay_ = view_menu->addAction(tr("Stiffness &overlay"));
  overlay_->setCheckable(true);
  connect(overlay_, &QAction::toggled, this, &InstructorWindow::set_stiffness_overlay);

  file->addAction(tr("Import stiffness &map…"), this, &InstructorWindow::import_dialog);
  file->addAction(tr("Import anatom&y…"), this, &InstructorWindow::import_anatomy_dialog);
  auto* try_action = file->addAction(tr("&Try it"), this, [this] { (void)try_it(); });
  try_action->setShortcut(QKeySequence(QStringLiteral("F5")));  // Ctrl+T is the File menu's "Train on a case"

  auto* bar = addToolBar(tr("Edit"));
  bar->setObjectName("instructorToolbar");
  bar->addAction(undo_);
  bar->addAction(redo_);
  bar->addSeparator();
  bar->addAction(overlay_);
  bar->addAction(try_action);
}

void InstructorWindow::edit(const std::function<void()>& op) {
  try {
    op();
  } catch (const io::CaseError& e) {
    set_message(QString::fromStdString(e.what()));
  } catch (const std::exception& e) {
    set_message(QString::fromStdString(e.what()));
  }
  refresh();
}

void InstructorWindow::refresh() {
  update_title();
  // A title being typed (not committed yet) stays; otherwise the field shows the draft's.
  const QString title = QString::fromStdString(draft_.title());
  if (!title_->isModified() && title_->text() != title) title_->setText(title);
  preset_panel_->show_params(draft_.preset_or_nearest(), draft_.preset().has_value());
  preset_panel_->set_map_in_kpa(draft_.tissue_in_pa());
  tumour_panel_->show_draft(draft_);
  exam_panel_->show_draft(draft_);

  // The bodies are drawn from the document without its tumours, so that a tumour's
  // problem does not hide the body it is in.
  const auto& doc = draft_.document();
  const nlohmann::json bodies = doc.is_object() && doc.contains("bodies") ? doc["bodies"] : nlohmann::json();
  if (bodies != drawn_bodies_) {
    nlohmann::json bodies_only = doc;
    if (bodies_only.is_object()) bodies_only.erase("tumors");
    // Another kind of body (new ids: breast -> prostate) is framed anew; a size change
    // keeps the camera, so the change shows.
    const auto ids = [](const nlohmann::json& list) {
      std::vector<nlohmann::json> out;
      if (list.is_array()) {
        for (const auto& b : list) out.push_back(b.is_object() && b.contains("id") ? b["id"] : nlohmann::json());
      }
      return out;
    };
    try {
      const bool reframe = !scene_->has_bodies() || ids(bodies) != ids(drawn_bodies_);
      scene_->set_bodies(io::parse_case(bodies_only.dump(), draft_.source()));
      drawn_bodies_ = bodies;
      if (reframe) frame_camera();
    } catch (const std::exception&) {
      // Not drawable: the problems list says why; the last good bodies stay drawn.
    }
  }
  std::vector<mat::Tumour> tumours;
  for (std::size_t k = 0; k < draft_.tumour_count(); ++k) {
    if (auto t = draft_.tumour(k)) tumours.push_back(*t);
  }
  scene_->set_tumours(tumours, tumour_panel_->selected());
  const auto problems = draft_.validate();
  std::vector<author::AuthorProblem> warnings;
  if (problems.empty()) {
    try {
      warnings = author::palpability_warnings(author::check_palpability(draft_.valid_case(), draft_.source()));
    } catch (const std::exception&) {
      // Valid a moment ago: nothing to warn about that validate() would not say.
    }
  }
  show_problems(problems, warnings);
  undo_->setEnabled(draft_.can_undo());
  redo_->setEnabled(draft_.can_redo());
  render();
}

void InstructorWindow::show_problems(const std::vector<io::Problem>& problems,
                                     const std::vector<author::AuthorProblem>& warnings) {
  problems_->clear();
  tumour_panel_->clear_problems();
  exam_panel_->clear_problems();
  preset_panel_->set_problem(QString());
  title_->setStyleSheet(QString());
  title_->setToolTip(QString());
  for (const auto& p : author::describe(problems)) show_problem(p);
  if (problems.empty()) {
    const QString valid = warnings.empty() ? tr("No problems: the case is valid.")
                                           : tr("No problems: the case is valid (%n warning(s) below).", "",
                                                static_cast<int>(warnings.size()));
    auto* item = new QListWidgetItem(valid, problems_);
    item->setForeground(QColor(20, 120, 40));
  }
  for (const auto& w : warnings) show_problem(w);
}

void InstructorWindow::show_problem(const author::AuthorProblem& p) {
  using author::ProblemField;
  const QString text = QString::fromStdString(p.text);
  auto* item = new QListWidgetItem(text, problems_);
  item->setData(Qt::UserRole, QString::fromStdString(p.where));
  item->setData(kWarningRole, p.warning);
  item->setForeground(p.warning ? QColor(150, 90, 0) : QColor(170, 20, 20));
  if (p.warning) {
    if (p.tumour) tumour_panel_->add_warning(*p.tumour, text);
    return;
  }
  if (p.tumour) {
    tumour_panel_->add_problem(*p.tumour, p.field, text);
  } else if (p.field == ProblemField::Body) {
    preset_panel_->set_problem(text);
  } else if (p.field == ProblemField::Scoring) {
    exam_panel_->add_scoring_problem(p.key, text);
  } else if (p.field == ProblemField::ExamRegion) {
    exam_panel_->add_region_problem(text);
  } else if (p.field == ProblemField::Title) {
    title_->setStyleSheet("background: #ffc8c8;");
    title_->setToolTip(text);
  }
}

void InstructorWindow::frame_camera() {
  // A body on a support from its free side, down its press axis, whichever way the support
  // faces (an imported breast's chest wall faces +y); free bodies from the front and above.
  if (const auto up = scene_->free_side()) {
    frame_from_free_side(*renderer_, scene_->bounds(), *up, 1.3);
  } else if (scene_->has_bodies()) {
    frame_from_front(*renderer_, scene_->bounds(), 0.75, 1.3);
  }
  render();
}

void InstructorWindow::render() {
  // Room for bodies that grew since the camera was framed.
  if (scene_->has_bodies()) {
    auto b = scene_->bounds();
    renderer_->ResetCameraClippingRange(b.data());
  }
  render_window_->Render();
}

QPoint InstructorWindow::to_view(const palpa::Vec3& point) const {
  return view_->to_view(*renderer_, point);
}

bool InstructorWindow::click_at(const QPoint& pos, bool move_selected) {
  const auto [near, far] = view_->pointer_ray(*renderer_, pos);
  const auto hit = scene_->pick(near, far - near);
  if (!hit) {
    set_message(tr("Click on the body to place a tumour there."));
    return false;
  }
  const author::SurfacePoint where{hit->body,
                                   {hit->point.x(), hit->point.y(), hit->point.z()},
                                   {hit->normal.x(), hit->normal.y(), hit->normal.z()}};
  const auto selected = tumour_panel_->selected();
  if (move_selected && selected) {
    edit([this, k = *selected, where] { draft_.move_tumour(k, where); });
  } else {
    std::optional<std::size_t> added;
    const auto spec = tumour_panel_->spec();
    edit([this, &added, where, spec] { added = draft_.add_tumour(where, spec); });
    if (added) {
      tumour_panel_->select(added);
      tabs_->setCurrentWidget(tumour_panel_);  // its values are what the instructor edits next
      set_message(tr("Tumour %1 placed %2 mm below the skin.").arg(*added + 1).arg(spec.depth * 1e3, 0, 'f', 1));
    }
  }
  return true;
}

bool InstructorWindow::eventFilter(QObject* watched, QEvent* event) {
  if (watched != view_->input() && watched->isWidgetType()) {
    if (filter_editor_event(static_cast<QWidget*>(watched), event)) return true;
  } else if (watched == view_->input()) {
    if (event->type() == QEvent::MouseButtonPress) {
      auto* e = static_cast<QMouseEvent*>(event);
      if (e->button() == Qt::LeftButton) {
        press_at_ = e->pos();
        pressed_ = true;
      }
    } else if (event->type() == QEvent::MouseButtonRelease) {
      auto* e = static_cast<QMouseEvent*>(event);
      if (e->button() == Qt::LeftButton && pressed_) {
        pressed_ = false;
        if ((e->pos() - press_at_).manhattanLength() <= kClickSlop) {
          click_at(e->pos(), e->modifiers().testFlag(Qt::ShiftModifier));
        }
      }
    }
  }
  return QMainWindow::eventFilter(watched, event);
}

void InstructorWindow::set_stiffness_overlay(bool on) {
  if (overlay_->isChecked() != on) overlay_->setChecked(on);  // re-enters through toggled
  scene_->set_stiffness_overlay(on);
  render();
}

void InstructorWindow::undo() {
  commit_pending();  // a value typed just before Undo is the step undone
  if (draft_.undo()) {
    set_message(tr("Undone."));
    refresh();
  }
}

void InstructorWindow::redo() {
  commit_pending();
  if (draft_.redo()) {
    set_message(tr("Redone."));
    refresh();
  }
}

void InstructorWindow::set_message(const QString& text) {
  message_ = text;
  statusBar()->showMessage(text);
}

void InstructorWindow::update_title() {
  const QString name = draft_.path().empty() ? tr("untitled")
                                             : QString::fromStdString(draft_.path().filename().string());
  setWindowTitle(tr("Palpa: instructor (%1%2)").arg(name, draft_.dirty() ? "*" : ""));
}

}  // namespace palpa::ui
