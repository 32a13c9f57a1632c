#!/usr/bin/env python3
"""palpa-cli exercise, end to end: a scripted trainee palpates the default case, the
session is recorded and scored.

Run: python3 tests/cli/test_exercise_cli.py --cli build/release/app/palpa-cli --repo .

The truths: each style fails (or passes) the gates it is built to (docs/scoring.md), the
session file holds exactly what the exercise did (read back with Python's own sqlite3),
the same seed gives the same samples, and bad input is refused with one line.
"""
import argparse
import json
import math
import os
import sqlite3
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
from session_samples import sample_rows  # noqa: E402  (either session format)

CLI = None
REPO = None
TIMEOUT = 300


def run(args, timeout=TIMEOUT):
    return subprocess.run([CLI] + args, capture_output=True, text=True, timeout=timeout)


class Exercise(unittest.TestCase):
    results = {}
    tmp = None

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="palpa_exercise_")
        cls.case = os.path.join(REPO, "data", "cases", "default.json")
        for style in ("expert", "sloppy", "light"):
            out = os.path.join(cls.tmp.name, style + ".palpa")
            res = run(["exercise", cls.case, "--trainee", "t-" + style, "--style", style, "--seed", "3",
                       "--out", out, "--json"])
            cls.results[style] = (res, out)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def score(self, style):
        res, _ = self.results[style]
        self.assertEqual(res.returncode, 0, res.stderr)
        return json.loads(res.stdout)

    def gates(self, style):
        return {g["name"]: g["passed"] for g in self.score(style)["gates"]}

    def test_score_json_has_the_promised_fields(self):
        s = self.score("expert")
        for key, kind in (("passed", bool), ("sensitivity", (int, float)), ("false_positives", int),
                          ("localization_error_mm", list), ("coverage", (int, float)),
                          ("deep_coverage", (int, float)), ("duration_s", (int, float)),
                          ("peak_force_n", (int, float))):
            self.assertIn(key, s)
            self.assertIsInstance(s[key], kind, key)
        for key in ("sensitivity", "coverage", "deep_coverage"):
            self.assertGreaterEqual(s[key], 0.0)
            self.assertLessEqual(s[key], 1.0)

    def test_expert_passes_every_gate(self):
        s = self.score("expert")
        self.assertTrue(s["passed"], json.dumps(s["gates"], indent=1))
        self.assertEqual(s["sensitivity"], 1.0)
        self.assertEqual(s["false_positives"], 0)
        self.assertEqual(len(s["localization_error_mm"]), 1)
        self.assertLess(s["localization_error_mm"][0], 16.0)  # within radius (6 mm) + 10 mm

    def test_sloppy_fails_for_gaps_and_wrong_marks(self):
        s = self.score("sloppy")
        g = self.gates("sloppy")
        self.assertFalse(s["passed"])
        self.assertFalse(g["coverage"])
        self.assertLess(s["coverage"], 0.9)
        self.assertGreaterEqual(s["false_positives"], 2)
        self.assertFalse(g["false_positives"])

    def test_light_fails_for_missing_the_deep_tumour(self):
        s = self.score("light")
        g = self.gates("light")
        self.assertFalse(s["passed"])
        self.assertEqual(s["sensitivity"], 0.0)
        self.assertFalse(g["sensitivity"])
        self.assertFalse(g["deep_coverage"])
        self.assertTrue(g["coverage"], "light covers the region; it only presses too lightly")
        self.assertTrue(g["false_positives"])

    def test_session_file_holds_the_exercise(self):
        _, out = self.results["expert"]
        db = sqlite3.connect("file:%s?mode=ro" % out, uri=True)
        meta = dict(db.execute("select key, value from meta"))
        self.assertEqual(meta["format"], "palpa-session")
        self.assertEqual(meta["trainee"], "t-expert")
        self.assertEqual(meta["seed"], "3")
        self.assertEqual(json.loads(meta["extra"])["exercise_style"], "expert")
        case = json.loads(meta["case"])
        self.assertEqual(len(case["tumors"]), 1)
        kinds = [k for (k,) in db.execute("select kind from events order by t, id")]
        self.assertEqual(kinds[0], "start")
        self.assertEqual(kinds[-1], "end")
        rows = sample_rows(db)
        (n, t0, t1) = (len(rows), rows[0][1], rows[-1][1])
        self.assertEqual(t0, 0.0)
        self.assertEqual(n, round(t1 * 1000) + 1)  # one sample per millisecond, none missing
        (end_t,) = db.execute("select t from events where kind = 'end'").fetchone()
        self.assertEqual(end_t, t1)
        s = self.score("expert")
        self.assertAlmostEqual(s["duration_s"], t1, places=6)
        peak = max(math.sqrt(fx * fx + fy * fy + fz * fz) for (_, _, _, _, _, fx, fy, fz, *rest) in rows)
        self.assertAlmostEqual(s["peak_force_n"], peak, places=9)
        db.close()

    def test_placed_tumour_is_the_ground_truth_and_differs_by_seed(self):
        _, out = self.results["light"]
        other = os.path.join(self.tmp.name, "light-seed4.palpa")
        res = run(["exercise", self.case, "--trainee", "x", "--style", "light", "--seed", "4", "--out", other])
        self.assertEqual(res.returncode, 0, res.stderr)

        def centre(path):
            db = sqlite3.connect("file:%s?mode=ro" % path, uri=True)
            (doc,) = db.execute("select value from meta where key = 'case'").fetchone()
            db.close()
            return json.loads(doc)["tumors"][0]["center"]
        self.assertNotEqual(centre(out), centre(other))

    def test_same_seed_same_samples(self):
        _, out = self.results["sloppy"]
        again = os.path.join(self.tmp.name, "sloppy-again.palpa")
        res = run(["exercise", self.case, "--trainee", "t-sloppy", "--style", "sloppy", "--seed", "3",
                   "--out", again])
        self.assertEqual(res.returncode, 0, res.stderr)
        a = sample_rows(sqlite3.connect(out))
        b = sample_rows(sqlite3.connect(again))
        self.assertEqual(a, b)
        ev = "select t, kind, mark, x, y, z from events order by t, id"
        self.assertEqual(sqlite3.connect(out).execute(ev).fetchall(), sqlite3.connect(again).execute(ev).fetchall())

    def test_score_card_on_stdout_without_json(self):
        out = os.path.join(self.tmp.name, "card.palpa")
        res = run(["exercise", self.case, "--trainee", "c", "--style", "sloppy", "--seed", "1", "--out", out])
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertIn("NOT PASSED", res.stdout)
        self.assertIn("FAIL", res.stdout)
        self.assertIn("seed 1", res.stderr)

    def test_report_folder_gets_the_session_report(self):
        out = os.path.join(self.tmp.name, "reported.palpa")
        folder = os.path.join(self.tmp.name, "reports")
        res = run(["exercise", self.case, "--trainee", "r", "--style", "light", "--seed", "2", "--out", out,
                   "--report", folder])
        self.assertEqual(res.returncode, 0, res.stderr)
        for suffix in (".html", ".json", ".xapi.json", ".csv"):
            self.assertTrue(os.path.getsize(os.path.join(folder, "reported" + suffix)) > 0, suffix)
        with open(os.path.join(folder, "reported.html")) as fh:
            self.assertEqual(fh.read().count("data:image/png;base64,"), 3)
        with open(os.path.join(folder, "reported.xapi.json")) as fh:
            self.assertTrue(json.load(fh)["verb"]["id"].endswith("/failed"))

    def test_existing_session_is_never_overwritten(self):
        _, out = self.results["expert"]
        before = os.path.getsize(out), os.path.getmtime(out)
        res = run(["exercise", self.case, "--trainee", "x", "--out", out, "--seed", "1"])
        self.assertEqual(res.returncode, 2)
        self.assertEqual(len(res.stderr.strip().splitlines()), 1, res.stderr)
        self.assertIn(out, res.stderr)
        self.assertIn("exists", res.stderr)
        self.assertEqual((os.path.getsize(out), os.path.getmtime(out)), before)

    def test_bad_input_is_one_line_and_exit_2(self):
        out = os.path.join(self.tmp.name, "never.palpa")
        cases = [
            (["exercise", self.case, "--trainee", "x", "--style", "lazy", "--out", out], "--style"),
            (["exercise", os.path.join(self.tmp.name, "missing.json"), "--trainee", "x", "--out", out], "missing.json"),
            (["exercise", self.case, "--out", out], "--trainee"),
            (["exercise", self.case, "--trainee", "", "--out", out], "--trainee"),
            (["exercise", self.case, "--trainee", "x", "--seed", "-1", "--out", out], "--seed"),
            (["exercise", self.case, "--trainee", "x", "--out", os.path.join(self.tmp.name, "no", "dir", "s.palpa")],
             "s.palpa"),
        ]
        for args, needle in cases:
            res = run(args)
            self.assertEqual(res.returncode, 2, (args, res.stderr))
            self.assertEqual(len(res.stderr.strip().splitlines()), 1, (args, res.stderr))
            self.assertIn(needle, res.stderr)
            self.assertTrue(res.stderr.startswith("palpa-cli: error: "), res.stderr)
        self.assertFalse(os.path.exists(out))

    def test_help(self):
        res = run(["exercise", "--help"])
        self.assertEqual(res.returncode, 0)
        for option in ("--trainee", "--style", "--seed", "--out", "--json", "--report"):
            self.assertIn(option, res.stdout)


def main():
    global CLI, REPO
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--repo", required=True)
    args, rest = ap.parse_known_args()
    CLI, REPO = os.path.abspath(args.cli), os.path.abspath(args.repo)
    prog = unittest.main(argv=[sys.argv[0]] + rest, exit=False, verbosity=2)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
