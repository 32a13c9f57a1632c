#pragma once
// The File menu every Palpa window shares: train on a case, author a case, review a
// session, quit. The menu only asks for a file and says what was chosen; the application
// (app/gui) opens the window for it, so a window never needs to know the others.
#include <functional>

#include <QObject>
#include <QString>

class QAction;
class QMainWindow;

namespace palpa::ui {

class ModeMenu : public QObject {
  Q_OBJECT
 public:
  /// Adds the menu to the window's menu bar (the menu belongs to the window).
  explicit ModeMenu(QMainWindow& window);

  /// Asks for a file to open: (title, name filter) -> path, empty when cancelled. A file
  /// dialog by default; tests replace it.
  std::function<QString(const QString& title, const QString& filter)> choose_file;

  QAction* train_action() const { return train_; }
  QAction* author_action() const { return author_; }
  QAction* import_anatomy_action() const { return import_anatomy_; }
  QAction* new_case_action() const { return new_case_; }
  QAction* review_action() const { return review_; }

 signals:
  /// Palpate this case as a trainee (its tumours hidden, placed anew where it allows).
  void train(const QString& case_path);
  /// Edit this case in the instructor's editor; an empty path starts a new case.
  void author(const QString& case_path);
  /// File > Import anatomy…: segmented anatomy to a case, in the instructor window
  /// (docs/anatomy-import.md).
  void import_anatomy();
  /// Replay this recorded session.
  void review(const QString& session_path);

 private:
  QAction* train_ = nullptr;
  QAction* author_ = nullptr;
  QAction* import_anatomy_ = nullptr;
  QAction* new_case_ = nullptr;
  QAction* review_ = nullptr;
};

}  // namespace palpa::ui
