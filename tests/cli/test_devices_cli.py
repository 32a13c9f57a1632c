#!/usr/bin/python3
"""palpa-cli devices and --device, without hardware.

Run:
    /usr/bin/python3 tests/cli/test_devices_cli.py --cli PATH/palpa-cli --repo REPO [unittest arguments]

`devices` lists the virtual device first and exits 0 even where /dev/bus/usb or
/dev/hidraw* is absent (then a note says so); --json gives the same list. `exercise
--device replay:SESSION` re-scores a recorded session: the recorded probe path through the
engine again finds the same tumours as the original. Bad device ids are one-line errors.
Standard library only.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import unittest

CLI = None
REPO = None
TIMEOUT = 120


def run(args):
    return subprocess.run([CLI] + list(args), capture_output=True, text=True, timeout=TIMEOUT,
                          stdin=subprocess.DEVNULL)


class DevicesCommand(unittest.TestCase):
    def test_lists_the_virtual_device_first_and_exits_0(self):
        res = run(["devices"])
        self.assertEqual(res.returncode, 0, res.stderr)
        lines = res.stdout.splitlines()
        self.assertTrue(lines[0].startswith("ID"), lines)
        self.assertTrue(lines[1].startswith("virtual "), lines)
        self.assertIn("virtual (mouse)", lines[1])
        notes = [l for l in lines if l.startswith("note: ")]
        if not os.path.exists("/dev/bus/usb"):
            self.assertTrue(any("/dev/bus/usb is absent" in n for n in notes), lines)
        self.assertEqual(res.stderr, "")

    def test_json_matches_the_table(self):
        res = run(["devices", "--json"])
        self.assertEqual(res.returncode, 0, res.stderr)
        listing = json.loads(res.stdout)
        self.assertEqual(listing["devices"][0],
                         {"id": "virtual", "kind": "virtual", "name": "virtual (mouse)", "force_output": False,
                          "detail": ""})
        table = run(["devices"]).stdout.splitlines()
        ids = [l.split()[0] for l in table[1:] if not l.startswith("note: ")]
        self.assertEqual(ids, [d["id"] for d in listing["devices"]])
        self.assertEqual(len(listing["notes"]), sum(1 for l in table if l.startswith("note: ")))


class DeviceOption(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.case = os.path.join(REPO, "data", "cases", "default.json")
        cls.original = os.path.join(cls.tmp.name, "original.palpa")
        res = run(["exercise", cls.case, "--trainee", "t1", "--seed", "3", "--out", cls.original, "--json"])
        assert res.returncode == 0, res.stderr
        cls.original_report = json.loads(res.stdout)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_replay_rescoring_finds_what_the_original_found(self):
        out = os.path.join(self.tmp.name, "rescored.palpa")
        res = run(["exercise", "--device", "replay:" + self.original, "--out", out, "--json"])
        self.assertEqual(res.returncode, 0, res.stderr)
        report = json.loads(res.stdout)
        # Same hand, same case, same marks: the same tumours found, the same false marks, the
        # same ground covered (the engine is deterministic).
        for key in ("sensitivity", "false_positives", "localization_error_mm", "passed"):
            self.assertEqual(report[key], self.original_report[key], key)
        self.assertAlmostEqual(report["coverage"], self.original_report["coverage"], places=9)
        self.assertGreater(report["sensitivity"], 0.0)  # the expert found something worth re-finding
        rescored = json.loads(run(["score", out, "--json"]).stdout)
        self.assertEqual(rescored["sensitivity"], report["sensitivity"])

    def test_simulate_replays_a_session_into_a_csv(self):
        out = os.path.join(self.tmp.name, "replayed.csv")
        res = run(["simulate", self.case, "--device", "replay:" + self.original, "--out", out])
        self.assertEqual(res.returncode, 0, res.stderr)
        with open(out) as fh:
            rows = fh.read().splitlines()
        self.assertGreater(len(rows), 1000)
        self.assertTrue(rows[0].startswith("t,x,y,z"), rows[0])

    def test_bad_device_ids_are_one_line_errors(self):
        out = os.path.join(self.tmp.name, "never.palpa")
        cases = [
            (["exercise", self.case, "--trainee", "x", "--device", "falcon", "--out", out], "--device: falcon"),
            (["exercise", "--device", "replay:" + os.path.join(self.tmp.name, "missing.palpa"), "--out", out],
             "missing.palpa"),
            (["exercise", self.case, "--device", "replay:" + self.original, "--out", out], "CASE is not used"),
            (["simulate", self.case, "--device", "spacemouse", "--out", out], "needs --realtime and --duration"),
            (["simulate", self.case, "--device", "phantom", "--realtime", "--duration", "1", "--out", out],
             "phantom: id: unknown device"),
            (["simulate", self.case, "--device", "falcon", "--realtime", "--duration", "1", "--out", out],
             "falcon: open: not attached"),
            (["simulate", self.case, "--out", out], "either --trajectory or --device"),
        ]
        for args, needle in cases:
            res = run(args)
            self.assertEqual(res.returncode, 2, (args, res.stderr))
            self.assertEqual(len(res.stderr.strip().splitlines()), 1, (args, res.stderr))
            self.assertIn(needle, res.stderr)
            self.assertTrue(res.stderr.startswith("palpa-cli: error: "), res.stderr)
        self.assertFalse(os.path.exists(out))


def main():
    global CLI, REPO
    parser = argparse.ArgumentParser()
    parser.add_argument("--cli", required=True)
    parser.add_argument("--repo", required=True)
    args, rest = parser.parse_known_args()
    CLI, REPO = args.cli, args.repo
    unittest.main(argv=[sys.argv[0]] + rest)


if __name__ == "__main__":
    main()
