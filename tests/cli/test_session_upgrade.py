#!/usr/bin/env python3
"""palpa-cli session upgrade: format-1 sessions (one row per tick) become format 2 (compact
blocks, docs/session-format.md) without losing anything. The truth: the committed format-1
sample sessions, scored before and after: the same gates, the score within 0.001, the same
samples and events; the originals untouched with --out; refusals named on one line.

Run: python3 tests/cli/test_session_upgrade.py --cli build/release/app/palpa-cli --repo .
"""
import argparse
import hashlib
import json
import os
import shutil
import sqlite3
import subprocess
import sys
import tempfile
import unittest

CLI = REPO = None
NAMES = ("expert", "sloppy", "light")
SCORE_TOLERANCE = 0.001  # docs/session-format.md, "Equivalence"


def run(*args):
    return subprocess.run([CLI] + list(args), capture_output=True, text=True, timeout=300)


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def version(path):
    db = sqlite3.connect("file:%s?mode=ro" % path, uri=True)
    meta = db.execute("select value from meta where key = 'format_version'").fetchone()[0]
    user = db.execute("pragma user_version").fetchone()[0]
    tables = sorted(n for (n,) in db.execute("select name from sqlite_schema where type = 'table'"))
    db.close()
    return meta, user, tables


def score(path):
    res = run("score", path, "--json")
    assert res.returncode == 0, res.stderr
    return json.loads(res.stdout)


class SessionUpgrade(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="palpa_upgrade_")
        cls.old = os.path.join(cls.tmp.name, "old")
        cls.new = os.path.join(cls.tmp.name, "new")
        os.makedirs(cls.old)
        os.makedirs(cls.new)
        cls.files = []
        for n in NAMES:
            path = os.path.join(cls.old, n + ".palpa")
            shutil.copyfile(os.path.join(REPO, "data", "sessions", n + ".palpa"), path)
            cls.files.append(path)
        cls.before = {f: digest(f) for f in cls.files}
        cls.res = run("session", "upgrade", *cls.files, "--out", cls.new)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_copies_are_format_2_and_the_originals_untouched(self):
        self.assertEqual(self.res.returncode, 0, self.res.stderr)
        self.assertEqual(len(self.res.stdout.splitlines()), 3, self.res.stdout)
        for f in self.files:
            self.assertEqual(digest(f), self.before[f])
            self.assertEqual(version(f), ("1", 1, ["events", "meta", "samples"]))
            copy = os.path.join(self.new, os.path.basename(f))
            self.assertEqual(version(copy), ("2", 2, ["events", "meta", "sample_blocks"]))
            # Format 2's promise: at most a quarter of format 1's bytes (measured: about a 45th).
            self.assertLess(os.path.getsize(copy) * 4, os.path.getsize(f))
        self.assertEqual(sorted(os.listdir(self.new)), sorted(n + ".palpa" for n in NAMES))  # no temporary left

    def test_copies_score_like_the_originals(self):
        for f in self.files:
            a, b = score(f), score(os.path.join(self.new, os.path.basename(f)))
            for key in ("passed", "safe", "complete", "samples", "false_positives", "sensitivity"):
                self.assertEqual(a[key], b[key], (f, key))
            self.assertEqual([t["found"] for t in a["tumours"]], [t["found"] for t in b["tumours"]], f)
            self.assertLessEqual(abs(a["score"] - b["score"]), SCORE_TOLERANCE, f)
            self.assertAlmostEqual(a["duration_s"], b["duration_s"], delta=1e-6)
            self.assertAlmostEqual(a["peak_force_n"], b["peak_force_n"], delta=1e-3)

    def test_in_place_replaces_the_file_and_a_second_run_leaves_it_alone(self):
        path = os.path.join(self.tmp.name, "inplace.palpa")
        shutil.copyfile(self.files[1], path)
        expected = score(path)
        res = run("session", "upgrade", path)
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertIn("format 2", res.stdout)
        self.assertEqual(version(path)[0], "2")
        self.assertEqual(score(path)["passed"], expected["passed"])
        self.assertFalse([n for n in os.listdir(self.tmp.name) if n.startswith(".")])  # no temporary left
        upgraded = digest(path)
        again = run("session", "upgrade", path)
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertEqual(again.stdout.strip(), path + ": already format 2")
        self.assertEqual(digest(path), upgraded)

    def test_a_session_open_in_another_process_is_refused(self):
        path = os.path.join(self.tmp.name, "live.palpa")
        shutil.copyfile(self.files[2], path)
        db = sqlite3.connect(path)  # this process holds it open in WAL mode, as a recorder does
        db.execute("pragma journal_mode=wal")
        db.execute("select count(*) from meta").fetchone()
        try:
            res = run("session", "upgrade", path)
        finally:
            db.close()
        self.assertEqual(res.returncode, 2)
        self.assertEqual(res.stderr.strip(), "palpa-cli: error: %s: being recorded or read by another process "
                         "(pid %d); upgrade it once it is finished" % (path, os.getpid()))
        self.assertEqual(version(path)[0], "1")

    def test_bad_inputs_are_one_line_each_and_the_others_still_upgraded(self):
        bad = os.path.join(self.tmp.name, "bad.palpa")
        with open(bad, "w") as f:
            f.write("not a session")
        good = os.path.join(self.tmp.name, "good.palpa")
        shutil.copyfile(self.files[1], good)
        with open(good + "-wal", "wb") as f:  # a -wal beside it: in place would apply it to the new file
            f.write(b"\0" * 32)
        res = run("session", "upgrade", bad, good)
        self.assertEqual(res.returncode, 2)
        lines = res.stderr.splitlines()
        self.assertEqual(len(lines), 2, res.stderr)
        self.assertIn(bad + ": file: not a Palpa session", lines[0])
        self.assertIn(good + ": has a -wal beside it", lines[1])
        os.remove(good + "-wal")
        out = os.path.join(self.tmp.name, "out")
        os.makedirs(out)
        shutil.copyfile(self.files[1], os.path.join(out, "good.palpa"))
        res = run("session", "upgrade", good, "--out", out)
        self.assertEqual(res.returncode, 2)
        self.assertIn("exists; upgrade never replaces a file in --out", res.stderr)
        res = run("session", "upgrade", good, "--out", bad)
        self.assertEqual(res.returncode, 2)
        self.assertIn("--out %s: not a folder" % bad, res.stderr)

    def test_help_names_the_command(self):
        res = run("session", "--help")
        self.assertEqual(res.returncode, 0)
        self.assertIn("upgrade", res.stdout)


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--repo", required=True)
    args, rest = ap.parse_known_args()
    CLI, REPO = os.path.abspath(args.cli), os.path.abspath(args.repo)
    unittest.main(argv=[sys.argv[0]] + rest)
