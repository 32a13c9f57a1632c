#include "palpa/ui/mode_menu.hpp"

#include <QAction>
#include <QApplication>
#include <QFileDialog>
#include <QKeySequence>
#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>

namespace palpa::ui {

namespace {
const QString kCaseFilter = QObject::tr("Palpa cases (*.json);;All files (*)");
const QString kSessionFilter = QObject::tr("Palpa sessions (*.palpa);;All files (*)");
}  // namespace

ModeMenu::ModeMenu(QMainWindow& window) : QObject(&window) {
  choose_file = [&window](const QString& title, const QString& filter) {
    return QFileDialog::getOpenFileName(&window, title, QString(), filter);
  };
  QMenu* file = window.menuBar()->addMenu(tr("&File"));
  train_ = file->addAction(tr("&Train on a case..."));
  train_->setShortcut(QKeySequence(tr("Ctrl+T")));
  file->addSeparator();
  new_case_ = file->addAction(tr("&New case (instructor)"));
  author_ = file->addAction(tr("&Author a case..."));
  import_anatomy_ = file->addAction(tr("&Import anatomy…"));
  file->addSeparator();
  review_ = file->addAction(tr("&Review a session..."));
  review_->setShortcut(QKeySequence(tr("Ctrl+R")));
  file->addSeparator();
  QAction* quit = file->addAction(tr("&Quit"));
  quit->setShortcut(QKeySequence::Quit);

  connect(train_, &QAction::triggered, this, [this] {
    const QString path = choose_file(tr("Train on a case"), kCaseFilter);
    if (!path.isEmpty()) emit train(path);
  });
  connect(new_case_, &QAction::triggered, this, [this] { emit author(QString()); });
  connect(author_, &QAction::triggered, this, [this] {
    const QString path = choose_file(tr("Author a case"), kCaseFilter);
    if (!path.isEmpty()) emit author(path);
  });
  connect(import_anatomy_, &QAction::triggered, this, [this] { emit import_anatomy(); });
  connect(review_, &QAction::triggered, this, [this] {
    const QString path = choose_file(tr("Review a session"), kSessionFilter);
    if (!path.isEmpty()) emit review(path);
  });
  // Closing every window ends the application (each window finishes its own work on close).
  connect(quit, &QAction::triggered, qApp, &QApplication::closeAllWindows);
}

}  // namespace palpa::ui
