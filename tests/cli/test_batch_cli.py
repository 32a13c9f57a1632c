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
import hashlib
import json
import math
import os
import re
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
          "safe,palpate_search_ratio,pattern,light_s,medium_s,deep_s,complete,samples,outcome,mode,case_file,case_id,score_100,station")
TRAINEE_HEADER = ("attempt,started_at,file,session_id,score,passed,sensitivity,coverage,deep_coverage,cusum,signal,"
                  "score_100,proficient,verdict,station")


def stem(name):
    """A trainee's file stem, by hand: a readable prefix, "-" and 16 hex digits of SHA-1."""
    prefix = re.sub(r"[^A-Za-z0-9._-]", "_", name)[:48]
    if prefix.startswith("."):
        prefix = "_" + prefix[1:]
    return (prefix or "trainee") + "-" + hashlib.sha1(name.encode()).hexdigest()[:16]
# CUSUM of failures, p0 0.1, p1 0.3, alpha = beta = 0.1: s = ln(9/7) / ln(27/7), h = ln 9 / ln(27/7).
CUSUM_S = math.log(9 / 7) / math.log(27 / 7)
CUSUM_H = math.log(9) / math.log(27 / 7)


def restarted_cusum(passed):
    """The CUSUM after each attempt, by hand: + (1 - s) per failure, - s per pass, back to 0
    after the attempt that reached a limit."""
    values, total = [], 0.0
    for ok in passed:
        total += -CUSUM_S if ok else 1 - CUSUM_S
        values.append(total)
        if abs(total) >= CUSUM_H - 1e-9:
            total = 0.0
    return values


def cell(value, decimals):
    """A number as the CSV writes it: fixed decimals, no sign on a zero."""
    text = "%.*f" % (decimals, value)
    return text[1:] if text.startswith("-") and not text.strip("-0.") else text


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

        alice = read_csv(os.path.join(out, "trainees", stem("alice") + ".csv"))
        self.assertEqual([r["attempt"] for r in alice], ["1", "2", "3"])
        self.assertEqual([r["session_id"] for r in alice], ["a0a0a0a0a0a0a0a0", "a1a1a1a1a1a1a1a1", "a2a2a2a2a2a2a2a2"])
        with open(os.path.join(out, "trainees", stem("alice") + ".csv")) as fh:
            self.assertEqual(fh.readline().rstrip("\r\n"), TRAINEE_HEADER)
        # The CUSUM, to 0.01 as the CSV writes it.
        expected = restarted_cusum([r["passed"] == "1" for r in alice])
        self.assertEqual([r["cusum"] for r in alice], [cell(v, 2) for v in expected])
        self.assertTrue(os.path.getsize(os.path.join(out, "trainees", stem("alice") + ".png")) > 1000)
        # The hostile trainee id became a safe file name of its own.
        names = sorted(os.listdir(os.path.join(out, "trainees")))
        self.assertEqual(len(names), 4, names)
        bob = [n for n in names if n.startswith("Bob") and n.endswith(".csv")]
        self.assertEqual(bob, [stem("Bob O'Neil/<x>") + ".csv"], names)
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

    def lifecycle_copy(self, name, session_id, trainee, started_at, mode, end_note=None, station=None):
        """alice-1 (a pass) copied with another id, trainee, start, mode and End note."""
        path = os.path.join(self.tmp.name, "in", name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        shutil.copy(os.path.join(SESSIONS, "alice-1.palpa"), path)
        db = sqlite3.connect(path)
        for key, value in (("id", session_id), ("trainee", trainee), ("started_at", started_at),
                           ("extra", json.dumps(dict({"mode": mode}, **({"station": station} if station else {}))))):
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
                                          "instructor-try", station="room-2"))
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
        # The station that recorded a session (extra.station); empty for sessions without it.
        self.assertEqual(rows["c1c1c1c1c1c1c1c1"]["station"], "room-2")
        self.assertEqual(rows["a1a1a1a1a1a1a1a1"]["station"], "")
        for r in rows.values():
            self.assertEqual(r["case_file"], "flat-5x5.json")
            self.assertTrue(r["case_id"].startswith("urn:palpa:case:"), r["case_id"])
        # Learning curves: trainee exercises only, the abandoned attempt left out.
        alice = read_csv(os.path.join(out, "trainees", stem("alice") + ".csv"))
        self.assertEqual([r["session_id"] for r in alice], ["a0a0a0a0a0a0a0a0", "a1a1a1a1a1a1a1a1"])
        self.assertFalse(os.path.exists(os.path.join(out, "trainees", stem("carol") + ".csv")))
        # On request they count too.
        out2 = os.path.join(self.tmp.name, "out2")
        res = self.batch(*inputs, "--out", out2, "--include-abandoned", "--all-modes")
        self.assertEqual(res.returncode, 0, res.stderr)
        alice = read_csv(os.path.join(out2, "trainees", stem("alice") + ".csv"))
        self.assertEqual(len(alice), 3)
        self.assertEqual(len(read_csv(os.path.join(out2, "trainees", stem("carol") + ".csv"))), 1)
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
        for option in ("--out", "--jobs", "--reports", "--since", "--until", "--case", "--trainee"):
            self.assertIn(option, res.stdout)
        self.assertEqual(self.batch(SESSIONS).returncode, 2)  # --out missing
        self.assertEqual(self.batch(SESSIONS, "--out", self.tmp.name, "--jobs", "0").returncode, 2)

class Cohort(unittest.TestCase):
    """Learning-curve verdicts, rounding and filters on a cohort made of copies of alice-1 (a
    pass) and alice-0 (a failure), each with its own trainee, start time and mode."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="palpa_cohort_")
        self.inputs = os.path.join(self.tmp.name, "in")
        os.makedirs(self.inputs)

    def tearDown(self):
        self.tmp.cleanup()

    def attempts(self, trainee, outcomes, first_day, case_file=None):
        """One session per letter of `outcomes` (P pass, F fail), a day apart from first_day
        of November 2026."""
        for k, outcome in enumerate(outcomes):
            path = os.path.join(self.inputs, "%s-%02d.palpa" % (trainee, k))
            shutil.copy(os.path.join(SESSIONS, "alice-1.palpa" if outcome == "P" else "alice-0.palpa"), path)
            db = sqlite3.connect(path)
            values = (("id", "%s%014d" % (trainee[:2], k)), ("trainee", trainee),
                      ("started_at", "2026-11-%02dT09:00:00Z" % (first_day + k)), ("extra", json.dumps({"mode": "trainee"})))
            for key, value in values:
                db.execute("update meta set value = ? where key = ?", (value, key))
            if case_file:
                db.execute("update meta set value = ? where key = 'case_source'", ("cases/" + case_file,))
            db.commit()
            db.close()

    def batch(self, *args):
        """A batch into a new folder (an earlier batch's trainee files would stay in the old one)."""
        self.runs = getattr(self, "runs", 0) + 1
        out = os.path.join(self.tmp.name, "out%d" % self.runs)
        return run(["batch", self.inputs, "--out", out] + list(args)), out

    def test_a_trainee_who_passes_her_last_three_is_proficient(self):
        self.attempts("dana", "FFFFFFPPP", 1)   # the CUSUM alone: failure rate above 30 %
        self.attempts("erin", "PPPPP", 1)       # the CUSUM alone: no signal yet
        self.attempts("fay", "PPPPFPP", 1)      # proficient at 3-4, then a failure and two passes
        res, out = self.batch()
        self.assertEqual(res.returncode, 0, res.stderr)
        dana = read_csv(os.path.join(out, "trainees", stem("dana") + ".csv"))
        self.assertEqual([r["proficient"] for r in dana], ["0"] * 8 + ["1"])
        self.assertEqual(dana[-1]["verdict"], "proficient since attempt 9")
        self.assertEqual(dana[7]["verdict"], "not yet: 2 of the last 5 passed")
        self.assertEqual([r["cusum"] for r in dana], [cell(v, 2) for v in restarted_cusum([False] * 6 + [True] * 3)])
        self.assertEqual([r["signal"] for r in dana][:6], ["", "unacceptable"] * 3)
        erin = read_csv(os.path.join(out, "trainees", stem("erin") + ".csv"))
        self.assertEqual(erin[-1]["verdict"], "proficient since attempt 3")
        fay = read_csv(os.path.join(out, "trainees", stem("fay") + ".csv"))
        self.assertEqual(fay[-1]["proficient"], "0")
        self.assertEqual(fay[-1]["verdict"],
                         "proficient at attempts 3-4; failed attempt 5: not yet again (4 of the last 5 passed)")
        with open(os.path.join(out, "cohort.html")) as fh:
            html = fh.read()
        self.assertIn('<td class="ok">proficient since attempt 9</td>', html)
        self.assertIn("dana: proficient since attempt 9</h2>", html)
        self.assertIn("failure rate probably above 30 % (attempt 6)", html)
        self.assertIn("the line then restarts at 0.", html)
        self.assertIn("Covers every session given.", html)

    def test_csv_numbers_are_rounded_to_their_unit(self):
        self.attempts("dana", "FP", 1)
        res, out = self.batch()
        self.assertEqual(res.returncode, 0, res.stderr)
        report = json.loads(run(["score", os.path.join(self.inputs, "dana-01.palpa"), "--json"]).stdout)
        row = [r for r in read_csv(os.path.join(out, "summary.csv")) if r["session_id"].endswith("1")][0]
        decimals = {"score": 3, "sensitivity": 3, "coverage": 3, "deep_coverage": 3, "duration_s": 2,
                    "contact_time_s": 2, "peak_force_n": 2, "palpate_search_ratio": 2}
        for column, d in decimals.items():
            self.assertEqual(row[column], cell(report[column], d), column)
        self.assertEqual(row["score_100"], cell(100 * report["score"], 1))
        mean = sum(report["localization_error_mm"]) / len(report["localization_error_mm"])
        self.assertEqual(row["localization_error_mm"], cell(mean, 1))
        for column in ("light_s", "medium_s", "deep_s"):
            self.assertEqual(row[column], cell(report["pressure"][column], 2), column)
        curve = read_csv(os.path.join(out, "trainees", stem("dana") + ".csv"))
        self.assertEqual(curve[1]["score_100"], row["score_100"])
        self.assertEqual(curve[1]["score"], row["score"])

    def test_filters_select_dates_case_and_trainee(self):
        self.attempts("dana", "PPPPP", 1)                            # 1st-5th, flat-5x5.json
        self.attempts("erin", "FFF", 28, case_file="default.json")   # 28th-30th, default.json
        res, out = self.batch("--since", "2026-11-03", "--until", "2026-11-30")
        self.assertEqual(res.returncode, 0, res.stderr)
        rows = read_csv(os.path.join(out, "summary.csv"))
        self.assertEqual(sorted(r["started_at"][:10] for r in rows),
                         ["2026-11-%02d" % d for d in (3, 4, 5, 28, 29, 30)])
        self.assertIn("6 of 8 sessions scored, 0 skipped, 2 outside sessions from 2026-11-03 to 2026-11-30", res.stderr)
        with open(os.path.join(out, "cohort.html")) as fh:
            self.assertIn("Covers sessions from 2026-11-03 to 2026-11-30.", fh.read())
        # A full time is an instant: until 09:00 on the 4th keeps the 4th's 09:00 session.
        res, out = self.batch("--since", "2026-11-02T09:00:01Z", "--until", "2026-11-04T09:00:00Z")
        self.assertEqual(sorted(r["started_at"][:10] for r in read_csv(os.path.join(out, "summary.csv"))),
                         ["2026-11-03", "2026-11-04"])
        for case in ("default", "default.json"):
            res, out = self.batch("--case", case)
            self.assertEqual(res.returncode, 0, res.stderr)
            self.assertEqual({r["trainee"] for r in read_csv(os.path.join(out, "summary.csv"))}, {"erin"}, case)
        case_id = [r for r in rows if r["trainee"] == "dana"][0]["case_id"]
        res, out = self.batch("--case", case_id, "--trainee", "dana", "--since", "2026-11-01", "--until", "2026-11-30")
        self.assertEqual(len(read_csv(os.path.join(out, "summary.csv"))), 5)
        self.assertEqual(sorted(os.listdir(os.path.join(out, "trainees"))), [stem("dana") + ".csv", stem("dana") + ".png"])
        with open(os.path.join(out, "cohort.html")) as fh:
            self.assertIn("Covers sessions from 2026-11-01 to 2026-11-30, case %s, trainee dana." % case_id, fh.read())

    def test_a_bad_date_is_one_line_naming_the_option(self):
        self.attempts("dana", "P", 1)
        for option, value in (("--since", "2026-13-01"), ("--until", "30/11/2026"), ("--since", "2026-02-30")):
            res, out = self.batch(option, value)
            self.assertEqual(res.returncode, 2, res.stderr)
            lines = [ln for ln in res.stderr.splitlines() if ln.strip()]
            self.assertEqual(len(lines), 1, res.stderr)
            self.assertTrue(lines[0].startswith("palpa-cli: error: %s: \"%s\" is not a date" % (option, value)), lines[0])
            self.assertFalse(os.path.exists(out))
        res, _ = self.batch("--since", "2026-12-01", "--until", "2026-11-30")
        self.assertEqual(res.returncode, 2, res.stderr)
        self.assertIn("--since: 2026-12-01 is after --until 2026-11-30", res.stderr)


def median(values):
    values = sorted(values)
    mid = len(values) // 2
    return values[mid] if len(values) % 2 else (values[mid - 1] + values[mid]) / 2


def proficient_now(passed):
    """Three passes in a row at the end (docs: report/README.md, the verdict)."""
    return len(passed) >= 3 and all(passed[-3:])


class Coordinator(unittest.TestCase):
    """The coordinator's view: per-case and per-station summaries, one learning curve per
    trainee and case, links to the session reports, notes on what the curves leave out, and
    names from session files that are escaped and shortened. Sessions are copies of alice-1
    (a pass) and alice-0 (a failure) with their meta rewritten."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="palpa_coordinator_")
        self.inputs = os.path.join(self.tmp.name, "in")
        os.makedirs(self.inputs)
        self.count = 0

    def tearDown(self):
        self.tmp.cleanup()

    def session(self, trainee, outcome, day, case=None, station=None, mode="trainee"):
        """One session (P pass, F fail) on the given day of November 2026; `case` renames the
        case's title (so its case_id), `station` goes to extra.station."""
        self.count += 1
        path = os.path.join(self.inputs, "s%03d.palpa" % self.count)
        shutil.copy(os.path.join(SESSIONS, "alice-1.palpa" if outcome == "P" else "alice-0.palpa"), path)
        db = sqlite3.connect(path)
        extra = {"mode": mode}
        if station is not None:
            extra["station"] = station
        values = [("id", "%016d" % self.count), ("trainee", trainee),
                  ("started_at", "2026-11-%02dT09:00:00Z" % day), ("extra", json.dumps(extra))]
        if case is not None:
            document = json.loads(db.execute("select value from meta where key = 'case'").fetchone()[0])
            document["title"] = case
            values.append(("case", json.dumps(document)))
        for key, value in values:
            db.execute("update meta set value = ? where key = ?", (value, key))
        db.commit()
        db.close()

    def batch(self, *args):
        out = os.path.join(self.tmp.name, "out%d" % len(os.listdir(self.tmp.name)))
        return run(["batch", self.inputs, "--out", out] + list(args)), out

    def two_cases_two_stations(self):
        for day, outcome in enumerate("PPP", 1):
            self.session("ann", outcome, day, "Case A", "north")
        for day, outcome in enumerate("FP", 10):
            self.session("ann", outcome, day, "Case B", "south")
        for day, outcome in enumerate("FFP", 1):
            self.session("ben", outcome, day, "Case A", "south")
        self.session("ben", "P", 20, "Case B", "north")
        self.session("cal", "P", 21, "Case A", "north", mode="scripted")   # in the summaries, not in the curves

    def expected_groups(self, rows, column):
        """cases.csv / stations.csv worked out from summary.csv alone."""
        curves = {}
        for r in sorted(rows, key=lambda r: r["started_at"]):
            if r["mode"] == "trainee" and r["outcome"] != "abandoned":
                curves.setdefault((r["trainee"], r["case_id"]), []).append(r["passed"] == "1")
        groups = {}
        for r in rows:
            groups.setdefault(r[column], []).append(r)
        expected = {}
        for key, group in groups.items():
            scored = [r for r in group if r["outcome"] != "abandoned"]
            passed = sum(r["passed"] == "1" for r in group)
            proficient = {r["trainee"] for r in group if proficient_now(curves.get((r["trainee"], r["case_id"]), []))}
            expected[key] = {"sessions": len(group), "scored": len(scored), "passed": passed,
                             "pass_rate": "%.3f" % (passed / len(scored)),
                             "median": median([float(r["score_100"]) for r in scored]),
                             "trainees": len({r["trainee"] for r in group}), "proficient_trainees": len(proficient)}
        return expected

    def assert_groups(self, path, column, rows):
        expected = self.expected_groups(rows, column)
        got = {r[column]: r for r in read_csv(path)}
        self.assertEqual(set(got), set(expected))
        for key, e in expected.items():
            g = got[key]
            for field in ("sessions", "scored", "passed", "trainees", "proficient_trainees"):
                self.assertEqual(int(g[field]), e[field], (key, field))
            self.assertEqual(g["pass_rate"], e["pass_rate"], key)
            # The median of the exact scores, to 0.1; summary.csv's are already rounded to 0.1.
            self.assertAlmostEqual(float(g["median_score_100"]), e["median"], delta=0.1 + 1e-9, msg=key)
        return got

    def test_per_case_and_per_station_summaries_match_summary_csv(self):
        self.two_cases_two_stations()
        res, out = self.batch("--reports")
        self.assertEqual(res.returncode, 0, res.stderr)
        rows = read_csv(os.path.join(out, "summary.csv"))
        self.assertEqual(len(rows), 10)
        self.assertEqual({r["station"] for r in rows}, {"north", "south"})
        cases = self.assert_groups(os.path.join(out, "cases.csv"), "case_id", rows)
        stations = self.assert_groups(os.path.join(out, "stations.csv"), "station", rows)
        self.assertEqual(len(cases), 2)
        # By hand: ann passed case A three times in a row (north); nobody else is proficient.
        a = [k for k in cases if k.endswith("case-a")][0]
        self.assertEqual((cases[a]["sessions"], cases[a]["passed"], cases[a]["proficient_trainees"]), ("7", "5", "1"))
        self.assertEqual(cases[a]["case"], "Case A")
        self.assertEqual((stations["north"]["sessions"], stations["north"]["proficient_trainees"]), ("5", "1"))
        self.assertEqual(stations["south"]["proficient_trainees"], "0")
        with open(os.path.join(out, "cohort.html")) as fh:
            html = fh.read()
        self.assertIn("<h2>Cases</h2>", html)
        self.assertIn("<h2>Stations</h2>", html)
        self.assertIn('<tr><td>north</td><td class="num">5</td>', html)
        # One curve per trainee and case, none mixing cases; the per-trainee files as before.
        self.assertEqual(len(read_csv(os.path.join(out, "trainees", stem("ann") + ".csv"))), 5)
        self.assertEqual(sorted(os.listdir(os.path.join(out, "curves"))), sorted([stem("ann"), stem("ben")]))
        ann_folder = os.path.join(out, "curves", stem("ann"))
        ann = {n: read_csv(os.path.join(ann_folder, n)) for n in os.listdir(ann_folder) if n.endswith(".csv")}
        self.assertEqual(sorted(len(v) for v in ann.values()), [2, 3])
        by_id = {r["session_id"]: r["case_id"] for r in rows}
        for attempts in ann.values():
            self.assertEqual(len({by_id[a["session_id"]] for a in attempts}), 1)
        case_a = [n for n in ann if n.startswith("case-a-")]
        self.assertEqual(len(case_a), 1, sorted(ann))
        self.assertEqual(ann[case_a[0]][-1]["verdict"], "proficient since attempt 3")
        self.assertIn('href="curves/%s/%s.png"' % (stem("ann"), case_a[0][:-len(".csv")]), html)
        # --reports: every session's page linked, relative, and there.
        links = [h for h in re.findall(r'href="([^"]+)"', html) if h.startswith("sessions/")]
        self.assertEqual(len(links), 10)
        for href in links:
            self.assertTrue(os.path.isfile(os.path.join(out, href)), href)

    def test_a_scripted_cohort_says_which_option_counts_it(self):
        for day in range(1, 4):
            self.session("sam", "P", day, mode="scripted")
        res, out = self.batch()
        self.assertEqual(res.returncode, 0, res.stderr)
        note = ("3 scripted sessions are not in the learning curves: only trainee exercises count; "
                "give --all-modes to include them.")
        self.assertIn(note, res.stderr)
        with open(os.path.join(out, "cohort.html")) as fh:
            html = fh.read()
        self.assertIn("0 sessions in the learning curves", html)
        self.assertIn('<p class="note">' + note + "</p>", html)
        res, out = self.batch("--all-modes")
        self.assertNotIn("--all-modes", res.stderr)
        with open(os.path.join(out, "cohort.html")) as fh:
            self.assertNotIn('class="note"', fh.read())
        self.session("tia", "P", 9)
        res, out = self.batch("--trainee", "tia")
        self.assertIn("3 sessions are outside the selection (sessions of trainee tia) and in no output; "
                      "run without --trainee to include them.", res.stderr)

    def test_hostile_trainee_ids_are_escaped_and_shortened(self):
        hostile = "\x1b[31m\u202eevil" + "x" * 100000
        self.session(hostile, "P", 1)
        self.session("ann", "F", 2)
        res, out = self.batch()
        self.assertEqual(res.returncode, 0, res.stderr)
        with open(os.path.join(out, "summary.csv"), newline="", encoding="utf-8") as fh:
            text = fh.read()
        for raw in ("\x1b", "\u202e"):
            self.assertNotIn(raw, text)
        rows = list(csv.DictReader(text.splitlines()))
        self.assertEqual(rows[0]["trainee"], "\\x1b[31m\\u{202e}evil" + "x" * 100000)  # escaped, not shortened
        self.assertEqual(rows[1]["trainee"], "ann")
        with open(os.path.join(out, "cohort.html"), encoding="utf-8") as fh:
            html = fh.read()
        for raw in ("\x1b", "\u202e"):
            self.assertFalse(raw in html, repr(raw))
        # What a reader sees (outside the title attributes) is at most 60 characters of it.
        visible = re.sub(r' title="[^"]*"', "", html)
        self.assertFalse("x" * 60 in visible, "more than 60 characters shown")
        shown = "\\x1b[31m\\u{202e}evil" + "x" * (60 - 10) + "\u2026"  # 60 characters of the original
        cell = "<span title=\"\\x1b[31m\\u{202e}evil" + "x" * 100000 + "\">" + shown + "</span>"
        self.assertTrue(cell in html, "the shortened cell with its title is missing")
        self.assertIn("overflow-wrap:anywhere", html)


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
