#pragma once
// SIGINT and SIGTERM (Ctrl+C in the terminal, a logout, `kill`) close every window the
// normal way, so a trainee's session is finished and its file left complete instead of
// cut off mid-write. A window may refuse to close (the instructor's unsaved-changes
// prompt, cancelled): then palpa stays, and a second signal quits anyway. A signal handler may do almost nothing: it writes one byte to a pipe
// that the event loop watches (the self-pipe trick).
namespace palpa::gui {

/// Call once, after the QApplication exists.
void quit_on_signals();

}  // namespace palpa::gui
