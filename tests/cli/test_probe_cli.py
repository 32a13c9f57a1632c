#!/usr/bin/env python3
"""palpa-cli probe and palpa-cli bench accuracy, end to end.

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
import math
import os
import subprocess
import sys
import tempfile
import unittest

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


class BenchAccuracy(unittest.TestCase):
    def test_small_run_writes_csv_and_png_with_sound_figures(self):
        with tempfile.TemporaryDirectory(prefix="palpa_bench_") as d:
            res = run(["bench", "accuracy", "--probes", "60", "--out", d], timeout=300)
            self.assertEqual(res.returncode, 0, res.stderr)
            with open(os.path.join(d, "accuracy.csv")) as fh:
                rows = list(csv.DictReader(fh))
            self.assertEqual(list(rows[0].keys()),
                             ["body", "method", "levels", "queries", "ns_per_query", "depth_error_max_m",
                              "depth_error_median_m", "param_error_max", "inside_wrong"])
            bodies = {r["body"] for r in rows}
            self.assertEqual(bodies, {"flat", "curved", "concave", "wavy"})
            for r in rows:
                self.assertGreater(float(r["ns_per_query"]), 0.0)
                if r["method"].startswith("fast"):
                    self.assertLess(float(r["depth_error_max_m"]), 1e-9, r)
                    self.assertEqual(r["inside_wrong"], "0", r)
            flat = {int(r["levels"]): float(r["depth_error_max_m"]) for r in rows
                    if r["body"] == "flat" and r["method"] == "bisect"}
            self.assertEqual(sorted(flat), list(range(6, 21, 2)))
            self.assertLess(flat[20], flat[6] / 1000)  # the bisection halves its interval per level
            with open(os.path.join(d, "accuracy.png"), "rb") as fh:
                self.assertEqual(fh.read(8), b"\x89PNG\r\n\x1a\n")


class BenchDynamics(unittest.TestCase):
    def test_exact_integrator_is_exact_and_explicit_euler_diverges(self):
        with tempfile.TemporaryDirectory(prefix="palpa_bench_dyn_") as d:
            res = run(["bench", "dynamics", "--out", d], timeout=600)
            self.assertEqual(res.returncode, 0, res.stderr)
            with open(os.path.join(d, "dynamics.csv")) as fh:
                rows = list(csv.DictReader(fh))
            exact = [r for r in rows if r["integrator"].startswith("exact")]
            self.assertEqual(len(exact), 7)
            for r in exact:
                self.assertLess(float(r["max_error_m"]), 1e-15, r)  # 1 mm released: round-off only
                self.assertEqual(r["stable"], "1")
            explicit = {float(r["dt_s"]): r for r in rows if r["integrator"] == "explicit Euler"}
            self.assertEqual(explicit[1e-2]["stable"], "0")  # why explicit Euler is not acceptable
            with open(os.path.join(d, "modification.csv")) as fh:
                mods = {int(r["p_prime"]): r for r in csv.DictReader(fh)}
            for p, r in mods.items():
                self.assertLess(float(r["landing_error_rel"]), 1e-12, r)
            # numerics.md: 1.78 at a knot with all 16 points; one point alone blows up.
            self.assertAlmostEqual(float(mods[4]["max_dp_over_d"]), 1.7778, delta=1e-3)
            self.assertGreater(float(mods[1]["max_dp_over_d"]), 3.0)
            with open(os.path.join(d, "dynamics.png"), "rb") as fh:
                self.assertEqual(fh.read(8), b"\x89PNG\r\n\x1a\n")


class BenchTessellation(unittest.TestCase):
    def test_deviation_stays_within_tolerance_at_display_tolerances(self):
        with tempfile.TemporaryDirectory(prefix="palpa_bench_tess_") as d:
            case = os.path.join(REPO, "data", "cases", "default.json")
            res = run(["bench", "tessellation", "--case", case, "--out", d], timeout=900)
            self.assertEqual(res.returncode, 0, res.stderr)
            with open(os.path.join(d, "tessellation.csv")) as fh:
                rows = list(csv.DictReader(fh))
            self.assertEqual({r["state"] for r in rows}, {"rest", "pressed"})
            for r in rows:
                if float(r["tolerance_m"]) >= 1e-5:  # every tolerance a display would use
                    self.assertEqual(r["within"], "1", r)
                    self.assertLessEqual(float(r["max_deviation_m"]), float(r["tolerance_m"]), r)
            finer = sorted(rows, key=lambda r: (r["state"], -float(r["tolerance_m"])))
            for a, b in zip(finer, finer[1:]):
                if a["state"] == b["state"]:
                    self.assertLessEqual(int(a["triangles"]), int(b["triangles"]))  # finer tolerance, more triangles
            res = run(["bench", "tessellation", "--case", os.path.join(d, "missing.json"), "--out", d])
            self.assertEqual(res.returncode, 2)
            self.assertIn("missing.json", res.stderr)


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
