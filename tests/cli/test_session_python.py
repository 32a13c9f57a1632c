#!/usr/bin/env python3
"""A finished session is readable with nothing but Python's standard library
(docs/session-format.md): pragmas, meta, events and marks with sqlite3; the ticks of format
2's blocks with the documentation's own decoder (zlib, struct), which gives every tick bit
for bit as Palpa's reader does, within half a unit of what was written, and format 1's rows
alike; and the documentation's example runs as printed."""
import argparse
import json
import os
import re
import shutil
import sqlite3
import subprocess
import sys
import tempfile
import unittest

ARGS = None


def documented_example():
    with open(os.path.join(ARGS.repo, "docs", "session-format.md"), encoding="utf-8") as f:
        doc = f.read()
    found = re.search(r"<!-- python-example-begin -->\s*```python\n(.*?)```\s*<!-- python-example-end -->", doc, re.S)
    assert found, "the example's markers are missing from docs/session-format.md"
    return found.group(1)


def documented_decoder():
    """The example's definitions (decode_block, ticks), without its reading of s.palpa."""
    code = documented_example()
    names = {}
    exec(code[:code.index("db = sqlite3.connect")], names)
    return names


def cpp_ticks(path):
    """Palpa's reader's ticks of `path` (session_example --dump), as (tick, t, ..., fault) tuples."""
    out = subprocess.run([ARGS.example, "--dump", path], check=True, capture_output=True, text=True).stdout
    return [tuple(None if v == "None" else float(v) for v in line.split()) for line in out.splitlines()]


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
        self.assertEqual(self.db.execute("pragma user_version").fetchone()[0], 2)
        self.assertEqual(self.db.execute("pragma journal_mode").fetchone()[0], "delete")
        self.assertFalse(os.path.exists(self.path + "-wal"))
        self.assertFalse(os.path.exists(self.path + "-shm"))

    def test_meta(self):
        meta = dict(self.db.execute("select key, value from meta"))
        self.assertEqual(meta["format"], "palpa-session")
        self.assertEqual(meta["format_version"], "2")
        self.assertEqual(meta["trainee"], "python-reader")
        self.assertEqual(float(meta["rate_hz"]), 1000.0)
        self.assertEqual(int(meta["seed"]), 42)
        self.assertEqual(json.loads(meta["extra"]), {"style": "free"})
        case = json.loads(meta["case"])
        self.assertEqual(case["format"], "palpa-case")
        self.assertEqual(len(case["bodies"]), 1)
        self.assertIn("ended_at", meta)

    def test_the_documented_decoder_reads_the_ticks_as_written(self):
        decoder = documented_decoder()
        ticks = decoder["ticks"](self.db)
        self.assertEqual(len(ticks), 100)
        # Written (session_example): t = k/1000, x = k/8, y = -k/16, z = 0.03, force (0, 0, k/4),
        # in contact when k is odd with u = k/1024, v = 0.5, depth = k/65536; button 1 at k = 50.
        # Whole microseconds, micrometres and millinewtons read back exactly; u and depth
        # within half their unit (1e-6, 1 um).
        for k, s in enumerate(ticks):
            contact = k % 2 == 1
            exact = {"tick": k, "t": k / 1000.0, "x": k / 8.0, "y": -k / 16.0, "z": 0.03, "fx": 0.0, "fy": 0.0,
                     "fz": k / 4.0, "body": 0 if contact else None, "v": 0.5 if contact else None,
                     "buttons": 1 if k == 50 else 0, "overrun": 0, "fault": 0}
            for name, value in exact.items():
                self.assertEqual(s[name], value, "tick %d %s" % (k, name))
            if contact:
                self.assertLessEqual(abs(s["u"] - k / 1024.0), 0.5e-6)
                self.assertLessEqual(abs(s["depth"] - k / 65536.0), 0.5e-6)
            else:
                self.assertEqual((s["u"], s["depth"]), (None, None))

    def test_the_documented_decoder_agrees_with_palpas_reader_bit_for_bit(self):
        decoder = documented_decoder()
        mine = [tuple(s[name] for name in decoder["COLUMNS"]) for s in decoder["ticks"](self.db)]
        self.assertEqual(mine, cpp_ticks(self.path))

    def test_the_documented_decoder_reads_a_recorded_session_in_both_formats(self):
        # A real recording (the sloppy sample session, format 1) and its upgraded copy.
        old = os.path.join(self.tmp.name, "sloppy.palpa")
        shutil.copyfile(os.path.join(ARGS.repo, "data", "sessions", "sloppy.palpa"), old)
        out = os.path.join(self.tmp.name, "v2")
        os.makedirs(out, exist_ok=True)
        subprocess.run([ARGS.cli, "session", "upgrade", old, "--out", out], check=True, capture_output=True)
        new = os.path.join(out, "sloppy.palpa")
        decoder = documented_decoder()
        rows = decoder["ticks"](sqlite3.connect("file:%s?mode=ro" % old, uri=True))
        blocks = decoder["ticks"](sqlite3.connect("file:%s?mode=ro" % new, uri=True))
        self.assertEqual(len(blocks), len(rows))
        half = {"t": 0.5e-6, "x": 0.5e-6, "y": 0.5e-6, "z": 0.5e-6, "fx": 0.5e-3, "fy": 0.5e-3, "fz": 0.5e-3,
                "u": 0.5e-6, "v": 0.5e-6, "depth": 0.5e-6}
        for a, b in zip(rows, blocks):
            for name in decoder["COLUMNS"]:
                if name in half and a[name] is not None:
                    self.assertLessEqual(abs(a[name] - b[name]), half[name] * (1 + 1e-9), (a["tick"], name))
                else:
                    self.assertEqual(a[name], b[name], (a["tick"], name))
        self.assertEqual([tuple(s[n] for n in decoder["COLUMNS"]) for s in blocks], cpp_ticks(new))
        self.assertLess(os.path.getsize(new) * 4, os.path.getsize(old))

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
        # The snippet opens s.palpa in the current folder: run it where the session is.
        run = subprocess.run([sys.executable, "-c", documented_example()], cwd=self.tmp.name,
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
    parser.add_argument("--cli", required=True)
    ARGS, rest = parser.parse_known_args()
    unittest.main(argv=[sys.argv[0]] + rest)
