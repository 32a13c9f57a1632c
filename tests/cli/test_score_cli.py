#!/usr/bin/env python3
"""palpa-cli score, end to end.

Run: python3 tests/cli/test_score_cli.py --cli build/release/app/palpa-cli --repo . \
         --make-sessions build/release/tests/make_test_sessions

make_test_sessions writes sessions with known content on data/cases/flat-5x5.json with one
tumour of radius 6 mm at (10, 10, 0) mm: alice-1 marks it 0.5 mm away (found, no false
positive), alice-0 marks only a point 57 mm away (nothing found, one false positive).
"""
import argparse
import base64
import csv
import io
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

CLI = None
REPO = None
MAKE_SESSIONS = None
TIMEOUT = 120
SESSIONS = None  # folder of the generated sessions (made once)


def run(args, timeout=TIMEOUT):
    return subprocess.run([CLI] + args, capture_output=True, text=True, timeout=timeout)


def setUpModule():
    global SESSIONS, _TMP
    _TMP = tempfile.TemporaryDirectory(prefix="palpa_score_sessions_")
    SESSIONS = _TMP.name
    subprocess.run([MAKE_SESSIONS, SESSIONS, os.path.join(REPO, "data", "cases", "flat-5x5.json")],
                   check=True, timeout=TIMEOUT)


def tearDownModule():
    _TMP.cleanup()


class Score(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="palpa_score_")

    def tearDown(self):
        self.tmp.cleanup()

    def score_json(self, name):
        res = run(["score", os.path.join(SESSIONS, name), "--json"])
        self.assertEqual(res.returncode, 0, res.stderr)
        return json.loads(res.stdout)

    def test_json_has_the_metrics_with_their_types(self):
        j = self.score_json("alice-1.palpa")
        for key, kind in (("passed", bool), ("sensitivity", (int, float)), ("false_positives", int),
                          ("localization_error_mm", list), ("coverage", (int, float)),
                          ("deep_coverage", (int, float)), ("duration_s", (int, float)),
                          ("peak_force_n", (int, float))):
            with self.subTest(key=key):
                self.assertIn(key, j)
                self.assertIsInstance(j[key], kind)
        self.assertNotIsInstance(j["false_positives"], bool)
        for key in ("coverage", "deep_coverage", "sensitivity"):
            self.assertGreaterEqual(j[key], 0.0)
            self.assertLessEqual(j[key], 1.0)
        s = j["session"]
        self.assertEqual(s["id"], "a1a1a1a1a1a1a1a1")
        self.assertEqual(s["trainee"], "alice")
        self.assertEqual(s["case"], "Flat 5x5: plane skeleton, polynomial radius")
        self.assertEqual(s["started_at"], "2026-11-20T10:00:00Z")
        self.assertTrue(s["file"].endswith("alice-1.palpa"))

    def test_known_marks_give_known_sensitivity_and_false_positives(self):
        good = self.score_json("alice-1.palpa")
        self.assertEqual(good["sensitivity"], 1.0)
        self.assertEqual(good["false_positives"], 0)
        self.assertEqual(len(good["localization_error_mm"]), 1)
        # The mark is 0.5 mm from the centre in x, 0.2 mm in y (over the top contour: at least that).
        self.assertGreaterEqual(good["localization_error_mm"][0], 0.5)
        self.assertLess(good["localization_error_mm"][0], 3.0)
        # 200 N/m times the deepest press: 0.6 of the thickness 2 r, r <= 20 mm.
        self.assertLessEqual(good["peak_force_n"], 200 * 0.6 * 0.04 + 1e-9)
        self.assertGreater(good["peak_force_n"], 200 * 0.6 * 0.04 * 0.9)
        bad = self.score_json("alice-0.palpa")
        self.assertEqual(bad["sensitivity"], 0.0)
        self.assertEqual(bad["false_positives"], 1)
        self.assertEqual(bad["localization_error_mm"], [])
        self.assertFalse(bad["passed"])
        self.assertLess(bad["coverage"], good["coverage"])

    def test_text_card_without_json(self):
        res = run(["score", os.path.join(SESSIONS, "alice-0.palpa")])
        self.assertEqual(res.returncode, 0, res.stderr)  # scored, even though failed
        self.assertTrue(res.stdout.strip())
        with self.assertRaises(ValueError):
            json.loads(res.stdout)

    def test_report_files_exist_and_the_html_embeds_images(self):
        out = os.path.join(self.tmp.name, "rep")
        res = run(["score", os.path.join(SESSIONS, "alice-1.palpa"), "--report", out])
        self.assertEqual(res.returncode, 0, res.stderr)
        for ext in (".html", ".json", ".xapi.json", ".csv"):
            self.assertTrue(os.path.isfile(os.path.join(out, "alice-1" + ext)), ext)
        with open(os.path.join(out, "alice-1.html")) as fh:
            html = fh.read()
        prefix = 'src="data:image/png;base64,'
        parts = html.split(prefix)[1:]
        self.assertEqual(len(parts), 3)
        for part in parts:
            png = base64.b64decode(part.split('"', 1)[0])
            self.assertEqual(png[:8], b"\x89PNG\r\n\x1a\n")
            self.assertGreater(len(png), 1000)
        self.assertNotIn("http://", html.replace("http://adlnet", ""))
        with open(os.path.join(out, "alice-1.json")) as fh:
            report = json.load(fh)
        with open(os.path.join(out, "alice-1.xapi.json")) as fh:
            xapi = json.load(fh)
        verb = "passed" if report["passed"] else "failed"
        self.assertEqual(xapi["verb"]["id"], "http://adlnet.gov/expapi/verbs/" + verb)
        self.assertEqual(xapi["actor"]["account"]["name"], "alice")
        self.assertAlmostEqual(xapi["result"]["score"]["scaled"], report["score"])
        self.assertEqual(xapi["result"]["success"], report["passed"])
        self.assertEqual(xapi["timestamp"], "2026-11-20T10:00:00Z")
        self.assertTrue(xapi["result"]["duration"].startswith("PT"))
        with open(os.path.join(out, "alice-1.csv")) as fh:
            rows = list(csv.DictReader(fh))
        self.assertEqual(len(rows), 1)
        self.assertEqual(rows[0]["session_id"], "a1a1a1a1a1a1a1a1")
        self.assertEqual(rows[0]["passed"], "1" if report["passed"] else "0")
        # CSV numbers are rounded to their unit (shares to 0.001, the score out of 100 to 0.1);
        # the JSON keeps full precision. Python's % rounds from the exact binary value too.
        self.assertEqual(rows[0]["coverage"], "%.3f" % report["coverage"])
        self.assertEqual(rows[0]["score"], "%.3f" % report["score"])
        self.assertEqual(rows[0]["score_100"], "%.1f" % (100 * report["score"]))

    def test_the_score_card_gives_the_score_out_of_100(self):
        path = os.path.join(SESSIONS, "alice-1.palpa")
        report = json.loads(run(["score", path, "--json"]).stdout)
        res = run(["score", path])
        self.assertEqual(res.returncode, 0, res.stderr)
        first = res.stdout.splitlines()[0]
        self.assertTrue(first.endswith("  score %.1f / 100" % (100 * report["score"])), first)

    def test_incomplete_session_is_scored_and_said_to_be_incomplete(self):
        out = os.path.join(self.tmp.name, "rep")
        res = run(["score", os.path.join(SESSIONS, "alice-2.palpa"), "--report", out, "--json"])
        self.assertEqual(res.returncode, 0, res.stderr)
        with open(os.path.join(out, "alice-2.csv")) as fh:
            row = next(csv.DictReader(fh))
        self.assertEqual(row["complete"], "0")
        with open(os.path.join(out, "alice-2.xapi.json")) as fh:
            self.assertFalse(json.load(fh)["result"]["completion"])

    def test_bad_sessions_are_one_line_errors(self):
        for name in ("corrupt.palpa", "truncated.palpa", "missing.palpa"):
            with self.subTest(name=name):
                res = run(["score", os.path.join(SESSIONS, name)])
                self.assertEqual(res.returncode, 2, res.stderr)
                lines = [ln for ln in res.stderr.splitlines() if ln.strip()]
                self.assertEqual(len(lines), 1, res.stderr)
                self.assertTrue(lines[0].startswith("palpa-cli: error: "), lines[0])
                self.assertIn(name, lines[0])
                self.assertGreaterEqual(lines[0].count(": "), 3, lines[0])  # FILE: WHERE: REASON
                self.assertEqual(res.stdout, "")

    def test_help_and_usage(self):
        res = run(["score", "--help"])
        self.assertEqual(res.returncode, 0)
        self.assertIn("--report", res.stdout)
        self.assertIn("--json", res.stdout)
        self.assertEqual(run(["score"]).returncode, 2)


class NeverOverwrites(unittest.TestCase):
    """No command writes over an existing file without --force, nor over one of its own
    inputs even with it; what was there stays byte for byte."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="palpa_overwrite_")
        self.dir = self.tmp.name
        self.session = os.path.join(self.dir, "default.palpa")
        shutil.copy(os.path.join(SESSIONS, "alice-1.palpa"), self.session)
        self.case = os.path.join(self.dir, "default.json")  # a case beside it, named like its report
        shutil.copy(os.path.join(REPO, "data", "cases", "flat-5x5.json"), self.case)

    def tearDown(self):
        self.tmp.cleanup()

    def content(self, path):
        with open(path, "rb") as fh:
            return fh.read()

    def assertRefused(self, res, *words):
        self.assertEqual(res.returncode, 2, res.stdout + res.stderr)
        lines = [ln for ln in res.stderr.splitlines() if ln.strip()]
        self.assertEqual(len(lines), 1, res.stderr)
        for w in words:
            self.assertIn(w, lines[0])

    def test_a_report_beside_a_case_of_the_same_name_is_refused_without_force(self):
        case = self.content(self.case)
        res = run(["score", self.session, "--report", self.dir])
        self.assertRefused(res, "--report", "default.json", "exists", "--force")
        self.assertEqual(self.content(self.case), case)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "default.html")))  # nothing half-written
        res = run(["score", self.session, "--report", self.dir, "--force"])
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertIn(b'"sensitivity"', self.content(self.case))  # replaced, as asked

    def test_simulate_refuses_an_existing_out_and_its_own_inputs_even_with_force(self):
        trajectory = os.path.join(self.dir, "t.csv")
        with open(trajectory, "w") as fh:
            fh.write("t,x,y,z\n0,0,0,0.1\n0.01,0,0,0.1\n")
        before = self.content(self.case), self.content(trajectory)
        for out in (self.case, trajectory):
            for force in ([], ["--force"]):
                res = run(["simulate", self.case, "--trajectory", trajectory, "--out", out] + force)
                self.assertRefused(res, "--out", "input")
        self.assertEqual((self.content(self.case), self.content(trajectory)), before)
        out = os.path.join(self.dir, "run.csv")
        self.assertEqual(run(["simulate", self.case, "--trajectory", trajectory, "--out", out]).returncode, 0)
        first = self.content(out)
        self.assertRefused(run(["simulate", self.case, "--trajectory", trajectory, "--out", out]), "exists")
        self.assertEqual(self.content(out), first)
        self.assertEqual(run(["simulate", self.case, "--trajectory", trajectory, "--out", out, "--force"]).returncode, 0)

    def test_batch_refuses_an_earlier_batchs_outputs_without_force(self):
        out = os.path.join(self.dir, "batch")
        self.assertEqual(run(["batch", self.session, "--out", out]).returncode, 0)
        summary = self.content(os.path.join(out, "summary.csv"))
        self.assertRefused(run(["batch", self.session, "--out", out]), "--out", "exists", "--force")
        self.assertEqual(self.content(os.path.join(out, "summary.csv")), summary)
        self.assertEqual(run(["batch", self.session, "--out", out, "--force"]).returncode, 0)
        # A session that sits where an output goes is never replaced, even with --force.
        trap = os.path.join(out, "summary.csv")
        shutil.copy(self.session, trap)
        self.assertRefused(run(["batch", trap, "--out", out, "--force"]), "input")
        self.assertEqual(self.content(trap), self.content(self.session))


def main():
    global CLI, REPO, MAKE_SESSIONS
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cli", required=True)
    ap.add_argument("--repo", required=True)
    ap.add_argument("--make-sessions", required=True)
    args, rest = ap.parse_known_args()
    CLI = os.path.abspath(args.cli)
    REPO = os.path.abspath(args.repo)
    MAKE_SESSIONS = os.path.abspath(args.make_sessions)
    prog = unittest.main(argv=[sys.argv[0]] + rest, exit=False)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
