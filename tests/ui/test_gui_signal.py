#!/usr/bin/env python3
"""palpa under Xvfb, stopped by SIGTERM (or Ctrl+C) mid-exercise: it closes its window the
normal way, so the session file is finished (an End event, no -wal left beside it) and
reads back with palpa-cli score.

Run: xvfb-run -a python3 tests/ui/test_gui_signal.py --gui build/release/app/gui/palpa --cli build/release/app/palpa-cli
"""
import argparse
import os
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


class StopBySignal(unittest.TestCase):
    def run_and_stop(self, sig):
        with tempfile.TemporaryDirectory(prefix="palpa_signal_") as d:
            session = os.path.join(d, "stopped.palpa")
            gui = subprocess.Popen([GUI, "--seed", "1", "--session", session], stderr=subprocess.PIPE, text=True)
            line = gui.stderr.readline()
            while line and "recording the session" not in line:
                line = gui.stderr.readline()
            self.assertIn(session, line)
            time.sleep(1.0)  # some ticks recorded
            gui.send_signal(sig)
            code = gui.wait(timeout=60)
            gui.stderr.close()
            self.assertEqual(code, 0)
            self.assertFalse(os.path.exists(session + "-wal"))
            with sqlite3.connect(f"file:{session}?mode=ro", uri=True) as db:
                kinds = [k for (k,) in db.execute("SELECT kind FROM events ORDER BY id")]
                samples = len(sample_rows(db))
            self.assertEqual(kinds[0], "start")
            self.assertEqual(kinds[-1], "end")
            self.assertGreater(samples, 200)
            score = subprocess.run([CLI, "score", session], capture_output=True, text=True, timeout=60)
            self.assertEqual(score.returncode, 0, score.stderr)

    def test_sigterm_finishes_the_session(self):
        self.run_and_stop(signal.SIGTERM)

    def test_sigint_finishes_the_session(self):
        self.run_and_stop(signal.SIGINT)


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
