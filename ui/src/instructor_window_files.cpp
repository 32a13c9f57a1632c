// The instructor window's files: New, Open, Save (As) with validation, the stiffness map
// import, and "Try it" (the case in a trainee window, recording a session).
#include <cstdlib>
#include <random>

#include <fmt/format.h>
#include <QCloseEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QMessageBox>

#include "palpa/live/live_exercise.hpp"
#include "palpa/ui/instructor_preset_panel.hpp"
#include "palpa/ui/instructor_stiffness_image.hpp"
#include "palpa/ui/instructor_window.hpp"
#include "palpa/ui/session_paths.hpp"
#include "palpa/ui/trainee_window.hpp"
#include "palpa/ui/window_frame.hpp"

namespace palpa::ui {

bool InstructorWindow::open_case(const QString& path) {
  commit_pending();
  try {
    draft_ = author::CaseDraft::load(path.toStdString());
  } catch (const io::CaseError& e) {
    // Nothing to edit (unreadable, not JSON): the current case and its problems stay.
    set_message(QString::fromStdString(e.lines().front()));
    return false;
  }
  drawn_bodies_ = nlohmann::json();
  refresh();
  frame_camera();
  const auto problems = draft_.validate();
  set_message(problems.empty() ? tr("Opened %1.").arg(path)
                               : tr("Opened %1: %2 problem(s), listed below.").arg(path).arg(problems.size()));
  return true;
}

bool InstructorWindow::save() {
  commit_pending();
  if (draft_.path().empty()) {
    set_message(tr("The case has no file yet: use Save As."));
    return false;
  }
  return save_as(QString::fromStdString(draft_.path().string()));
}

bool InstructorWindow::save_as(const QString& path) {
  commit_pending();
  try {
    draft_.save(path.toStdString());
  } catch (const io::CaseError& e) {
    show_problems(e.problems());
    set_message(tr("Not saved: the case has %1 problem(s), listed below.").arg(e.problems().size()));
    return false;
  } catch (const std::exception& e) {
    set_message(tr("Not saved: %1").arg(e.what()));
    return false;
  }
  set_message(tr("Saved %1.").arg(path));
  refresh();
  return true;
}

void InstructorWindow::new_case(author::Preset preset) {
  commit_pending();  // the typed title must not be applied to the new case later
  draft_ = author::CaseDraft(preset_panel_->defaults(preset));
  drawn_bodies_ = nlohmann::json();
  refresh();
  frame_camera();
  set_message(tr("New %1 case.").arg(tr(author::label(preset))));
}

bool InstructorWindow::import_stiffness_map(const QString& path) {
  std::string error;
  const auto map = read_stiffness_image(path.toStdString(), error);
  if (!map) {
    set_message(QString::fromStdString(error));
    return false;
  }
  const double lo = preset_panel_->map_k_min(), hi = preset_panel_->map_k_max();
  const bool kpa = preset_panel_->map_in_kpa();
  bool ok = false;
  edit([&] {
    if (kpa) {
      draft_.apply_modulus_map(0, *map, lo * 1e3, hi * 1e3);
    } else {
      draft_.apply_stiffness_map(0, *map, lo, hi);
    }
    ok = true;
  });
  if (ok) {
    set_message(kpa ? tr("Modulus map %1 applied: %2 to %3 kPa.").arg(path).arg(lo).arg(hi)
                    : tr("Stiffness map %1 applied: %2 to %3 N/m.").arg(path).arg(lo).arg(hi));
    set_stiffness_overlay(true);  // show what it did
  }
  return ok;
}

TraineeWindow* InstructorWindow::try_it() {
  commit_pending();
  io::CaseFile file;
  try {
    file = draft_.valid_case();
  } catch (const io::CaseError& e) {
    show_problems(e.problems());
    set_message(tr("Fix the problems listed below before trying the case."));
    return nullptr;
  }
  live::LiveOptions options;
  const char* user = std::getenv("USER");
  options.trainee = user && *user ? user : "instructor";
  options.mode = "instructor-try";
  std::random_device entropy;
  options.seed = (static_cast<std::uint64_t>(entropy()) << 32) ^ entropy();
  const std::filesystem::path dir = sessions_dir_.empty() ? ui::try_it_sessions_dir() : sessions_dir_;
  options.session_path = dir / fmt::format("tryout-{}-{}.palpa", ui::utc_stamp(), ++try_count_);
  if (device_opener_) {
    try {
      options.device = device_opener_();
    } catch (const std::exception& e) {
      const QString what = QString::fromStdString(e.what());
      set_message(what.section('\n', 0, 0));
      return nullptr;
    }
  }
  try {
    std::filesystem::create_directories(dir);
    auto exercise = std::make_unique<live::LiveExercise>(file, draft_.source(), options);
    const QString case_name = draft_.path().empty() ? tr("untitled")
                                                    : QString::fromStdString(draft_.path().filename().string());
    auto* window = new TraineeWindow(std::move(exercise), case_name, true);
    window->setAttribute(Qt::WA_DeleteOnClose);
    if (try_adopter_) try_adopter_(*window);
    window->show();
    take_keys(*window, window->centralWidget());  // M and the arrows work before any click
    try_windows_.emplace_back(window);
    set_message(tr("Trying the case; the session is recorded in %1.").arg(QString::fromStdString(options.session_path.string())));
    return window;
  } catch (const std::exception& e) {
    set_message(tr("Could not start the exercise: %1").arg(e.what()));
    return nullptr;
  }
}

bool InstructorWindow::confirm_discard() {
  commit_pending();
  if (!draft_.dirty()) return true;
  const auto answer = QMessageBox::question(this, tr("Unsaved changes"),
                                            tr("The case has unsaved changes. Save them first?"),
                                            QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel);
  if (answer == QMessageBox::Cancel) return false;
  if (answer == QMessageBox::Discard) return true;
  if (draft_.path().empty()) {
    save_as_dialog();
  } else {
    save();
  }
  return !draft_.dirty();
}

void InstructorWindow::closeEvent(QCloseEvent* event) {
  if (confirm_discard()) {
    // Their closeEvent finishes the sessions (End event); they delete themselves.
    for (auto& w : try_windows_) {
      if (!w) continue;
    w->setProperty(TraineeWindow::kCloseWithoutAsking, true);  // the instructor closed the case
    w->close();
    }
    event->accept();
  } else {
    event->ignore();
  }
}

void InstructorWindow::open_dialog() {
  if (!confirm_discard()) return;
  const QString path = QFileDialog::getOpenFileName(this, tr("Open case"), QString(), tr("Palpa cases (*.json)"));
  if (!path.isEmpty() && !open_case(path)) QMessageBox::warning(this, tr("Cannot open"), message_);
}

QString InstructorWindow::choose_save_path() {
  if (save_path_chooser_) return save_path_chooser_();
  QFileDialog dialog(this, tr("Save case"), QString(), tr("Palpa cases (*.json)"));
  dialog.setAcceptMode(QFileDialog::AcceptSave);
  dialog.setDefaultSuffix("json");  // added before the dialog asks about replacing a file
  if (dialog.exec() != QDialog::Accepted || dialog.selectedFiles().isEmpty()) return {};
  return dialog.selectedFiles().front();
}

bool InstructorWindow::save_as_dialog() {
  commit_pending();
  QString path = choose_save_path();
  if (path.isEmpty()) return false;
  if (!path.endsWith(".json", Qt::CaseInsensitive)) {
    path += ".json";
    // The chooser asked about the name without ".json", not this one.
    if (QFileInfo::exists(path) &&
        QMessageBox::question(this, tr("Replace file"), tr("%1 already exists. Replace it?").arg(path),
                              QMessageBox::Yes | QMessageBox::No, QMessageBox::No) != QMessageBox::Yes) {
      set_message(tr("Not saved: %1 exists.").arg(path));
      return false;
    }
  }
  if (!save_as(path)) {
    QMessageBox::warning(this, tr("Not saved"), message_);
    return false;
  }
  return true;
}

void InstructorWindow::import_dialog() {
  const QString path = QFileDialog::getOpenFileName(this, tr("Import stiffness map"), QString(),
                                                    tr("Images (*.png *.jpg *.jpeg *.bmp *.tif *.tiff);;All files (*)"));
  if (!path.isEmpty() && !import_stiffness_map(path)) QMessageBox::warning(this, tr("Stiffness map"), message_);
}

}  // namespace palpa::ui
