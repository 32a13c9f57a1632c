#!/usr/bin/env python3
"""palpa --bench, end to end under Xvfb on the smallest Table 1 scenes: the table and the
CSV have one row per scene and mode, frames were drawn (positive frame rates), bodies were
re-tessellated (the finger deformed them), the haptic loop ticked, and the frame breakdown
adds up to no more than the frame. No timing thresholds: the rates depend on the machine.

Run: python3 tests/ui/test_frame_bench.py --gui build/release/app/gui/palpa --xvfb-run xvfb-run
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile
import unittest

GUI = None
XVFB_RUN = None


def bench(args):
    return subprocess.run([XVFB_RUN, "-a", GUI, "--bench"] + args, capture_output=True, text=True, timeout=300)


class FrameBench(unittest.TestCase):
    def test_smallest_scenes_give_rows_with_frames_and_haptic_ticks(self):
        with tempfile.TemporaryDirectory(prefix="palpa_framebench_") as d:
            out = os.path.join(d, "frames.csv")
            res = bench(["--seconds", "0.3", "--max-bodies", "1", "--csv", out])
            self.assertEqual(res.returncode, 0, res.stderr)
            with open(out, newline="") as f:
                rows = list(csv.DictReader(f))
        # Table 1's two single-body scenes (49 and 105 MAT points), dynamics on and off.
        self.assertEqual([(r["bodies"], r["mat_points"], r["dynamics"]) for r in rows],
                         [("1", "49", "1"), ("1", "49", "0"), ("1", "105", "1"), ("1", "105", "0")])
        for r in rows:
            frames = int(r["frames"])
            self.assertGreater(frames, 0, r)
            self.assertGreater(float(r["fps_mean"]), 0.0, r)
            self.assertGreater(float(r["fps_p5"]), 0.0, r)
            # fps p5 is by definition 1 / p95 frame time (both rounded in the CSV: compare relatively)
            self.assertAlmostEqual(float(r["fps_p5"]), 1000.0 / float(r["frame_p95_ms"]),
                                   delta=0.01 * float(r["fps_p5"]) + 0.1)
            self.assertGreater(float(r["render_ms"]), 0.0, r)  # frames drew something
            self.assertGreater(float(r["bodies_changed_per_frame"]), 0.0, r)  # the finger deformed the body
            self.assertEqual(r["view"], "all", r)
            self.assertEqual(float(r["bodies_drawn_per_frame"]), 1.0, r)  # one body, in view: never culled
            self.assertGreater(float(r["cpu_ms_per_frame"]), 0.0, r)
            self.assertGreater(int(r["haptic_ticks"]), 0, r)
            self.assertLessEqual(int(r["haptic_missed"]), int(r["haptic_ticks"]), r)
            # the parts of a frame cannot take longer than the mean frame
            parts = float(r["tessellate_ms"]) + float(r["upload_ms"]) + float(r["render_ms"])
            self.assertLessEqual(parts, 1000.0 / float(r["fps_mean"]) + 1e-6, r)
            # what the frame drew, and how far from the surfaces (a body filling the view keeps
            # the tolerance's grid: within about a pixel)
            self.assertGreater(float(r["triangles_per_frame"]), 0.0, r)
            self.assertGreaterEqual(float(r["deviation_px"]), 0.0, r)
            self.assertLess(float(r["deviation_px"]), 2.0, r)
            self.assertEqual(float(r["detail_px"]), 0.5, r)
        self.assertIn("bodies", res.stdout)
        self.assertEqual(sum(1 for line in res.stdout.splitlines() if line.strip().startswith("1 ")), 4, res.stdout)

    def test_bench_options_without_bench_are_refused(self):
        for option in (["--seconds", "1"], ["--no-overlay"], ["--detail-px", "4"]):
            res = subprocess.run([GUI] + option, capture_output=True, text=True, timeout=60)
            self.assertEqual(res.returncode, 2)
            self.assertIn("--bench", res.stderr)

    def test_the_level_of_detail_thins_the_many_small_bodies(self):
        # Table 1's 10-body scene, each body small on screen: the level of detail draws fewer
        # triangles than full detail (--detail-px 0), and the header says which was measured.
        with tempfile.TemporaryDirectory(prefix="palpa_framebench_") as d:
            rows = {}
            for px in ("0", "0.5"):
                out = os.path.join(d, "frames.csv")
                res = bench(["--seconds", "0.3", "--max-bodies", "10", "--detail-px", px, "--csv", out])
                self.assertEqual(res.returncode, 0, res.stderr)
                self.assertIn("level of detail " + ("off" if px == "0" else "0.5 px"), res.stdout)
                with open(out, newline="") as f:
                    rows[px] = [r for r in csv.DictReader(f) if r["bodies"] == "10"]
        self.assertEqual(len(rows["0"]), 2)
        for full, coarse in zip(rows["0"], rows["0.5"]):
            self.assertLess(2.0 * float(coarse["triangles_per_frame"]), float(full["triangles_per_frame"]))
            self.assertLess(float(coarse["deviation_px"]), 2.0)

    def test_the_overlay_can_be_left_out_and_the_rows_say_so(self):
        with tempfile.TemporaryDirectory(prefix="palpa_framebench_") as d:
            rows = {}
            for flag in ([], ["--no-overlay"]):
                out = os.path.join(d, "frames.csv")
                res = bench(["--seconds", "0.3", "--max-bodies", "1", "--csv", out] + flag)
                self.assertEqual(res.returncode, 0, res.stderr)
                self.assertIn("coverage overlay " + ("off" if flag else "on"), res.stdout)
                with open(out, newline="") as f:
                    rows[bool(flag)] = list(csv.DictReader(f))
        self.assertEqual({r["overlay"] for r in rows[False]}, {"1"})
        self.assertEqual({r["overlay"] for r in rows[True]}, {"0"})
        self.assertTrue(all(int(r["frames"]) > 0 for r in rows[True]))


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--gui", required=True)
    parser.add_argument("--xvfb-run", required=True)
    args, rest = parser.parse_known_args()
    GUI = os.path.abspath(args.gui)
    XVFB_RUN = args.xvfb_run
    unittest.main(argv=[sys.argv[0]] + rest)
