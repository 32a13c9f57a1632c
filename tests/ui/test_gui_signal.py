#!/usr/bin/env python3
"""palpa under Xvfb ended every way but Finish: SIGTERM, SIGINT, SIGHUP, its window destroyed
under it (xdotool windowclose: XDestroyWindow without a close request) and the X server
killed. Each time the process ends within a couple of seconds and the session file is
complete (an End event, no -wal left beside it), ends "abandoned: REASON" (nobody finished
the attempt) and reads back with palpa-cli score.

Each test runs its own Xvfb (so that it can kill it).
Run: python3 tests/ui/test_gui_signal.py --gui build/release/app/gui/palpa --cli build/release/app/palpa-cli
"""
import argparse
import os
import shutil
import signal
import sqlite3
import subprocess
import sys
import tempfile
import time
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
from session_samples import sample_rows  # noqa: E402  (either session format)

GUI = CLI = None
QUICK = 2.0  # s: "ends at once", with room for a loaded 2-core machine


class Display:
    """An Xvfb of its own; DISPLAY for the children."""

    def __enter__(self):
        r, w = os.pipe()
        self.server = subprocess.Popen(["Xvfb", "-displayfd", str(w), "-screen", "0", "1280x1024x24", "-nolisten", "tcp"],
                                       pass_fds=(w,), stderr=subprocess.DEVNULL)
        os.close(w)
        with os.fdopen(r) as f:
            self.name = ":" + f.readline().strip()
        self.env = dict(os.environ, DISPLAY=self.name)
        return self

    def kill(self):
        if self.server.poll() is None:
            self.server.kill()
            self.server.wait(timeout=10)

    def __exit__(self, *exc):
        self.kill()


class EndedWithoutFinish(unittest.TestCase):
    def start(self, display, session):
        gui = subprocess.Popen([GUI, "--seed", "1", "--session", session], stderr=subprocess.PIPE, text=True,
                               env=display.env)
        line = gui.stderr.readline()
        while line and "recording the session" not in line:
            line = gui.stderr.readline()
        self.assertIn(session, line)
        time.sleep(1.5)  # some ticks recorded
        return gui

    def ended_quickly(self, gui, since):
        try:
            code = gui.wait(timeout=30)
        finally:
            if gui.poll() is None:
                gui.kill()
        took = time.monotonic() - since
        gui.stderr.close()
        self.assertLess(took, QUICK, f"palpa took {took:.1f} s to end")
        return code

    def check_abandoned(self, session, reason):
        self.assertFalse(os.path.exists(session + "-wal"))
        with sqlite3.connect(f"file:{session}?mode=ro", uri=True) as db:
            events = db.execute("SELECT kind, note FROM events ORDER BY id").fetchall()
            samples = len(sample_rows(db))
        self.assertEqual(events[0][0], "start")
        self.assertEqual(events[-1], ("end", "abandoned: " + reason))
        self.assertGreater(samples, 200)
        score = subprocess.run([CLI, "score", session], capture_output=True, text=True, timeout=60)
        self.assertEqual(score.returncode, 0, score.stderr)
        self.assertIn("ABANDONED", score.stdout)

    def run_and_stop(self, sig, name):
        with tempfile.TemporaryDirectory(prefix="palpa_signal_") as d, Display() as display:
            session = os.path.join(d, "stopped.palpa")
            gui = self.start(display, session)
            since = time.monotonic()
            gui.send_signal(sig)
            self.assertEqual(self.ended_quickly(gui, since), 0)
            self.check_abandoned(session, name)

    def test_sigterm_abandons_the_attempt(self):
        self.run_and_stop(signal.SIGTERM, "SIGTERM")

    def test_sigint_abandons_the_attempt(self):
        self.run_and_stop(signal.SIGINT, "SIGINT")

    def test_sighup_abandons_the_attempt(self):
        self.run_and_stop(signal.SIGHUP, "SIGHUP")

    @unittest.skipUnless(shutil.which("xdotool"), "xdotool not installed (scripts/install-deps.sh)")
    def test_destroyed_window_ends_palpa(self):
        with tempfile.TemporaryDirectory(prefix="palpa_destroy_") as d, Display() as display:
            session = os.path.join(d, "destroyed.palpa")
            gui = self.start(display, session)
            found = subprocess.run(["xdotool", "search", "--name", "Palpa: trainee"], capture_output=True, text=True,
                                   env=display.env, timeout=30)
            ids = found.stdout.split()
            self.assertTrue(ids, found.stderr)
            since = time.monotonic()
            subprocess.run(["xdotool", "windowclose", ids[0]], env=display.env, timeout=30, check=True)
            self.assertEqual(self.ended_quickly(gui, since), 0)
            self.check_abandoned(session, "window destroyed")

    def test_display_lost_ends_palpa(self):
        with tempfile.TemporaryDirectory(prefix="palpa_display_") as d, Display() as display:
            session = os.path.join(d, "lost.palpa")
            gui = self.start(display, session)
            since = time.monotonic()
            display.kill()
            self.assertNotEqual(self.ended_quickly(gui, since), 0)  # Qt ends it: exit 1
            self.check_abandoned(session, "display lost")


class DeviceOption(unittest.TestCase):
    def test_a_device_that_is_not_attached_is_one_line_and_exit_2(self):
        with tempfile.TemporaryDirectory(prefix="palpa_device_") as d:
            session = os.path.join(d, "never.palpa")
            res = subprocess.run([GUI, "--device", "spacemouse", "--session", session],
                                 capture_output=True, text=True, timeout=60)
            self.assertEqual(res.returncode, 2, res.stderr)
            lines = [l for l in res.stderr.splitlines() if l.startswith("palpa: error:")]
            self.assertEqual(len(lines), 1, res.stderr)
            self.assertIn("spacemouse", lines[0])
            self.assertFalse(os.path.exists(session))  # nothing recorded


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--gui", required=True)
    parser.add_argument("--cli", required=True)
    args, rest = parser.parse_known_args()
    GUI, CLI = os.path.abspath(args.gui), os.path.abspath(args.cli)
    unittest.main(argv=[sys.argv[0]] + rest)
