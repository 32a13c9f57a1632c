#include "gui_device.hpp"

#include <chrono>
#include <cstdio>
#include <future>

#include <QApplication>
#include <QMetaObject>
#include <QProgressDialog>

#include "palpa/device/registry.hpp"

namespace palpa::gui {

std::shared_ptr<engine::Device> open_chosen_device(const DeviceChoice& choice,
                                                   std::function<void(const std::string&)> progress) {
  if (choice.id.empty() || choice.id == "virtual") return nullptr;
  device::OpenOptions options;
  if (!choice.falcon_firmware.empty()) options.falcon.firmware = choice.falcon_firmware;
  options.progress = progress ? std::move(progress)
                              : [](const std::string& line) { std::fprintf(stderr, "palpa: %s\n", line.c_str()); };
  return device::open_device(choice.id, options);
}

std::shared_ptr<engine::Device> open_chosen_device_with_progress(const DeviceChoice& choice, QWidget* parent) {
  if (choice.id.empty() || choice.id == "virtual") return nullptr;
  QProgressDialog dialog(QObject::tr("Opening %1...").arg(QString::fromStdString(choice.id)), QString(), 0, 0, parent);
  dialog.setWindowTitle(QObject::tr("Palpa: device"));
  dialog.setWindowModality(Qt::WindowModal);
  dialog.setMinimumDuration(300);  // a device that opens at once shows no dialog
  auto* label_target = &dialog;
  auto opening = std::async(std::launch::async, [&choice, label_target] {
    return open_chosen_device(choice, [label_target](const std::string& line) {
      // From the opening thread: hand the line to the GUI thread.
      QMetaObject::invokeMethod(
          label_target, [label_target, text = QString::fromStdString(line)] { label_target->setLabelText(text); },
          Qt::QueuedConnection);
    });
  });
  while (opening.wait_for(std::chrono::milliseconds(20)) != std::future_status::ready) {
    QApplication::processEvents(QEventLoop::AllEvents, 20);
  }
  // Lines still queued for the dialog are dropped with it (get() rethrows the device's error).
  QApplication::removePostedEvents(&dialog);
  return opening.get();
}

}  // namespace palpa::gui
