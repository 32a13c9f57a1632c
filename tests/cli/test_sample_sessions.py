#!/usr/bin/env python3
"""The bundled sample sessions (data/sessions) score as their README says, from the CLI.

Run: python3 tests/cli/test_sample_sessions.py --cli build/release/app/palpa-cli --repo .
"""
import argparse
import json
import os
import subprocess
import sys
import unittest

CLI = None
REPO = None


def score(name):
    path = os.path.join(REPO, "data", "sessions", name + ".palpa")
    res = subprocess.run([CLI, "score", path, "--json"], capture_output=True, text=True, timeout=120)
    if res.returncode != 0:
        raise AssertionError(res.stderr)
    s = json.loads(res.stdout)
    return s, {g["name"]: g["passed"] for g in s["gates"]}


class SampleSessions(unittest.TestCase):
    def test_expert_passes(self):
        s, gates = score("expert")
        self.assertTrue(s["passed"], gates)
        self.assertEqual(s["sensitivity"], 1.0)
        self.assertEqual(s["false_positives"], 0)
        self.assertEqual(s["session"]["trainee"], "sample-expert")
        self.assertTrue(s["complete"])

    def test_sloppy_fails_coverage_and_false_positives(self):
        s, gates = score("sloppy")
        self.assertFalse(s["passed"])
        self.assertFalse(gates["coverage"])
        self.assertFalse(gates["false_positives"])

    def test_light_misses_the_deep_tumour(self):
        s, gates = score("light")
        self.assertFalse(s["passed"])
        self.assertFalse(gates["sensitivity"])
        self.assertFalse(gates["deep_coverage"])
        self.assertTrue(gates["coverage"])

    def test_score_cards_and_reports_are_current(self):
        # The committed score cards and report JSON match what this build computes: a change
        # to scoring must come with regenerated samples (bash data/sessions/make_sessions.sh).
        for name in ("expert", "sloppy", "light"):
            s, _ = score(name)
            with open(os.path.join(REPO, "data", "sessions", "reports", name + ".json")) as fh:
                committed = json.load(fh)
            for key in ("passed", "score", "sensitivity", "false_positives", "coverage", "deep_coverage",
                        "peak_force_n", "duration_s"):
                self.assertEqual(committed[key], s[key], (name, key))
            with open(os.path.join(REPO, "data", "sessions", "reports", name + ".html")) as fh:
                self.assertEqual(fh.read().count("data:image/png;base64,"), 3, name)


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
