#!/usr/bin/env python3
"""palpa-cli bench accuracy, dynamics, tessellation, fidelity and contrast-modes, end to end: each runs a
small configuration and its CSV figures are checked against properties that must hold (the
fast foot point at round-off, the exact integrator exact, tessellation within tolerance,
the calibrated force within 10 % of the committed finite-element curves).

Run: python3 tests/cli/test_bench_cli.py --cli build/release/app/palpa-cli --repo .
(Not run in the sanitizer build: the benchmarks exercise the same core code as the unit
tests, and instrumented they take minutes.)
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile
import unittest

CLI = None
REPO = None
TIMEOUT = 600


def run(args, timeout=TIMEOUT):
    return subprocess.run([CLI] + args, capture_output=True, text=True, timeout=timeout)


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
            # The least-norm modification on uniform cubic knots: 1.78 at a knot with all 16 points; one point alone blows up.
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
            self.assertEqual({r["state"] for r in rows}, {"rest", "pressed", "drawn"})
            # The fingertip dent on the refined net as the trainee window draws it: the grid
            # that follows the knots needs a fraction of the uniform grid's triangles.
            drawn = [r for r in rows if r["state"] == "drawn" and abs(float(r["tolerance_m"]) - 2e-4) < 1e-9]
            self.assertEqual(len(drawn), 1)
            self.assertLess(3 * int(drawn[0]["triangles"]), int(drawn[0]["uniform_triangles"]), drawn[0])
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


class BenchContrastModes(unittest.TestCase):
    def test_every_case_has_both_modes_with_sound_readings(self):
        with tempfile.TemporaryDirectory(prefix="palpa_bench_") as d:
            res = run(["bench", "contrast-modes", "--out", d])
            self.assertEqual(res.returncode, 0, res.stderr)
            with open(os.path.join(d, "contrast-modes.csv")) as fh:
                rows = list(csv.DictReader(fh))
            self.assertEqual(len(rows), 5 * 6)  # five cases, three settings per mode
            for r in rows:
                over, away = float(r["reading_over"]), float(r["reading_away"])
                self.assertGreater(away, 0.0, r)
                self.assertAlmostEqual(float(r["contrast"]), over / away - 1.0, places=9)
            # Independent of the bench: a stiff mass under the tissue makes the press
            # stiffer over it than 12 mm away in force mode, and the finger sinks less there.
            for r in rows:
                if r["mode"] == "force" and r["case"] in ("default.json", "ladder-1.json"):
                    self.assertGreater(float(r["contrast"]), 0.0, r)
                    self.assertLess(float(r["depth_over_m"]), float(r["depth_away_m"]), r)


class BenchImport(unittest.TestCase):
    def test_short_form_reports_time_beside_fit_error(self):
        # The short form (64^3, 2 x 7938 triangles); the long form is the default (256^3, 2 x 199712).
        with tempfile.TemporaryDirectory(prefix="palpa_bench_import_") as d:
            res = run(["bench", "import", "--voxels", "64", "--mesh-points", "64", "--out", d], timeout=300)
            self.assertEqual(res.returncode, 0, res.stderr)
            with open(os.path.join(d, "import.csv")) as fh:
                rows = list(csv.DictReader(fh))
            self.assertEqual(len(rows), 2 + 7)
            self.assertEqual([r["grid"] for r in rows[2:]], ["9x11", "13x15", "17x17", "25x25", "33x33", "49x49", "65x65"])
            for r in rows:
                self.assertGreater(float(r["seconds"]), 0.0, r)
                self.assertGreater(float(r["peak_rss_mb"]), 0.0, r)
                # 4 mm voxels: the fit stays within half a voxel + 0.2 mm of what it read.
                self.assertLess(float(r["top_interior_max_mm"]), 2.2, r)
                self.assertLess(float(r["bottom_interior_max_mm"]), 2.2, r)


class BenchTable1(unittest.TestCase):
    def test_the_table1_scenes_run_in_kpa_with_either_indenter_and_refuse_a_finger_on_springs(self):
        with tempfile.TemporaryDirectory(prefix="palpa_bench_t1_") as d:
            for extra in ([], ["--tissue", "kpa"], ["--tissue", "kpa", "--indenter", "finger"]):
                out = os.path.join(d, "t1.csv")
                res = run(["bench", "table1", "--seconds", "0.2", "--realtime-seconds", "0", "--csv", out, *extra],
                          timeout=300)
                self.assertEqual(res.returncode, 0, res.stdout + res.stderr)
                self.assertEqual(("calibrated law" in res.stdout), bool(extra), res.stdout[:300])
                with open(out) as fh:
                    rows = list(csv.DictReader(fh))
                self.assertEqual([int(r["bodies"]) for r in rows], [1, 1, 4, 10, 17, 35])
                for r in rows:
                    self.assertGreater(float(r["step_p99_us_dyn"]), 0.0, r)
                    self.assertGreater(int(r["contact_ticks"]), 0, r)  # the palpation touched the bodies
            res = run(["bench", "table1", "--indenter", "finger"])
            self.assertEqual(res.returncode, 2)
            self.assertIn("--indenter finger needs --tissue kpa", res.stderr)
            self.assertEqual(len(res.stderr.strip().splitlines()), 1, res.stderr)


class BenchFidelity(unittest.TestCase):
    def test_calibrated_law_is_within_ten_percent_of_every_reference_and_the_papers_is_not(self):
        with tempfile.TemporaryDirectory(prefix="palpa_bench_fid_") as d:
            res = run(["bench", "fidelity", "--out", d], timeout=300)
            self.assertEqual(res.returncode, 0, res.stdout + res.stderr)
            with open(os.path.join(d, "fidelity.csv")) as fh:
                rows = list(csv.DictReader(fh))
            self.assertEqual(list(rows[0].keys()), ["reference", "law", "thickness_m", "depth_m", "depth_share",
                                                    "fem_n", "palpa_n", "error"])
            refs = {r["reference"] for r in rows}
            self.assertIn("slab40_E5k_flat_neohooke.csv", refs)
            self.assertIn("slab20_E5k_flat_linear.csv", refs)
            with open(os.path.join(REPO, "data", "reference", "slab40_E5k_flat_neohooke.csv")) as fh:
                fem = {float(r["depth_m"]): float(r["force_n"]) for r in csv.DictReader(fh)}
            for r in rows:
                # The error column is what the two force columns say, against the committed file.
                self.assertAlmostEqual(float(r["error"]), float(r["palpa_n"]) / float(r["fem_n"]) - 1.0, places=4)
                if r["reference"] == "slab40_E5k_flat_neohooke.csv":
                    self.assertAlmostEqual(float(r["fem_n"]), fem[float(r["depth_m"])], places=5)
                if r["law"] == "calibrated":
                    self.assertLessEqual(abs(float(r["error"])), 0.10, r)
            paper_10 = [r for r in rows if r["law"] == "paper" and r["reference"] == "slab40_E5k_flat_neohooke.csv"
                        and abs(float(r["depth_m"]) - 0.004) < 1e-9]
            self.assertEqual(len(paper_10), 1)
            self.assertGreater(float(paper_10[0]["error"]), 0.10)  # the shear springs overshoot
            with open(os.path.join(d, "fidelity_contrast.csv")) as fh:
                contrast = list(csv.DictReader(fh))
            swept = 0
            for mm in (20, 30, 40):
                with open(os.path.join(REPO, "data", "reference", f"contrast_slab{mm}_E5k_linear.csv")) as fh:
                    n = len(list(csv.DictReader(fh)))
                swept += n
                self.assertEqual(len([r for r in contrast if abs(float(r["thickness_m"]) - mm / 1000) < 1e-9]), n, mm)
            self.assertEqual(len(contrast), swept)
            for r in contrast:
                fem, model = float(r["fem_contrast"]), float(r["calibrated_contrast"])
                self.assertLessEqual(abs(model - fem), max(0.2 * (fem - 1.0), 0.02), r)
                # Onset: the first press with contrast >= 1.10; the linear FEM's is at first touch or never.
                self.assertEqual(r["fem_onset_m"] == "", fem < 1.10, r)
                if r["fem_onset_m"] != "":
                    self.assertEqual(float(r["fem_onset_m"]), 0.0)
                self.assertEqual(r["calibrated_onset_m"] == "", r["fem_onset_m"] == "", r)
                if r["calibrated_onset_m"] != "":
                    self.assertLessEqual(float(r["calibrated_onset_m"]), 0.002, r)
            with open(os.path.join(d, "fidelity_lateral.csv")) as fh:
                lateral = list(csv.DictReader(fh))
            with open(os.path.join(REPO, "data", "reference", "lateral_slab40_E5k_linear.csv")) as fh:
                reference = list(csv.DictReader(fh))
            self.assertEqual(len(lateral), len(reference))
            for r, ref in zip(lateral, reference):
                self.assertAlmostEqual(float(r["fem_contrast"]), float(ref["contrast"]), places=4)
                fem, model = float(r["fem_contrast"]), float(r["calibrated_contrast"])
                self.assertLessEqual(abs(model - fem), max(0.2 * (fem - 1.0), 0.02), r)
            self.assertIn("half-width: FEM", res.stdout)
            # Growing with the press: the neo-Hookean twins, each row the 5x file over its 1x
            # twin at that press; under the pad within the mark at every press.
            with open(os.path.join(d, "fidelity_growth.csv")) as fh:
                growth = list(csv.DictReader(fh))
            self.assertEqual(list(growth[0].keys())[-1], "indenter")
            pads = [r for r in growth if r["indenter"] == "pad"]
            self.assertGreaterEqual(len(pads), 15)
            self.assertTrue(any(r["indenter"] == "finger" for r in growth))
            with open(os.path.join(REPO, "data", "reference", "slab40_E5k_flat_neohooke_pinned_r10d20_incl5x.csv")) as f5, \
                    open(os.path.join(REPO, "data", "reference", "slab40_E5k_flat_neohooke_pinned_r10d20_incl1x.csv")) as f1:
                stiff = {float(r["depth_m"]): float(r["force_n"]) for r in csv.DictReader(f5)}
                plain = {float(r["depth_m"]): float(r["force_n"]) for r in csv.DictReader(f1)}
            checked = 0
            for r in pads:
                fem, model = float(r["fem_contrast"]), float(r["calibrated_contrast"])
                self.assertLessEqual(abs(model - fem), max(0.2 * (fem - 1.0), 0.02), r)
                if abs(float(r["inclusion_radius_m"]) - 0.010) < 1e-9:
                    depth = min(stiff, key=lambda k: abs(k - float(r["press_m"])))
                    self.assertAlmostEqual(fem, stiff[depth] / plain[depth], places=4)
                    checked += 1
            self.assertEqual(checked, 4)
            with open(os.path.join(d, "fidelity.png"), "rb") as fh:
                self.assertEqual(fh.read(8), b"\x89PNG\r\n\x1a\n")
            # A folder without the curves: one line naming the file, exit 2.
            res = run(["bench", "fidelity", "--reference", d, "--out", d])
            self.assertEqual(res.returncode, 2)
            self.assertIn("slab40_E5k_flat_neohooke.csv", res.stderr)
            self.assertEqual(len(res.stderr.strip().splitlines()), 1, res.stderr)


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
