#pragma once
// The instructor's authoring window: a case from a preset (breast, prostate,
// skin/abdomen patch, generic slab) with its size and stiffness, tumours placed by
// clicking the body with their depth, size, stiffness and randomization rule, a
// stiffness overlay, stiffness maps imported from images, undo/redo, New/Open/Save with
// the validation problems listed by JSON pointer and the offending control highlighted,
// "Import anatomy…" (a case fitted to segmented anatomy, previewed before it replaces the
// draft), and "Try it", which opens the case in a trainee window. The case itself is
// author::CaseDraft (core); this window only shows it and turns controls into its edits.
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <QMainWindow>
#include <QPoint>
#include <QPointer>

#include <vtkSmartPointer.h>

#include "palpa/author/case_draft.hpp"
#include "palpa/author/problem_text.hpp"
#include "palpa/engine/device.hpp"
#include "palpa/render/surface_pick.hpp"

class QAction;
class QLabel;
class QLineEdit;
class QListWidget;
class QTabWidget;
class vtkGenericOpenGLRenderWindow;
class vtkRenderer;

namespace palpa::ui {

class InstructorExamPanel;
class InstructorPresetPanel;
class InstructorScene;
class InstructorTumourPanel;
class TraineeWindow;
class VtkView;

class InstructorWindow : public QMainWindow {
  Q_OBJECT
 public:
  explicit InstructorWindow(author::CaseDraft draft, QWidget* parent = nullptr);
  ~InstructorWindow() override;

  const author::CaseDraft& draft() const { return draft_; }
  VtkView* view() const { return view_; }
  InstructorPresetPanel* preset_panel() const { return preset_panel_; }
  InstructorTumourPanel* tumour_panel() const { return tumour_panel_; }
  InstructorExamPanel* exam_panel() const { return exam_panel_; }
  /// The side panel's tabs: Body, Tumours, Exam (description, scoring, exam region).
  QTabWidget* side_tabs() const { return tabs_; }
  /// The validation problems and warnings, one item each, in mm and kPa with the tumour's
  /// row ("Tumour 2, radius: ..."); the item's Qt::UserRole holds the JSON pointer.
  QListWidget* problems() const { return problems_; }
  static constexpr int kWarningRole = Qt::UserRole + 1;
  QLineEdit* title_edit() const { return title_; }
  const InstructorScene& scene() const { return *scene_; }
  /// The bodies' renderer (its camera is the view's).
  vtkRenderer* renderer() const { return renderer_; }
  QAction* undo_action() const { return undo_; }
  QAction* redo_action() const { return redo_; }
  /// Where a scene point (m) appears in the view (widget pixels).
  QPoint to_view(const palpa::Vec3& point) const;
  /// Where "Try it" records its sessions (created when needed); by default
  /// ui::try_it_sessions_dir(), never the trainees' sessions folder.
  void set_sessions_dir(const std::filesystem::path& dir) { sessions_dir_ = dir; }
  /// Called with each trainee window "Try it" opens, before it is shown: the application
  /// gives it the menus every window has (File, Device).
  void set_try_window_adopter(std::function<void(QMainWindow&)> adopter) { try_adopter_ = std::move(adopter); }
  /// The device "Try it" opens the trainee window with, called once per try (e.g. the
  /// application's chosen device). It may return null (the virtual device the pointer
  /// steers, also the default without an opener) or throw std::exception: the first line
  /// of what() is shown and no trainee window opens.
  void set_device_opener(std::function<std::shared_ptr<engine::Device>()> opener) {
    device_opener_ = std::move(opener);
  }
  /// Where Save As writes (an empty string: cancelled). Default: a file dialog that adds
  /// ".json" to a name without it before asking whether to replace an existing file.
  void set_save_path_chooser(std::function<QString()> chooser) { save_path_chooser_ = std::move(chooser); }
  /// The newest trainee window "Try it" opened, while it is open.
  TraineeWindow* try_window() const { return try_windows_.empty() ? nullptr : try_windows_.back().data(); }
  /// The last message shown in the status bar (errors included).
  const QString& message() const { return message_; }

  /// File > Import anatomy… (and the Case menu's): segmented anatomy imported and
  /// previewed in a dialog; "Use this case" makes it the draft
  /// (ui/src/import_anatomy_dialog.hpp).
  void import_anatomy_dialog();

 public slots:
  /// Opens a case for editing. A file that is JSON but not a valid case opens with its
  /// problems listed; one that cannot be read or is not JSON leaves the current case and
  /// returns false. Returns true when it opened.
  bool open_case(const QString& path);
  /// Saves to the case's file; false without one, or when the case has problems (listed).
  bool save();
  bool save_as(const QString& path);
  /// Save As through the chooser: ".json" is added to a name without it, and a file of that
  /// name the chooser did not ask about is replaced only when the instructor says so.
  /// False when cancelled or not saved.
  bool save_as_dialog();
  void new_case(author::Preset preset);
  void undo();
  void redo();
  /// Sets the first body's stiffness from a grayscale image, between the panel's black and
  /// white stiffness. False (and a message) when the image cannot be read.
  bool import_stiffness_map(const QString& path);
  void set_stiffness_overlay(bool on);
  /// A click at `pos` (view pixels): adds a tumour under it with the panel's depth, radius
  /// and stiffness, or moves the selected one there (move_selected). False off the body.
  bool click_at(const QPoint& pos, bool move_selected = false);
  /// Opens the current case in a trainee window (seeded placement, a new session file in
  /// the sessions directory). Nothing, with the problems listed, when it is invalid.
  TraineeWindow* try_it();

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;
  /// Closing (accepted) also closes the Try-it trainee windows, which finishes their sessions.
  void closeEvent(QCloseEvent* event) override;

 private:
  void build_view();
  /// The side panel: the title over the Body, Tumours and Exam tabs, in a scroll area.
  QWidget* build_side(QWidget* parent);
  void connect_panels();
  void build_actions();
  /// Runs an edit of the draft; errors become a message. Then refresh().
  void edit(const std::function<void()>& op);
  /// Shows the draft: panels, problems, bodies (refit when they changed), tumours.
  void refresh();
  /// The problems in the instructor's terms (author::describe), then the warnings (e.g. a
  /// tumour likely not palpable), each item carrying its JSON pointer (Qt::UserRole) and
  /// whether it is a warning (kWarningRole).
  void show_problems(const std::vector<io::Problem>& problems, const std::vector<author::AuthorProblem>& warnings = {});
  void show_problem(const author::AuthorProblem& p);
  void frame_camera();
  void render();
  void set_message(const QString& text);
  void update_title();
  bool confirm_discard();
  /// Makes the focused editor of this window commit what was typed in it (its
  /// editingFinished and value), so that the action about to run sees it.
  void commit_pending();
  /// Side-panel editors: Undo/Redo keys reach the window; the wheel changes a value only
  /// with focus (so scrolling the panel does not edit the case).
  void guard_editors();
  bool filter_editor_event(QWidget* editor, QEvent* event);
  QString choose_save_path();
  void open_dialog();
  void import_dialog();
  void use_imported_case(const io::CaseFile& file);

  author::CaseDraft draft_;
  VtkView* view_ = nullptr;
  InstructorPresetPanel* preset_panel_ = nullptr;
  InstructorTumourPanel* tumour_panel_ = nullptr;
  InstructorExamPanel* exam_panel_ = nullptr;
  QTabWidget* tabs_ = nullptr;
  QListWidget* problems_ = nullptr;
  QLineEdit* title_ = nullptr;
  QAction* undo_ = nullptr;
  QAction* redo_ = nullptr;
  QAction* overlay_ = nullptr;
  vtkSmartPointer<vtkGenericOpenGLRenderWindow> render_window_;
  vtkSmartPointer<vtkRenderer> renderer_;
  vtkSmartPointer<vtkRenderer> overlay_renderer_;
  std::unique_ptr<InstructorScene> scene_;
  nlohmann::json drawn_bodies_;  // the "bodies" the view shows
  std::filesystem::path sessions_dir_;
  std::function<std::shared_ptr<engine::Device>()> device_opener_;
  std::function<QString()> save_path_chooser_;
  std::function<void(QMainWindow&)> try_adopter_;
  std::vector<QPointer<TraineeWindow>> try_windows_;
  QString message_;
  QPoint press_at_;
  bool pressed_ = false;
  int try_count_ = 0;
};

}  // namespace palpa::ui
