#!/usr/bin/python3
"""Scoring reads the samples as a stream: its memory is that of the case, not of the session.

A valid format-2 session of identical ticks (tests/tools/constant_session.py) is a few
hundred bytes per 65536 ticks on disk; a reader that holds every sample needs 96 bytes a
tick in memory. Here `palpa-cli score` (and `batch`) score 8 million of them (768 MB held,
1.15 GB while the vector grew from its 4 M reservation, before scoring read them as a
stream) with their address space limited to 1 GB, and must report every sample. The long
form, 72 million ticks (20 hours at 1 kHz, the most a session may hold, 12.6 GB at the
peak before), runs only with PALPA_LONG_TESTS=1.

Run:
    /usr/bin/python3 tests/cli/test_stream_scoring.py --cli PATH/palpa-cli --repo REPO
"""

import argparse
import csv
import json
import os
import resource
import subprocess
import sys
import tempfile
import unittest

CLI = None
REPO = None
SANITIZED = False
ADDRESS_SPACE = 1 << 30  # bytes
TICKS = 8_000_000
LONG_TICKS = 72_000_000


def limited(limit):
    """A preexec_fn capping the child's address space (a memory limit that also holds
    where RSS is not accounted, and that fails loudly: std::bad_alloc)."""
    def apply():
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    return apply


class StreamScoring(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="palpa_stream_")

    def tearDown(self):
        self.tmp.cleanup()

    def run_limited(self, args, timeout):
        # ASan reserves terabytes of address space for its shadow memory: no limit there
        # (the sanitized run still checks the count).
        preexec = None if SANITIZED else limited(ADDRESS_SPACE)
        return subprocess.run([CLI] + args, capture_output=True, text=True, timeout=timeout, preexec_fn=preexec)

    def constant_session(self, ticks):
        sys.path.insert(0, os.path.join(REPO, "tests", "tools"))
        from constant_session import write_constant_session
        path = os.path.join(self.tmp.name, "constant.palpa")
        write_constant_session(path, REPO, ticks)
        return path

    def assert_scores(self, ticks, timeout):
        path = self.constant_session(ticks)
        res = self.run_limited(["score", path, "--json"], timeout)
        self.assertEqual(res.returncode, 0, res.stderr[-2000:])
        report = json.loads(res.stdout)
        self.assertEqual(report["samples"], ticks)
        # One held press: contact all along, one period a tick.
        self.assertAlmostEqual(report["duration_s"], (ticks - 1) / 1000.0, places=3)
        return path

    def test_millions_of_identical_ticks_score_in_a_bounded_address_space(self):
        self.assert_scores(TICKS, timeout=120)

    def test_batch_scores_them_in_a_bounded_address_space(self):
        path = self.constant_session(TICKS)
        out = os.path.join(self.tmp.name, "out")
        res = self.run_limited(["batch", path, "--out", out, "--jobs", "1"], timeout=120)
        self.assertEqual(res.returncode, 0, res.stderr[-2000:])
        with open(os.path.join(out, "summary.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
        self.assertEqual(len(rows), 1)
        self.assertEqual(int(rows[0]["samples"]), TICKS)

    @unittest.skipUnless(os.environ.get("PALPA_LONG_TESTS") == "1", "set PALPA_LONG_TESTS=1 (72 M ticks, minutes)")
    def test_the_longest_session_scores_in_a_bounded_address_space(self):
        self.assert_scores(LONG_TICKS, timeout=1800)


def main():
    global CLI, REPO, SANITIZED
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cli", required=True)
    ap.add_argument("--repo", required=True)
    ap.add_argument("--sanitized", action="store_true", help="the command is built with ASan + UBSan: no RLIMIT_AS")
    args, rest = ap.parse_known_args()
    CLI = os.path.abspath(args.cli)
    REPO = os.path.abspath(args.repo)
    SANITIZED = args.sanitized
    prog = unittest.main(argv=[sys.argv[0]] + rest, exit=False)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
