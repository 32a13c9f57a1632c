#pragma once
// Opens Palpa's windows by mode (trainee, instructor, review) and
// wires each one's File menu (ui::ModeMenu) back here, so a trainee can pick another case,
// an instructor try a case, anyone review a session, from whichever window is open.
// Windows delete themselves when closed; the application ends with the last one.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <QObject>
#include <QString>

#include "gui_device.hpp"

class QMainWindow;
class QThread;
class QWidget;

namespace palpa::ui {
class TraineeWindow;
}

namespace palpa::gui {

struct TraineeSettings {
  std::string trainee = "trainee";       ///< id recorded in every session
  std::optional<std::uint64_t> seed;     ///< placement seed; a fresh one per exercise when unset
  /// The first trainee window open_trainee makes records here; later ones (and an empty
  /// path) record to default_session_path().
  std::filesystem::path first_session;
  /// The device new exercises palpate with (palpa --device; the Device menu changes it).
  DeviceChoice device;
};

/// $XDG_DATA_HOME/palpa/sessions/trainee-UTCSTAMP.palpa (~/.local/share/... by default).
std::filesystem::path default_session_path();

class AppWindows : public QObject {
  Q_OBJECT
 public:
  explicit AppWindows(TraineeSettings settings);
  /// Waits for uploads still running (each is bounded by its connection timeouts).
  ~AppWindows() override;

  /// Each opens a window and shows it, or reports why not (the one-line error: in a
  /// message box over `parent`, on stderr without one) and returns nullptr.
  QMainWindow* open_trainee(const QString& case_path, QWidget* parent = nullptr);
  QMainWindow* open_review(const QString& session_path, QWidget* parent = nullptr);
  /// The instructor's editor on this case; an empty path starts a new case (a breast).
  QMainWindow* open_instructor(const QString& case_path, QWidget* parent = nullptr);

  /// Takes a window opened elsewhere (main's first window): gives it the File menu and
  /// lets it delete itself when closed.
  void adopt(QMainWindow& window);

  /// The last error line ("FILE: WHERE: REASON"), empty after a success.
  const QString& last_error() const { return last_error_; }
  /// The device the next exercise will use.
  const DeviceChoice& device() const { return settings_.device; }
  void choose_device(const std::string& id) { settings_.device.id = id; }

 private:
  void fail(const QString& line, QWidget* parent);
  /// The menus every window has: File (ui::ModeMenu, wired here) and Device.
  void add_menus(QMainWindow& window);
  /// The Device menu: what is attached now (listed again each time it opens: hot-plug).
  void add_device_menu(QMainWindow& window);
  /// After an exercise: the session to the centre store and its statement to the LRS, off
  /// the GUI thread; the outcome goes to the window's status bar while it is open.
  void upload_when_finished(ui::TraineeWindow& window);

  TraineeSettings settings_;
  bool first_trainee_ = true;
  QString last_error_;
  std::vector<QThread*> uploads_;
};

}  // namespace palpa::gui
