// The application's windows by mode and the File menu they share (QtTest under Xvfb):
// the menu opens another case or a session, and a bad file is refused with one line that
// names it, without closing what is open.
#include <QAction>
#include <QApplication>
#include <QDialog>
#include <QFile>
#include <QMenu>
#include <QMenuBar>
#include <QPushButton>
#include <QLabel>
#include <QSurfaceFormat>
#include <QTcpServer>
#include <QTcpSocket>
#include <QTemporaryDir>
#include <QVTKOpenGLNativeWidget.h>
#include <QtTest>

#include "app_windows.hpp"
#include "palpa/ui/instructor_window.hpp"
#include "palpa/ui/mode_menu.hpp"
#include "palpa/ui/review_window.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/ui/trainee_window.hpp"

namespace {

const QString kDefaultCase = PALPA_SOURCE_DIR "/data/cases/default.json";
const QString kFlatCase = PALPA_SOURCE_DIR "/data/cases/flat-5x5.json";
const QString kExpert = PALPA_SOURCE_DIR "/data/sessions/expert.palpa";

template <class W>
int open_windows() {
  int n = 0;
  for (auto* w : QApplication::topLevelWidgets()) {
    if (qobject_cast<W*>(w) && w->isVisible()) ++n;
  }
  return n;
}

// A loopback receiver standing in for a learning record store: records each request's first
// line and answers 204 No Content, as an LRS answers a PUT of a statement it now holds.
// (Palpa's statements against a real LRS: cli.lrs.)
int content_length(const QByteArray& head) {
  for (const QByteArray& line : head.toLower().split('\n')) {
    if (line.startsWith("content-length:")) return line.mid(15).trimmed().toInt();
  }
  return 0;
}

class LoopbackLrs : public QObject {
 public:
  LoopbackLrs() {
    server_.listen(QHostAddress::LocalHost, 0);
    connect(&server_, &QTcpServer::newConnection, this, [this] {
      QTcpSocket* s = server_.nextPendingConnection();
      connect(s, &QTcpSocket::readyRead, s, [this, s] {
        buffer_ += s->readAll();
        const int end = buffer_.indexOf("\r\n\r\n");
        if (end < 0) return;
        const int length = content_length(buffer_.left(end));
        if (buffer_.size() < end + 4 + length) return;
        requests << QString::fromUtf8(buffer_.left(buffer_.indexOf("\r\n")));
        buffer_.clear();
        s->write("HTTP/1.1 204 No Content\r\nConnection: close\r\n\r\n");
        s->disconnectFromHost();
      });
    });
  }
  QString endpoint() const { return QString("http://127.0.0.1:%1/xapi").arg(server_.serverPort()); }
  QStringList requests;

 private:
  QTcpServer server_;
  QByteArray buffer_;
};

}  // namespace

class AppWindowsTest : public QObject {
  Q_OBJECT
 private slots:
  void initTestCase() {
    QVERIFY(sessions_.isValid());
    // Sessions recorded by these windows go to a scratch directory, not the user's.
    qputenv("XDG_DATA_HOME", sessions_.path().toLocal8Bit());
  }

  void cleanup() {
    // As a signal would: running exercises end without asking (nobody answers here).
    for (auto* w : QApplication::topLevelWidgets()) w->setProperty(palpa::ui::TraineeWindow::kCloseWithoutAsking, true);
    QApplication::closeAllWindows();
    QTest::qWait(50);
  }

  void fileMenuOpensAnotherCaseAndASession() {
    palpa::gui::AppWindows app({"ui-test", 3, {}, {}});
    auto* first = app.open_trainee(kDefaultCase);
    QVERIFY2(first, qPrintable(app.last_error()));
    QVERIFY(QTest::qWaitForWindowExposed(first));
    auto* menu = first->findChild<palpa::ui::ModeMenu*>();
    QVERIFY(menu);
    QCOMPARE(first->menuBar()->actions().size(), 2);  // File, Device

    menu->choose_file = [](const QString&, const QString& filter) {
      return filter.contains("json") ? kFlatCase : kExpert;
    };
    menu->train_action()->trigger();
    QCOMPARE(open_windows<palpa::ui::TraineeWindow>(), 2);
    menu->review_action()->trigger();
    QCOMPARE(open_windows<palpa::ui::ReviewWindow>(), 1);
    palpa::ui::ReviewWindow* review = nullptr;
    for (auto* w : QApplication::topLevelWidgets()) {
      if (auto* r = qobject_cast<palpa::ui::ReviewWindow*>(w)) review = r;
    }
    QVERIFY(review);
    // Opened from another window, it takes the keys at once (no window manager here would).
    QTRY_VERIFY(review->isActiveWindow());
    // The trainee id data/sessions/make_sessions.sh recorded.
    QCOMPARE(review->session().info.trainee, std::string("sample-expert"));

    // Cancelling the dialog opens nothing.
    menu->choose_file = [](const QString&, const QString&) { return QString(); };
    menu->train_action()->trigger();
    QCOMPARE(open_windows<palpa::ui::TraineeWindow>(), 2);

    // Each exercise records its own session file under $XDG_DATA_HOME/palpa/sessions.
    const QDir dir(sessions_.path() + "/palpa/sessions");
    QCOMPARE(dir.entryList({"*.palpa"}, QDir::Files).size(), 2);
  }

  // File > Import anatomy… (docs/anatomy-import.md): from a trainee's window it opens an
  // instructor window with the import dialog; from an instructor's window, the dialog there.
  void fileMenuImportsAnatomyInTheInstructorWindow() {
    palpa::gui::AppWindows app({"ui-test", 3, {}, {}});
    auto* trainee = app.open_trainee(kDefaultCase);
    QVERIFY2(trainee, qPrintable(app.last_error()));
    QVERIFY(QTest::qWaitForWindowExposed(trainee));
    const auto import_dialog = [] {
      for (int tries = 0; tries < 100; ++tries) {
        for (auto* w : QApplication::topLevelWidgets()) {
          auto* d = qobject_cast<QDialog*>(w);
          if (d && d->objectName() == "importAnatomyDialog" && d->isVisible()) return d;
        }
        QTest::qWait(20);
      }
      return static_cast<QDialog*>(nullptr);
    };
    trainee->findChild<palpa::ui::ModeMenu*>()->import_anatomy_action()->trigger();
    QCOMPARE(open_windows<palpa::ui::InstructorWindow>(), 1);
    QDialog* dialog = import_dialog();
    QVERIFY(dialog);
    dialog->reject();
    QTRY_VERIFY(!dialog->isVisible());
    palpa::ui::InstructorWindow* instructor = nullptr;
    for (auto* w : QApplication::topLevelWidgets()) {
      if (auto* i = qobject_cast<palpa::ui::InstructorWindow*>(w)) instructor = i;
    }
    QVERIFY(instructor);
    instructor->findChild<palpa::ui::ModeMenu*>()->import_anatomy_action()->trigger();
    QCOMPARE(open_windows<palpa::ui::InstructorWindow>(), 1);
    dialog = import_dialog();
    QVERIFY(dialog);
    QVERIFY(dialog->parentWidget() == nullptr || dialog->window() == dialog);
    dialog->reject();
  }

  void deviceMenuListsTheVirtualDeviceAndAMissingDeviceIsRefused() {
    palpa::gui::AppWindows app({"ui-test", 3, {}, {}});
    auto* first = app.open_trainee(kDefaultCase);
    QVERIFY2(first, qPrintable(app.last_error()));
    QMenu* devices = nullptr;
    for (auto* action : first->menuBar()->actions()) {
      if (action->text() == "&Device") devices = action->menu();
    }
    QVERIFY(devices);
    emit devices->aboutToShow();  // listed afresh each time it opens (hot-plug)
    QStringList ids;
    QString checked;
    for (auto* action : devices->actions()) {
      if (!action->data().isValid()) continue;
      ids << action->data().toString();
      if (action->isChecked()) checked = action->data().toString();
    }
    QVERIFY2(ids.contains("virtual"), qPrintable(ids.join(",")));
    QCOMPARE(checked, QString("virtual"));

    // No Falcon on this machine: the next exercise is refused with one line naming it,
    // and the window already open stays.
    app.choose_device("falcon");
    QVERIFY(!app.open_trainee(kDefaultCase));
    QVERIFY2(app.last_error().startsWith("falcon"), qPrintable(app.last_error()));
    QVERIFY(!app.last_error().contains('\n'));
    QCOMPARE(open_windows<palpa::ui::TraineeWindow>(), 1);
  }

  void instructorTryItUsesTheChosenDevice() {
    palpa::gui::AppWindows app({"ui-test", 3, {}, {}});
    auto* window = qobject_cast<palpa::ui::InstructorWindow*>(app.open_instructor(QString()));
    QVERIFY2(window, qPrintable(app.last_error()));
    // No Falcon here: Try it is refused (the reason shown in the window), nothing opens.
    app.choose_device("falcon");
    QVERIFY(!window->try_it());
    QCOMPARE(open_windows<palpa::ui::TraineeWindow>(), 0);
    // The mouse: Try it opens an exercise on the edited case.
    app.choose_device("virtual");
    const QString trainees = sessions_.path() + "/palpa/sessions";
    const auto before = QDir(trainees).entryList({"*.palpa"}, QDir::Files).size();
    auto* trainee = window->try_it();
    QVERIFY(trainee);
    QCOMPARE(trainee->exercise().device_name(), std::string("virtual (mouse)"));
    // The Try-it window has the menus of a trainee window (File, Device) ...
    QStringList menus;
    for (auto* action : trainee->menuBar()->actions()) menus << action->text();
    QCOMPARE(menus, QStringList({"&File", "&Device"}));
    QVERIFY(trainee->findChild<palpa::ui::ModeMenu*>());
    // ... and records into its own folder, not the trainees' sessions folder.
    QCOMPARE(QString::fromStdString(trainee->exercise().session_path().parent_path().string()), trainees + "/try-it");
    QVERIFY(QFile::exists(QString::fromStdString(trainee->exercise().session_path().string())));
    QCOMPARE(QDir(trainees).entryList({"*.palpa"}, QDir::Files).size(), before);
  }

  // A station with a centre store that is down and an LRS that is up: finishing the exercise
  // (a click on the button) queues the session in the outbox, sends the statement, and the
  // status bar says both in words.
  void aFinishedExerciseIsUploadedAndTheStatusBarSaysHow() {
    LoopbackLrs lrs;
    QTemporaryDir config;
    qputenv("XDG_CONFIG_HOME", config.path().toLocal8Bit());  // no config files of the user's
    qputenv("PALPA_LRS", lrs.endpoint().toLocal8Bit());
    qputenv("PALPA_STORE", "host=127.0.0.1 port=1 dbname=palpa connect_timeout=2");  // nothing listens there
    qputenv("PALPA_STATION", "room-7");
    palpa::gui::AppWindows app({"ui-upload", 3, {}, {}});
    auto* window = qobject_cast<palpa::ui::TraineeWindow*>(app.open_trainee(kDefaultCase));
    QVERIFY2(window, qPrintable(app.last_error()));
    QVERIFY(QTest::qWaitForWindowExposed(window));
    auto* state = window->findChild<QLabel*>("uploadState");
    QVERIFY(state);
    QVERIFY(!state->isVisible());
    QPushButton* finish = nullptr;
    for (auto* b : window->findChildren<QPushButton*>()) {
      if (b->text().startsWith("Finish")) finish = b;
    }
    QVERIFY(finish);
    QTest::qWait(300);  // a few hundred ticks recorded
    QTest::mouseClick(finish, Qt::LeftButton);
    QTRY_VERIFY_WITH_TIMEOUT(state->isVisible(), 20000);
    QVERIFY2(state->text().contains("Centre store: 1 waiting in the outbox"), qPrintable(state->text()));
    QVERIFY2(state->text().contains("Learning record store: sent."), qPrintable(state->text()));
    QCOMPARE(lrs.requests.size(), 1);
    QVERIFY2(lrs.requests[0].startsWith("PUT /xapi/statements?statementId="), qPrintable(lrs.requests[0]));
    // The session waits in the store outbox as a copy; the station's own file is untouched.
    const QDir outbox(sessions_.path() + "/palpa/outbox");
    QCOMPARE(outbox.entryList({"*.palpa"}, QDir::Files).size(), 1);
    QVERIFY(QFile::exists(QString::fromStdString(window->exercise().session_path().string())));
    // The session says which station recorded it (summary.csv's station column).
    const auto info = palpa::session::read_session(window->exercise().session_path(), {false}).info;
    QCOMPARE(QString::fromStdString(info.extra.value("station", std::string())), QString("room-7"));
    qunsetenv("PALPA_LRS");
    qunsetenv("PALPA_STORE");
    qunsetenv("PALPA_STATION");
  }

  void badFilesAreRefusedWithOneLineNamingThem() {
    palpa::gui::AppWindows app({"ui-test", 3, {}, {}});
    QTemporaryDir dir;
    const QString bad_case = dir.filePath("bad.json");
    QFile f(bad_case);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(R"({"format": "palpa-case", "version": 1, "title": "x", "bodies": []})");
    f.close();
    QVERIFY(!app.open_trainee(bad_case));
    QVERIFY2(app.last_error().startsWith(bad_case + ": /bodies"), qPrintable(app.last_error()));

    const QString bad_session = dir.filePath("bad.palpa");
    QFile g(bad_session);
    QVERIFY(g.open(QIODevice::WriteOnly));
    g.write("this is not a session");
    g.close();
    QVERIFY(!app.open_review(bad_session));
    QVERIFY2(app.last_error().startsWith(bad_session + ":"), qPrintable(app.last_error()));
    QCOMPARE(open_windows<palpa::ui::ReviewWindow>(), 0);
  }

 private:
  QTemporaryDir sessions_;
};

int main(int argc, char** argv) {
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  AppWindowsTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "app_windows_test.moc"
