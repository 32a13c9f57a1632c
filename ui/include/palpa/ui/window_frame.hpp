#pragma once
// What every Palpa window and dialog does with its frame: it opens at a size that fits the
// screen it opens on, title bar and desktop panel included (a 1280 x 800 laptop leaves
// about 1280 x 730 for the frame), and Ctrl+W closes it from its own keys, also on a
// display without a window manager, where no window is active and no shortcut fires.
#include <QSize>

class QRect;
class QWidget;
class QWindow;

namespace palpa::ui {

/// The size a window opens at when it would like `preferred`: at most kLargestFrame with
/// its title bar, and at most what the screen offers (`available`: the screen's available
/// geometry) less the frame's decorations (`decoration`: the title bar and borders).
QSize fitted_size(QSize preferred, const QRect& available, QSize decoration);

/// The frame every window fits in: 1280 x 800 less a desktop panel (40 px) and a little.
inline constexpr QSize kLargestFrame{1280, 730};
/// Assumed title bar and borders before a window manager has framed the window.
inline constexpr QSize kDecoration{8, 34};

/// Resizes `window` (a top-level widget) to fitted_size on the screen it opens on: its
/// parent's screen for a dialog, else the screen under it.
void fit_to_screen(QWidget& window, QSize preferred);

/// Makes `window` (shown) the active window, raised, with the keyboard focus on `focus` (or
/// where it last was): without a window manager nothing else does, and a window opened
/// from another would take no keys until clicked.
void take_keys(QWidget& window, QWidget* focus = nullptr);

/// Ctrl+W closes `window`: a shortcut while it is active, and its key events (and those of
/// `view`, a VTK view's own native window, which are not the window's) when it is not.
void close_on_ctrl_w(QWidget& window, QWindow* view = nullptr);

}  // namespace palpa::ui
