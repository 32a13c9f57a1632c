#!/usr/bin/env python3
"""palpa-cli probe, end to end.

Run: python3 tests/cli/test_probe_cli.py --cli build/release/app/palpa-cli --repo .

The probe checks use data/cases/flat-5x5.json, whose truth is closed-form: the skeleton
is the plane z = 0 over [-0.05, 0.05]^2 on a uniform grid (so u = (x + 0.05) / 0.1), the
radius r = 0.02 (1 - a^2)(1 - b^2) with a = x / 0.05, b = y / 0.05 (which the bicubic
spline reproduces exactly) and the stiffness 200 N/m. A probe (x, y, z) over the body
has depth r(x, y) - |z| and, without shear, force 200 * depth * (0, 0, sign z).
"""
import argparse
import csv
import io
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
TIMEOUT = 120


def run(args, timeout=TIMEOUT):
    return subprocess.run([CLI] + args, capture_output=True, text=True, timeout=timeout)


def flat_radius(x, y):
    a, b = x / 0.05, y / 0.05
    return 0.02 * (1 - a * a) * (1 - b * b)


class Probe(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="palpa_probe_")
        self.case = os.path.join(REPO, "data", "cases", "flat-5x5.json")

    def tearDown(self):
        self.tmp.cleanup()

    def points(self, rows, name="pts.csv", header="x,y,z"):
        path = os.path.join(self.tmp.name, name)
        with open(path, "w") as fh:
            fh.write(header + "\n")
            for r in rows:
                fh.write(",".join(repr(v) for v in r) + "\n")
        return path

    def probe(self, rows, *extra):
        res = run(["probe", self.case, "--points", self.points(rows)] + list(extra))
        self.assertEqual(res.returncode, 0, res.stderr)
        table = list(csv.DictReader(io.StringIO(res.stdout)))
        self.assertEqual(res.stdout.splitlines()[0], "x,y,z,inside,body,u,v,depth,fx,fy,fz")
        self.assertEqual(len(table), len(rows))
        return table

    def test_flat_case_matches_the_closed_form(self):
        rows = [(x, y, z) for x in (-0.03, 0.0, 0.017) for y in (-0.04, 0.01, 0.025)
                for z in (0.019, 0.006, -0.002, -0.011)]
        # The fast method converges to round-off; the bisection at 30 levels leaves its
        # foot point within 2^-30 of the truth in (u, v), i.e. about 1e-10 m here.
        for method, tol_depth, tol_force in (("fast", 1e-9, 1e-9), ("bisect", 1e-8, 1e-6)):
            extra = ["--no-shear"] + (["--method", "bisect", "--bisect-levels", "30"] if method == "bisect" else [])
            for r, out in zip(rows, self.probe(rows, *extra)):
                x, y, z = r
                depth = flat_radius(x, y) - abs(z)
                with self.subTest(method=method, probe=r):
                    self.assertAlmostEqual(float(out["depth"]), depth, delta=tol_depth)
                    self.assertAlmostEqual(float(out["u"]), (x + 0.05) / 0.1, delta=1e-9)
                    self.assertAlmostEqual(float(out["v"]), (y + 0.05) / 0.1, delta=1e-9)
                    inside = depth >= 0
                    self.assertEqual(out["inside"], "1" if inside else "0")
                    self.assertEqual(out["body"], "flat" if inside else "")
                    fz = 200.0 * depth * math.copysign(1.0, z) if inside else 0.0
                    self.assertAlmostEqual(float(out["fz"]), fz, delta=tol_force * max(1.0, abs(fz)))
                    self.assertAlmostEqual(float(out["fx"]), 0.0, delta=tol_force)

    def test_shear_adds_to_the_push_and_the_cap_holds(self):
        rows = [(0.0, 0.0, z) for z in (0.018, 0.012, 0.006, 0.0005)]
        plain = self.probe(rows, "--no-shear")
        sheared = self.probe(rows)
        previous = 0.0
        for p, s in zip(plain, sheared):
            self.assertGreater(float(s["fz"]), float(p["fz"]))  # shear pushes out too
            self.assertGreater(float(s["fz"]), previous)         # and grows with depth
            previous = float(s["fz"])
        capped = self.probe(rows, "--max-force", "1.5")
        for c in capped:
            f = math.sqrt(sum(float(c[k]) ** 2 for k in ("fx", "fy", "fz")))
            self.assertLessEqual(f, 1.5 + 1e-12)

    def test_far_probe_is_culled_with_empty_fields(self):
        out = self.probe([(1.0, 1.0, 1.0)])[0]
        self.assertEqual((out["inside"], out["body"], out["u"], out["depth"]), ("0", "", "", ""))
        self.assertEqual(float(out["fz"]), 0.0)

    def test_bad_inputs_are_one_line_errors(self):
        bad_header = self.points([(0, 0, 0)], "bad.csv", header="x,y")
        cases = [
            (["probe", self.case, "--points", bad_header], "bad.csv"),
            (["probe", self.case, "--points", os.path.join(self.tmp.name, "missing.csv")], "missing.csv"),
            (["probe", os.path.join(self.tmp.name, "nocase.json"), "--points", bad_header], "nocase.json"),
            (["probe", self.case, "--points", bad_header, "--method", "magic"], "method"),
            (["probe", self.case], "points"),
        ]
        for args, word in cases:
            with self.subTest(args=args):
                res = run(args)
                self.assertEqual(res.returncode, 2, res.stderr)
                lines = [ln for ln in res.stderr.splitlines() if ln.strip()]
                self.assertEqual(len(lines), 1, res.stderr)
                self.assertIn(word, lines[0])

    def test_tumour_outside_its_body_is_rejected_by_validate_and_probe(self):
        import json
        with open(os.path.join(REPO, "data", "cases", "flat-5x5.json")) as fh:
            case = json.load(fh)
        case["tumors"] = [{"body": "flat", "center": [0.0, 0.0, 0.03], "radius": 0.004, "stiffness": 1000}]
        path = os.path.join(self.tmp.name, "tumour-out.json")
        with open(path, "w") as fh:
            json.dump(case, fh)
        for args in (["validate", path], ["probe", path, "--points", self.points([(0, 0, 0)])]):
            res = run(args)
            self.assertEqual(res.returncode, 2, res.stderr)
            self.assertIn("/tumors/0", res.stderr)
            self.assertIn("not inside", res.stderr)


class Simulate(unittest.TestCase):
    """palpa-cli simulate: a scripted press through the default case."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="palpa_sim_")
        self.case = os.path.join(REPO, "data", "cases", "default.json")
        self.traj = os.path.join(self.tmp.name, "traj.csv")
        with open(self.traj, "w") as fh:
            fh.write("t,x,y,z\n")
            for k in range(21):  # down 30 mm over the tumour in 1 s, back out in 1 s
                depth = 0.003 * (k if k <= 10 else 20 - k)
                fh.write("%r,0.0245,0.02,%r\n" % (0.1 * k, 0.046 - depth))

    def tearDown(self):
        self.tmp.cleanup()

    def simulate(self, out, *extra, case=None):
        res = run(["simulate", case or self.case, "--trajectory", self.traj, "--out", out] + list(extra))
        self.assertEqual(res.returncode, 0, res.stderr)
        with open(out, "rb") as fh:
            return fh.read()

    def test_fast_runs_are_byte_identical_and_press_the_tumour(self):
        a = self.simulate(os.path.join(self.tmp.name, "a.csv"), "--fast")
        b = self.simulate(os.path.join(self.tmp.name, "b.csv"))
        self.assertEqual(a, b)
        rows = list(csv.DictReader(io.StringIO(a.decode())))
        self.assertEqual(len(rows), 2001)  # t = 0 .. 2 s at 1 kHz
        self.assertEqual(list(rows[0].keys()), ["t", "x", "y", "z", "fx", "fy", "fz", "body", "u", "v", "depth",
                                                "buttons", "overrun", "fault"])
        deepest = max(rows, key=lambda r: float(r["depth"]))
        self.assertEqual(deepest["body"], "breast")
        # The tumour is felt: the same press on the case without it pushes back far less
        # (about 1.4 times less at 28 mm: BENCHMARKS.md, "The tumour felt by light and deep presses").
        with open(self.case) as fh:
            without = json.load(fh)
        without["tumors"] = []
        plain_case = os.path.join(self.tmp.name, "plain.json")
        with open(plain_case, "w") as fh:
            json.dump(without, fh)
        plain_rows = list(csv.DictReader(io.StringIO(
            self.simulate(os.path.join(self.tmp.name, "p.csv"), "--fast", case=plain_case).decode())))
        plain_deepest = max(plain_rows, key=lambda r: float(r["depth"]))
        self.assertAlmostEqual(float(plain_deepest["depth"]), float(deepest["depth"]), places=6)
        self.assertGreater(float(deepest["fz"]), 1.25 * float(plain_deepest["fz"]))
        self.assertEqual(rows[-1]["body"], "")           # and the probe left again
        plain = self.simulate(os.path.join(self.tmp.name, "c.csv"), "--no-shear", "--no-dynamics", "--rate", "500")
        self.assertEqual(len(plain.decode().splitlines()), 1 + 1001)

    def test_realtime_run_reports_its_scheduling_and_loop_statistics(self):
        out = os.path.join(self.tmp.name, "rt.csv")
        res = run(["simulate", self.case, "--trajectory", self.traj, "--out", out, "--realtime"])
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertIn("SCHED_FIFO", res.stderr)           # granted or refused, said either way
        self.assertRegex(res.stderr, r"\d+ missed deadlines? \(")
        self.assertRegex(res.stderr, r"Period p50 [0-9.]+ us, p99 [0-9.]+ us")
        with open(out) as fh:
            rows = list(csv.DictReader(fh))
        # About 2 s at 1 kHz plus the closing ramp; a loaded machine (ctest runs two tests at
        # once, maybe another real-time loop) can cost the loop ticks, never add any.
        self.assertGreater(len(rows), 1000)
        self.assertLess(len(rows), 2300)
        last = rows[-1]
        self.assertEqual((float(last["fx"]), float(last["fy"]), float(last["fz"])), (0.0, 0.0, 0.0))
        both = run(["simulate", self.case, "--trajectory", self.traj, "--out", out, "--realtime", "--fast"])
        self.assertEqual(both.returncode, 2)

    def test_marks_are_checked_and_kept(self):
        marks = os.path.join(self.tmp.name, "marks.csv")
        with open(marks, "w") as fh:
            fh.write("t,x,y,z\n1.2,0.0245,0.02,0.03\n")
        out = os.path.join(self.tmp.name, "m.csv")
        self.simulate(out, "--marks", marks)
        with open(out + ".marks.csv") as fh:
            self.assertEqual(fh.read().splitlines()[1].split(",")[0], "1.2")

    def test_session_records_the_run_and_its_marks_for_scoring(self):
        marks = os.path.join(self.tmp.name, "marks.csv")
        with open(marks, "w") as fh:  # one mark over the tumour, one far from it
            fh.write("t,x,y,z\n1.2,0.0245,0.02,0.046\n1.5,-0.05,-0.05,0.02\n")
        csv_out = os.path.join(self.tmp.name, "s.csv")
        session = os.path.join(self.tmp.name, "s.palpa")
        res = run(["simulate", self.case, "--trajectory", self.traj, "--out", csv_out, "--session", session,
                   "--marks", marks, "--trainee", "sim-1"])
        self.assertEqual(res.returncode, 0, res.stderr)
        db = sqlite3.connect("file:%s?mode=ro" % session, uri=True)
        samples = [r[1:8] + (r[11],) for r in sample_rows(db)]
        with open(csv_out) as fh:
            rows = list(csv.DictReader(fh))
        self.assertEqual(len(samples), len(rows))  # the same ticks, within format 2's units
        half_unit = {"t": 0.5e-6, "x": 0.5e-6, "y": 0.5e-6, "z": 0.5e-6, "fx": 0.5e-3, "fy": 0.5e-3, "fz": 0.5e-3}
        for (t, x, y, z, fx, fy, fz, depth), row in zip(samples[::97], rows[::97]):
            for value, k in zip((t, x, y, z, fx, fy, fz), ("t", "x", "y", "z", "fx", "fy", "fz")):
                self.assertLessEqual(abs(value - float(row[k])), half_unit[k] * (1 + 1e-9), k)
            self.assertLessEqual(abs((depth or 0.0) - float(row["depth"])), 0.5e-6 * (1 + 1e-9))
        events = db.execute("select kind, mark, t from events order by t, id").fetchall()
        self.assertEqual([e[0] for e in events], ["start", "mark", "mark", "end"])
        self.assertEqual((events[1][1], events[1][2]), (1, 1.2))
        meta = dict(db.execute("select key, value from meta"))
        self.assertEqual(meta["trainee"], "sim-1")
        db.close()
        scored = run(["score", session, "--json"])
        self.assertEqual(scored.returncode, 0, scored.stderr)
        s = json.loads(scored.stdout)
        self.assertEqual(s["sensitivity"], 1.0)       # the mark over the tumour found it
        self.assertEqual(s["false_positives"], 1)     # the far one did not
        again = run(["simulate", self.case, "--trajectory", self.traj, "--session", session])
        self.assertEqual(again.returncode, 2)         # a recorded session is never overwritten
        self.assertIn("exists", again.stderr)
        neither = run(["simulate", self.case, "--trajectory", self.traj])
        self.assertEqual(neither.returncode, 2)
        self.assertIn("--out or --session", neither.stderr)

    def test_bad_trajectories_are_one_line_errors(self):
        bad = os.path.join(self.tmp.name, "bad.csv")
        for text, word in (("t,x,y\n0,0,0\n", "header"), ("t,x,y,z\n0,0,0,0\n0,1,1,1\n", "increase"),
                           ("t,x,y,z\n0,0,0,0\n", "two rows")):
            with open(bad, "w") as fh:
                fh.write(text)
            res = run(["simulate", self.case, "--trajectory", bad, "--out", os.path.join(self.tmp.name, "x.csv")])
            self.assertEqual(res.returncode, 2, res.stderr)
            lines = [ln for ln in res.stderr.splitlines() if ln.strip()]
            self.assertEqual(len(lines), 1, res.stderr)
            self.assertIn("bad.csv", lines[0])
            self.assertIn(word, lines[0])


def main():
    global CLI, REPO
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cli", required=True)
    ap.add_argument("--repo", required=True)
    args, rest = ap.parse_known_args()
    CLI = os.path.abspath(args.cli)
    REPO = os.path.abspath(args.repo)
    prog = unittest.main(argv=[sys.argv[0]] + rest, exit=False)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
