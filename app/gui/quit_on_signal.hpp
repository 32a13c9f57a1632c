#pragma once
// How palpa ends when it is not closed the usual way (docs/user-guide.md, "Closing"):
//
// - SIGINT, SIGTERM and SIGHUP (Ctrl+C in the terminal, `kill`, the terminal or the login
//   going away) close every window without a question. A trainee's unfinished attempt is
//   abandoned with the signal's name ("abandoned: SIGHUP"): nobody finished it, so it is no
//   exam. A window may refuse to close (the instructor's unsaved-changes prompt,
//   cancelled): then palpa stays, and a second signal quits anyway. A signal handler may do
//   almost nothing: it writes the signal's number to a pipe that the event loop watches
//   (the self-pipe trick).
// - A top-level window destroyed under palpa (xdotool windowclose, a crashed window
//   manager: XDestroyWindow without a close request): that window closes, an attempt in it
//   abandoned ("abandoned: window destroyed"); with its last window palpa ends.
// - The display going away (the X server killed): Qt ends the process at once (exit 1);
//   on the way out every running attempt is abandoned ("abandoned: display lost"), so the
//   session file is complete and says why it ended.
namespace palpa::gui {

/// Call once, after the QApplication exists.
void quit_on_signals();

}  // namespace palpa::gui
