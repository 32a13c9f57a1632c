#!/usr/bin/env python3
"""palpa-cli batch over 1000 sessions with corrupt files among them.

Run: python3 tests/cli/test_batch_1000.py --cli build/release/app/palpa-cli --repo . \
         --make-sessions build/release/tests/make_test_sessions

The 1000 sessions are copies of three small sessions of known content (written by
make_test_sessions), each with its own id, trainee and start time
(tests/tools/make_batch_corpus.py). So the truth is exact: every copy scores like its
original, every trainee's learning curve has its attempts in time order, and the corrupt
files are reported and skipped without stopping the batch.
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile
import unittest

CLI = MAKE = REPO = None
COUNT, TRAINEES, CORRUPT = 1000, 10, 2


class Batch1000(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="palpa_batch1000_")
        base = os.path.join(cls.tmp.name, "base")
        subprocess.run([MAKE, base, os.path.join(REPO, "data", "cases", "flat-5x5.json")], check=True,
                       capture_output=True)
        cls.bases = [os.path.join(base, n) for n in ("alice-0.palpa", "alice-1.palpa", "sub/bob-1.palpa")]
        cls.corpus = os.path.join(cls.tmp.name, "corpus")
        subprocess.run([sys.executable, os.path.join(REPO, "tests", "tools", "make_batch_corpus.py")] + cls.bases +
                       ["--out", cls.corpus, "--count", str(COUNT), "--trainees", str(TRAINEES),
                        "--corrupt", str(CORRUPT)], check=True, capture_output=True)
        cls.out = os.path.join(cls.tmp.name, "out")
        # Scripted sessions: their learning curves count only with --all-modes.
        cls.res = subprocess.run([CLI, "batch", cls.corpus, "--out", cls.out, "--jobs", "2", "--all-modes"], capture_output=True,
                                 text=True, timeout=600)
        with open(os.path.join(cls.out, "summary.csv")) as fh:
            cls.rows = list(csv.DictReader(fh))

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def base_scores(self):
        scores = []
        for b in self.bases:
            out = os.path.join(self.tmp.name, "one-" + os.path.basename(b))
            res = subprocess.run([CLI, "batch", b, "--out", out], capture_output=True, text=True, timeout=60)
            self.assertEqual(res.returncode, 0, res.stderr)
            with open(os.path.join(out, "summary.csv")) as fh:
                scores.append(list(csv.DictReader(fh))[0])
        return scores

    def test_every_good_session_is_scored_and_the_corrupt_ones_skipped(self):
        self.assertEqual(self.res.returncode, 2, self.res.stderr[-2000:])
        self.assertEqual(len(self.rows), COUNT)
        with open(os.path.join(self.out, "errors.csv")) as fh:
            errors = list(csv.DictReader(fh))
        self.assertEqual(len(errors), CORRUPT)
        for e in errors:
            self.assertIn("corrupt", os.path.basename(e["file"]))
        error_lines = [l for l in self.res.stderr.splitlines() if l.startswith("palpa-cli: error: ")]
        self.assertEqual(len(error_lines), CORRUPT, self.res.stderr[-2000:])

    def test_copies_score_like_their_originals(self):
        truth = self.base_scores()
        keys = ("passed", "score", "sensitivity", "false_positives", "coverage", "deep_coverage", "duration_s",
                "peak_force_n", "samples")
        for row in self.rows:
            index = int(os.path.basename(row["file"])[1:6])
            expected = truth[index % 3]
            for k in keys:
                self.assertEqual(row[k], expected[k], (row["file"], k))

    def test_learning_curves_have_every_attempt_in_order(self):
        folder = os.path.join(self.out, "trainees")
        curves = [f for f in os.listdir(folder) if f.endswith(".csv")]
        self.assertEqual(len(curves), TRAINEES)
        for name in curves:
            with open(os.path.join(folder, name)) as fh:
                attempts = list(csv.DictReader(fh))
            self.assertEqual(len(attempts), COUNT // TRAINEES, name)
            starts = [a["started_at"] for a in attempts]
            self.assertEqual(starts, sorted(starts), name)
        self.assertTrue(os.path.getsize(os.path.join(self.out, "cohort.html")) > 0)


def main():
    global CLI, MAKE, REPO
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--repo", required=True)
    ap.add_argument("--make-sessions", required=True)
    args, rest = ap.parse_known_args()
    CLI, MAKE, REPO = (os.path.abspath(p) for p in (args.cli, args.make_sessions, args.repo))
    prog = unittest.main(argv=[sys.argv[0]] + rest, exit=False, verbosity=2)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
