#!/usr/bin/env python3
"""A finished session is readable with nothing but Python's standard sqlite3 module
(docs/session-format.md): pragmas, meta, samples to the bit, events and marks; and the
documentation's own Python example runs as printed."""
import argparse
import json
import os
import re
import sqlite3
import subprocess
import sys
import tempfile
import unittest

ARGS = None


class SessionFromPython(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.path = os.path.join(cls.tmp.name, "s.palpa")
        case = os.path.join(ARGS.repo, "data", "cases", "flat-5x5.json")
        subprocess.run([ARGS.example, cls.path, case], check=True)
        cls.db = sqlite3.connect("file:" + cls.path + "?mode=ro", uri=True)

    @classmethod
    def tearDownClass(cls):
        cls.db.close()
        cls.tmp.cleanup()

    def test_identity_and_a_single_file(self):
        self.assertEqual(self.db.execute("pragma application_id").fetchone()[0], 0x50414C50)
        self.assertEqual(self.db.execute("pragma user_version").fetchone()[0], 1)
        self.assertEqual(self.db.execute("pragma journal_mode").fetchone()[0], "delete")
        self.assertFalse(os.path.exists(self.path + "-wal"))
        self.assertFalse(os.path.exists(self.path + "-shm"))

    def test_meta(self):
        meta = dict(self.db.execute("select key, value from meta"))
        self.assertEqual(meta["format"], "palpa-session")
        self.assertEqual(meta["format_version"], "1")
        self.assertEqual(meta["trainee"], "python-reader")
        self.assertEqual(float(meta["rate_hz"]), 1000.0)
        self.assertEqual(int(meta["seed"]), 42)
        self.assertEqual(json.loads(meta["extra"]), {"style": "free"})
        case = json.loads(meta["case"])
        self.assertEqual(case["format"], "palpa-case")
        self.assertEqual(len(case["bodies"]), 1)
        self.assertIn("ended_at", meta)

    def test_samples_are_exact(self):
        rows = self.db.execute(
            "select tick, t, x, y, z, fx, fy, fz, body, u, v, depth, buttons, overrun, fault "
            "from samples order by tick").fetchall()
        self.assertEqual(len(rows), 100)
        for k, row in enumerate(rows):
            contact = k % 2 == 1
            expected = (k, k / 1000.0, k / 8.0, -k / 16.0, 0.03, 0.0, 0.0, k / 4.0,
                        0 if contact else None, k / 1024.0 if contact else None,
                        0.5 if contact else None, k / 65536.0 if contact else None,
                        1 if k == 50 else 0, 0, 0)
            self.assertEqual(row, expected, "tick %d" % k)
        in_contact = self.db.execute("select count(*) from samples where body is not null").fetchone()[0]
        self.assertEqual(in_contact, 50)

    def test_events_and_standing_marks(self):
        kinds = [k for (k,) in self.db.execute("select kind from events order by t, id")]
        self.assertEqual(kinds, ["start", "mark", "mark", "unmark", "end"])
        marks = {}
        for kind, mark, x, y, z in self.db.execute(
                "select kind, mark, x, y, z from events where kind in ('mark', 'unmark') order by t, id"):
            marks.pop(mark, None)
            if kind == "mark":
                marks[mark] = (x, y, z)
        self.assertEqual(marks, {2: (0.04, 0.05, 0.06)})


    def test_the_documented_example_runs(self):
        with open(os.path.join(ARGS.repo, "docs", "session-format.md"), encoding="utf-8") as f:
            doc = f.read()
        found = re.search(r"<!-- python-example-begin -->\s*```python\n(.*?)```\s*<!-- python-example-end -->",
                          doc, re.S)
        self.assertIsNotNone(found, "the example's markers are missing from docs/session-format.md")
        # The snippet opens s.palpa in the current folder: run it where the session is.
        run = subprocess.run([sys.executable, "-c", found.group(1)], cwd=self.tmp.name,
                             capture_output=True, text=True, timeout=60)
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertEqual(run.stdout.splitlines(), [
            "python-reader %s 1 bodies" % self.db.execute(
                "select value from meta where key = 'started_at'").fetchone()[0],
            "50 ticks in contact, peak normal force 24.75 N",
            "standing marks: {2: (0.04, 0.05, 0.06)}",
            "complete: True",
        ])


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--example", required=True)
    parser.add_argument("--repo", required=True)
    ARGS, rest = parser.parse_known_args()
    unittest.main(argv=[sys.argv[0]] + rest)
