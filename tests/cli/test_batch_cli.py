#!/usr/bin/env python3
"""palpa-cli batch, end to end.

Run: python3 tests/cli/test_batch_cli.py --cli build/release/app/palpa-cli --repo . \
         --make-sessions build/release/tests/make_test_sessions

The sessions folder (see tests/report/make_test_sessions.cpp) holds four good sessions
(alice-0, alice-1, alice-2 of trainee "alice", started on the 19th, 20th and 21st, and
sub/bob-1 of "Bob O'Neil/<x>"), a corrupt and a truncated .palpa file, and notes.txt.
"""
import argparse
import csv
import json
import os
import shutil
import sqlite3
import subprocess
import sys
import tempfile
import unittest

CLI = None
REPO = None
MAKE_SESSIONS = None
TIMEOUT = 300
SESSIONS = None
HEADER = ("file,session_id,trainee,case,started_at,passed,score,sensitivity,false_positives,"
          "localization_error_mm,coverage,deep_coverage,duration_s,contact_time_s,peak_force_n,"
          "safe,palpate_search_ratio,pattern,light_s,medium_s,deep_s,complete,samples,outcome,mode,case_file,case_id")


def run(args, timeout=TIMEOUT):
    return subprocess.run([CLI] + args, capture_output=True, text=True, timeout=timeout)


def read_csv(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def setUpModule():
    global SESSIONS, _TMP
    _TMP = tempfile.TemporaryDirectory(prefix="palpa_batch_sessions_")
    SESSIONS = _TMP.name
    subprocess.run([MAKE_SESSIONS, SESSIONS, os.path.join(REPO, "data", "cases", "flat-5x5.json")],
                   check=True, timeout=TIMEOUT)


def tearDownModule():
    _TMP.cleanup()


class Batch(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="palpa_batch_")

    def tearDown(self):
        self.tmp.cleanup()

    def batch(self, *args):
        return run(["batch"] + list(args))

    def test_folder_with_bad_files_skips_them_and_exits_2(self):
        out = os.path.join(self.tmp.name, "out")
        res = self.batch(SESSIONS, "--out", out, "--jobs", "2")
        self.assertEqual(res.returncode, 2, res.stderr)
        errors = [ln for ln in res.stderr.splitlines() if ln.startswith("palpa-cli: error: ")]
        self.assertEqual(len(errors), 2, res.stderr)
        self.assertEqual(sorted("corrupt.palpa" in e for e in errors), [False, True])
        self.assertTrue(any("truncated.palpa" in e for e in errors))
        # Not a terminal: no progress bar, one final line.
        self.assertNotIn("\r", res.stderr)
        self.assertIn("4 of 6 sessions scored, 2 skipped", res.stderr)

        with open(os.path.join(out, "summary.csv")) as fh:
            self.assertEqual(fh.readline().rstrip("\r\n"), HEADER)
        rows = read_csv(os.path.join(out, "summary.csv"))
        # Sorted by trainee then start: "Bob..." < "alice" in byte order.
        self.assertEqual([r["session_id"] for r in rows],
                         ["b1b1b1b1b1b1b1b1", "a0a0a0a0a0a0a0a0", "a1a1a1a1a1a1a1a1", "a2a2a2a2a2a2a2a2"])
        self.assertEqual(rows[0]["trainee"], "Bob O'Neil/<x>")
        self.assertEqual(rows[3]["complete"], "0")
        self.assertEqual(rows[2]["complete"], "1")
        self.assertEqual(rows[1]["false_positives"], "1")
        self.assertEqual(rows[1]["localization_error_mm"], "")
        self.assertEqual(float(rows[2]["sensitivity"]), 1.0)
        self.assertEqual(rows[0]["false_positives"], "1")

        skipped = read_csv(os.path.join(out, "errors.csv"))
        self.assertEqual(sorted(os.path.basename(r["file"]) for r in skipped), ["corrupt.palpa", "truncated.palpa"])
        for r in skipped:
            self.assertIn(os.path.basename(r["file"]), r["error"])

        alice = read_csv(os.path.join(out, "trainees", "alice.csv"))
        self.assertEqual([r["attempt"] for r in alice], ["1", "2", "3"])
        self.assertEqual([r["session_id"] for r in alice], ["a0a0a0a0a0a0a0a0", "a1a1a1a1a1a1a1a1", "a2a2a2a2a2a2a2a2"])
        # CUSUM of failures (p0 0.1, p1 0.3): + (1 - s) per failure, - s per pass, s = 0.18617.
        s, total = 0.18616894171033568, 0.0
        for r in alice:
            total += -s if r["passed"] == "1" else 1 - s
            self.assertAlmostEqual(float(r["cusum"]), total, places=9)
        self.assertTrue(os.path.getsize(os.path.join(out, "trainees", "alice.png")) > 1000)
        # The hostile trainee id became a safe file name of its own.
        names = sorted(os.listdir(os.path.join(out, "trainees")))
        self.assertEqual(len(names), 4, names)
        bob = [n for n in names if n.startswith("Bob") and n.endswith(".csv")]
        self.assertEqual(len(bob), 1, names)
        for ch in "/<>' ":
            self.assertNotIn(ch, bob[0])
        self.assertEqual(len(read_csv(os.path.join(out, "trainees", bob[0]))), 1)

        with open(os.path.join(out, "cohort.html")) as fh:
            html = fh.read()
        self.assertEqual(html.count('src="data:image/png;base64,'), 2)
        self.assertIn("Bob O&#39;Neil/&lt;x&gt;", html)
        self.assertNotIn("<x>", html)
        self.assertIn("corrupt.palpa", html)
        self.assertIn("truncated.palpa", html)

    def test_jobs_1_and_2_give_the_same_summary(self):
        outs = []
        for jobs in ("1", "2"):
            out = os.path.join(self.tmp.name, "out" + jobs)
            res = self.batch(SESSIONS, "--out", out, "--jobs", jobs)
            self.assertEqual(res.returncode, 2, res.stderr)
            with open(os.path.join(out, "summary.csv"), "rb") as fh:
                outs.append(fh.read())
        self.assertEqual(outs[0], outs[1])

    def test_good_files_only_exit_0_and_duplicates_count_once(self):
        out = os.path.join(self.tmp.name, "out")
        a1 = os.path.join(SESSIONS, "alice-1.palpa")
        sub = os.path.join(SESSIONS, "sub")
        res = self.batch(a1, a1, os.path.join(SESSIONS, ".", "alice-1.palpa"), sub, "--out", out, "--reports")
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertEqual(len(read_csv(os.path.join(out, "summary.csv"))), 2)
        self.assertEqual(read_csv(os.path.join(out, "errors.csv")), [])
        for stem in ("alice-1", "bob-1"):
            for ext in (".html", ".json", ".xapi.json"):
                self.assertTrue(os.path.isfile(os.path.join(out, "sessions", stem + ext)), stem + ext)
        with open(os.path.join(out, "sessions", "bob-1.xapi.json")) as fh:
            self.assertEqual(json.load(fh)["actor"]["account"]["name"], "Bob O'Neil/<x>")

    def test_explicit_files_are_taken_whatever_their_extension(self):
        renamed = os.path.join(self.tmp.name, "session.db")
        shutil.copy(os.path.join(SESSIONS, "alice-1.palpa"), renamed)
        out = os.path.join(self.tmp.name, "out")
        res = self.batch(renamed, "--out", out)
        self.assertEqual(res.returncode, 0, res.stderr)
        rows = read_csv(os.path.join(out, "summary.csv"))
        self.assertEqual([r["file"] for r in rows], [renamed])

    def test_missing_path_is_reported_and_skipped(self):
        out = os.path.join(self.tmp.name, "out")
        res = self.batch(os.path.join(SESSIONS, "alice-0.palpa"), os.path.join(self.tmp.name, "nope.palpa"),
                         "--out", out)
        self.assertEqual(res.returncode, 2, res.stderr)
        self.assertIn("nope.palpa", res.stderr)
        self.assertEqual(len(read_csv(os.path.join(out, "summary.csv"))), 1)
        self.assertEqual(len(read_csv(os.path.join(out, "errors.csv"))), 1)

    def test_unwritable_output_is_a_failure(self):
        blocker = os.path.join(self.tmp.name, "file")
        with open(blocker, "w") as fh:
            fh.write("x")
        res = self.batch(os.path.join(SESSIONS, "alice-0.palpa"), "--out", os.path.join(blocker, "out"))
        self.assertEqual(res.returncode, 1, res.stderr)
        self.assertIn("palpa-cli: error: ", res.stderr)

    def lifecycle_copy(self, name, session_id, trainee, started_at, mode, end_note=None):
        """alice-1 (a pass) copied with another id, trainee, start, mode and End note."""
        path = os.path.join(self.tmp.name, "in", name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        shutil.copy(os.path.join(SESSIONS, "alice-1.palpa"), path)
        db = sqlite3.connect(path)
        for key, value in (("id", session_id), ("trainee", trainee), ("started_at", started_at),
                           ("extra", json.dumps({"mode": mode}))):
            db.execute("update meta set value = ? where key = ?", (value, key))
        if end_note is not None:
            db.execute("update events set note = ? where kind = 'end'", (end_note,))
        db.commit()
        db.close()
        return path

    def test_abandoned_and_try_it_sessions_are_told_apart(self):
        # alice: three trainee exercises, then one she abandoned; carol: an instructor's Try it.
        for name in ("alice-0.palpa", "alice-1.palpa"):
            shutil.copy(os.path.join(SESSIONS, name), os.path.join(self.tmp.name, name))
        inputs = [os.path.join(self.tmp.name, "alice-0.palpa"), os.path.join(self.tmp.name, "alice-1.palpa")]
        inputs.append(self.lifecycle_copy("alice-3.palpa", "a3a3a3a3a3a3a3a3", "alice", "2026-11-22T08:00:00Z",
                                          "trainee", "abandoned: the trainee closed the window"))
        inputs.append(self.lifecycle_copy("carol-1.palpa", "c1c1c1c1c1c1c1c1", "carol", "2026-11-22T09:00:00Z",
                                          "instructor-try"))
        out = os.path.join(self.tmp.name, "out")
        res = self.batch(*inputs, "--out", out)
        self.assertEqual(res.returncode, 0, res.stderr)
        rows = {r["session_id"]: r for r in read_csv(os.path.join(out, "summary.csv"))}
        self.assertEqual(len(rows), 4)
        self.assertEqual(rows["a3a3a3a3a3a3a3a3"]["outcome"], "abandoned")
        self.assertEqual(rows["a3a3a3a3a3a3a3a3"]["passed"], "0")
        self.assertEqual(rows["a1a1a1a1a1a1a1a1"]["outcome"], "passed")
        self.assertEqual(rows["a0a0a0a0a0a0a0a0"]["outcome"], "failed")
        self.assertEqual(rows["c1c1c1c1c1c1c1c1"]["mode"], "instructor-try")
        self.assertEqual(rows["a1a1a1a1a1a1a1a1"]["mode"], "trainee")
        for r in rows.values():
            self.assertEqual(r["case_file"], "flat-5x5.json")
            self.assertTrue(r["case_id"].startswith("urn:palpa:case:"), r["case_id"])
        # Learning curves: trainee exercises only, the abandoned attempt left out.
        alice = read_csv(os.path.join(out, "trainees", "alice.csv"))
        self.assertEqual([r["session_id"] for r in alice], ["a0a0a0a0a0a0a0a0", "a1a1a1a1a1a1a1a1"])
        self.assertFalse(os.path.exists(os.path.join(out, "trainees", "carol.csv")))
        # On request they count too.
        out2 = os.path.join(self.tmp.name, "out2")
        res = self.batch(*inputs, "--out", out2, "--include-abandoned", "--all-modes")
        self.assertEqual(res.returncode, 0, res.stderr)
        alice = read_csv(os.path.join(out2, "trainees", "alice.csv"))
        self.assertEqual(len(alice), 3)
        self.assertEqual(len(read_csv(os.path.join(out2, "trainees", "carol.csv"))), 1)
        # palpa-cli score says so too, and it is not a failed exam.
        res = run(["score", inputs[2], "--json"])
        self.assertEqual(res.returncode, 0, res.stderr)
        j = json.loads(res.stdout)
        self.assertTrue(j["abandoned"])
        self.assertFalse(j["passed"])
        res = run(["score", inputs[2]])
        self.assertIn("ABANDONED", res.stdout)

    def test_help_and_usage(self):
        res = run(["batch", "--help"])
        self.assertEqual(res.returncode, 0)
        for option in ("--out", "--jobs", "--reports"):
            self.assertIn(option, res.stdout)
        self.assertEqual(self.batch(SESSIONS).returncode, 2)  # --out missing
        self.assertEqual(self.batch(SESSIONS, "--out", self.tmp.name, "--jobs", "0").returncode, 2)


class SpreadsheetSafe(unittest.TestCase):
    """A trainee id a spreadsheet would run as a formula reaches summary.csv neutralised (a
    leading ' inside quotes, OWASP's advice) and the JSON report as typed."""

    def test_a_formula_trainee_id_is_written_safely(self):
        hostile = '=HYPERLINK("http://example.invalid","click")'
        with tempfile.TemporaryDirectory(prefix="palpa_csv_") as d:
            session = os.path.join(d, "s.palpa")
            res = run(["exercise", os.path.join(REPO, "data", "cases", "flat-5x5.json"), "--trainee", hostile,
                       "--style", "light", "--seed", "1", "--out", session])
            self.assertEqual(res.returncode, 0, res.stderr)
            res = run(["batch", session, "--out", os.path.join(d, "out")])
            self.assertEqual(res.returncode, 0, res.stderr)
            with open(os.path.join(d, "out", "summary.csv"), newline="") as fh:
                rows = list(csv.DictReader(fh))
            self.assertEqual(rows[0]["trainee"], "'" + hostile)
            res = run(["score", session, "--json"])
            self.assertEqual(json.loads(res.stdout)["session"]["trainee"], hostile)


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
