#pragma once
// Renders a window once at its current size and saves it (palpa --screenshot, docs, tests).
#include <QImage>
#include <QString>

class QWidget;

namespace palpa::ui {

/// Shows the window, lets it draw (GL included), and grabs it.
QImage grab_window(QWidget& window);
/// grab_window, saved as an image file (format from the extension); false on failure.
bool save_screenshot(QWidget& window, const QString& path);

}  // namespace palpa::ui
