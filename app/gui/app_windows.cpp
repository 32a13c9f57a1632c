#include "app_windows.hpp"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <random>

#include <QMainWindow>
#include <QAction>
#include <QActionGroup>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QPointer>
#include <QStatusBar>
#include <QThread>

#include "palpa/author/case_draft.hpp"
#include "palpa/device/device_error.hpp"
#include "palpa/device/registry.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/score/score.hpp"
#include "palpa/session/session.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/live/live_exercise.hpp"
#include "palpa/ui/instructor_window.hpp"
#include "palpa/ui/mode_menu.hpp"
#include "palpa/ui/review_window.hpp"
#include "palpa/ui/session_paths.hpp"
#include "palpa/ui/trainee_window.hpp"
#include "palpa/ui/window_frame.hpp"
#include "session_upload.hpp"

namespace palpa::gui {

namespace {

std::uint64_t fresh_seed() {
  std::random_device entropy;
  return (static_cast<std::uint64_t>(entropy()) << 32) ^ entropy();
}

QString file_name(const QString& path) { return QString::fromStdString(std::filesystem::path(path.toStdString()).filename().string()); }

}  // namespace

std::filesystem::path default_session_path() { return ui::new_session_path(ui::sessions_dir(), "trainee"); }

AppWindows::AppWindows(TraineeSettings settings) : settings_(std::move(settings)) {
  // libpq waits for an unroutable store without limit; an upload must end (and let the
  // application quit). A timeout the user set (PGCONNECT_TIMEOUT, or in PALPA_STORE) wins.
  if (qEnvironmentVariableIsEmpty("PGCONNECT_TIMEOUT")) qputenv("PGCONNECT_TIMEOUT", "10");
}

AppWindows::~AppWindows() {
  for (QThread* t : uploads_) {
    t->wait();
    delete t;
  }
}

void AppWindows::upload_when_finished(ui::TraineeWindow& window) {
  connect(&window, &ui::TraineeWindow::session_ended, this, [this, w = QPointer<ui::TraineeWindow>(&window)](
                                                                const QString& path, bool scored) {
    std::optional<score::Score> score;
    if (scored && w && w->score()) score = *w->score();
    auto* thread = QThread::create([this, w, file = path.toStdString(), score] {
      const UploadOutcome outcome = upload_finished_session(file, score ? &*score : nullptr);
      QMetaObject::invokeMethod(this, [w, text = upload_status_text(outcome)] {
        if (w) w->show_upload_state(text);
      }, Qt::QueuedConnection);
    });
    // Threads of earlier exercises that are done go now; running ones are waited for at exit.
    std::erase_if(uploads_, [](QThread* t) { return t->isFinished() ? (delete t, true) : false; });
    uploads_.push_back(thread);
    thread->start();
  });
}

void AppWindows::fail(const QString& line, QWidget* parent) {
  last_error_ = line;
  if (parent) {
    QMessageBox::warning(parent, tr("Palpa"), line);
  } else {
    std::fprintf(stderr, "palpa: error: %s\n", line.toLocal8Bit().constData());
  }
}

void AppWindows::add_menus(QMainWindow& window) {
  auto* menu = new ui::ModeMenu(window);
  connect(menu, &ui::ModeMenu::train, this, [this, w = &window](const QString& path) { open_trainee(path, w); });
  connect(menu, &ui::ModeMenu::review, this, [this, w = &window](const QString& path) { open_review(path, w); });
  connect(menu, &ui::ModeMenu::author, this, [this, w = &window](const QString& path) { open_instructor(path, w); });
  // File > Import anatomy…: in this window when it is the instructor's, else in a new one.
  connect(menu, &ui::ModeMenu::import_anatomy, this, [this, w = &window] {
    auto* instructor = qobject_cast<ui::InstructorWindow*>(w);
    if (instructor == nullptr) instructor = qobject_cast<ui::InstructorWindow*>(open_instructor(QString(), w));
    if (instructor != nullptr) instructor->import_anatomy_dialog();
  });
  add_device_menu(window);
}

void AppWindows::adopt(QMainWindow& window) {
  window.setAttribute(Qt::WA_DeleteOnClose);
  add_menus(window);
  if (auto* trainee = qobject_cast<ui::TraineeWindow*>(&window)) upload_when_finished(*trainee);
  // The instructor's Try it palpates with the device chosen here, like any exercise, in a
  // window with the same menus (its session is a test-run: not uploaded).
  if (auto* instructor = qobject_cast<ui::InstructorWindow*>(&window)) {
    instructor->set_device_opener(
        [this, instructor] { return open_chosen_device_with_progress(settings_.device, instructor); });
    instructor->set_try_window_adopter([this](QMainWindow& tried) { add_menus(tried); });
  }
}

void AppWindows::add_device_menu(QMainWindow& window) {
  QMenu* menu = window.menuBar()->addMenu(tr("&Device"));
  connect(menu, &QMenu::aboutToShow, this, [this, menu, w = &window] {
    // clear() deletes the actions, not their group: the last listing's group goes with them.
    for (auto* old : menu->findChildren<QActionGroup*>()) delete old;
    menu->clear();
    auto* group = new QActionGroup(menu);
    const auto listing = device::list_devices();
    for (const auto& entry : listing.devices) {
      QString text = QString::fromStdString(entry.name);
      if (!entry.detail.empty()) text += QString(" (%1)").arg(QString::fromStdString(entry.detail));
      if (entry.force_output) text += tr(", force feedback");
      QAction* action = menu->addAction(text);
      action->setCheckable(true);
      // "spacemouse" or "falcon" (the first one found) ticks the first of that kind.
      const bool chosen = entry.id == settings_.device.id ||
                          (entry.kind == settings_.device.id && !group->checkedAction());
      action->setChecked(chosen);
      action->setData(QString::fromStdString(entry.id));
      group->addAction(action);
      connect(action, &QAction::triggered, this, [this, w, id = entry.id, text] {
        choose_device(id);
        w->statusBar()->showMessage(tr("The next exercise (File > Train on a case) uses %1").arg(text), 10000);
      });
    }
    for (const auto& note : listing.notes) menu->addSection(QString::fromStdString(note))->setEnabled(false);
  });
}

QMainWindow* AppWindows::open_trainee(const QString& case_path, QWidget* parent) {
  last_error_.clear();
  live::LiveOptions options;
  options.trainee = settings_.trainee;
  options.mode = "trainee";
  options.station = station_name();
  options.seed = settings_.seed ? *settings_.seed : fresh_seed();
  options.session_path = first_trainee_ && !settings_.first_session.empty() ? settings_.first_session
                                                                            : default_session_path();
  try {
    if (std::filesystem::exists(options.session_path)) {
      fail(QString::fromStdString(options.session_path.string() + ": file: exists (a session is never overwritten)"),
           parent);
      return nullptr;
    }
    options.device = open_chosen_device_with_progress(settings_.device, parent);
    const std::string source = case_path.toStdString();
    auto exercise = std::make_unique<live::LiveExercise>(io::load_case(source), source, options);
    auto* window = new ui::TraineeWindow(std::move(exercise), file_name(case_path));
    first_trainee_ = false;
    adopt(*window);
    window->show();
    ui::take_keys(*window);  // opened from another window: no window manager may activate it
    std::fprintf(stderr, "palpa: recording the session in %s\n", options.session_path.c_str());
    return window;
  } catch (const device::DeviceError& e) {
    fail(QString::fromStdString(e.what()), parent);
  } catch (const io::CaseError& e) {
    QString line = QString::fromStdString(e.what());
    if (e.problems().size() > 1) {
      line += tr(" (and %1 more: palpa-cli validate lists them)").arg(e.problems().size() - 1);
    }
    fail(line, parent);
  } catch (const std::exception& e) {
    fail(QString::fromStdString(e.what()), parent);
  }
  return nullptr;
}

QMainWindow* AppWindows::open_review(const QString& session_path, QWidget* parent) {
  last_error_.clear();
  const std::string path = session_path.toStdString();
  try {
    session::Session session = session::read_session(path);
    score::Score score = score::score_session(session, path);
    auto* window = new ui::ReviewWindow(std::move(session), std::move(score), path);
    adopt(*window);
    window->show();
    ui::take_keys(*window);  // opened from another window: no window manager may activate it
    return window;
  } catch (const session::SessionError& e) {
    fail(QString::fromStdString(e.what()), parent);
  } catch (const io::CaseError& e) {
    fail(QString::fromStdString(e.what()), parent);
  } catch (const std::exception& e) {
    fail(QString::fromStdString(path + ": " + e.what()), parent);
  }
  return nullptr;
}

QMainWindow* AppWindows::open_instructor(const QString& case_path, QWidget* parent) {
  last_error_.clear();
  try {
    // A case that is JSON but not valid opens with its problems listed; only a file that
    // cannot be read or is not JSON is refused.
    auto draft = case_path.isEmpty() ? author::CaseDraft() : author::CaseDraft::load(case_path.toStdString());
    auto* window = new ui::InstructorWindow(std::move(draft));
    window->set_sessions_dir(ui::try_it_sessions_dir());  // apart from the trainees' sessions
    adopt(*window);
    window->show();
    ui::take_keys(*window);  // opened from another window: no window manager may activate it
    return window;
  } catch (const io::CaseError& e) {
    fail(QString::fromStdString(e.what()), parent);
  } catch (const std::exception& e) {
    fail(QString::fromStdString(e.what()), parent);
  }
  return nullptr;
}

}  // namespace palpa::gui
