#!/usr/bin/python3
"""Hostile session files stay bounded: each is refused or scored in under 1 s of CPU and 200 MB.

The files are built here from a sample session (its meta rows) with Python's sqlite3:
  - samples alternating between u = 0.02 and 0.98 on a body 2 m wide (the widest a case
    may be): search-pattern resampling once emitted a segment per 2 mm of each jump;
  - the same on a body 200 m wide: no longer a plausible body, refused by the reader;
  - a body with one boundary skeleton point pulled 0.45 m out (its cells as large as a
    plausible body allows), palpated 10 000 times: every coverage stamp once flooded the
    whole grid; pulled 50 m out, it is refused;
  - jumps across the body every tick on one line, then on another: two strips of 100 000
    points each, whose spacing once compared every point of one with every point of the
    other (10^10 distances).

Run:
    /usr/bin/python3 tests/cli/test_hostile_sessions.py --cli PATH/palpa-cli --repo REPO
"""

import argparse
import json
import os
import random
import resource
import shutil
import sqlite3
import subprocess
import sys
import tempfile
import unittest

CLI = None
REPO = None
SECONDS = 1.0        # of CPU per hostile file
MEGABYTES = 200      # per hostile file
LONG_MEGABYTES = 300  # a million samples


def flat_body(width, rows=5, cols=5, pulled=None):
    """A flat body `width` m across on z = 0, 20 mm thick in the middle; `pulled` moves the
    first boundary point that far along -x."""
    medial, radius = [], []
    for i in range(rows):
        for j in range(cols):
            x = -width / 2 + width * i / (rows - 1)
            y = -width / 2 + width * j / (cols - 1)
            medial.append([x, y, 0.0])
            radius.append(0.0 if i in (0, rows - 1) or j in (0, cols - 1) else 0.01)
    if pulled:
        medial[0][0] -= pulled
    return {"format": "palpa-case", "version": 1, "title": "hostile",
            "bodies": [{"id": "b", "rows": rows, "cols": cols, "medial": medial, "radius": radius,
                        "stiffness": [200.0] * (rows * cols)}]}


def session_with(path, case, samples):
    """A copy of the light sample session with `case` and `samples` (t, u, v) in contact."""
    shutil.copy(os.path.join(REPO, "data", "sessions", "light.palpa"), path)
    db = sqlite3.connect(path)
    db.execute("UPDATE meta SET value = ? WHERE key = 'case'", (json.dumps(case),))
    db.execute("DELETE FROM samples")
    last = [0.0]

    def rows():
        for k, (t, u, v) in enumerate(samples):
            last[0] = t
            yield k, t, u, v

    db.executemany("INSERT INTO samples VALUES (?, ?, 0, 0, 0.01, 0, 0, 1, 0, ?, ?, 0.005, 0, 0, 0)", rows())
    db.execute("UPDATE events SET t = ? WHERE kind = 'end'", (last[0],))
    db.commit()
    db.execute("VACUUM")
    db.close()


def timed(args):
    """(result, CPU seconds it used, the largest resident size of any child so far in MB).
    CPU time rather than wall time: CI runs other tests beside this one."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    res = subprocess.run([CLI] + args, capture_output=True, text=True, timeout=60)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    seconds = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    return res, seconds, after.ru_maxrss / 1024.0


class HostileSessions(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="palpa_hostile_")

    def tearDown(self):
        self.tmp.cleanup()

    def assertBounded(self, seconds, megabytes, what):
        print("%s: %.2f s, %.0f MB" % (what, seconds, megabytes), file=sys.stderr)
        self.assertLess(seconds, SECONDS, "%s took %.2f s" % (what, seconds))
        self.assertLess(megabytes, MEGABYTES, "%s took %.0f MB" % (what, megabytes))

    def test_jumps_across_the_widest_body_score_quickly(self):
        path = os.path.join(self.tmp.name, "jumps.palpa")
        session_with(path, flat_body(2.0), [(k * 1e-3, 0.02 if k % 2 else 0.98, 0.5) for k in range(2000)])
        res, seconds, mb = timed(["score", path])
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertBounded(seconds, mb, "2000 jumps of 1.9 m")

    def test_a_body_two_hundred_metres_wide_is_refused(self):
        path = os.path.join(self.tmp.name, "wide.palpa")
        session_with(path, flat_body(200.0), [(k * 1e-3, 0.02 if k % 2 else 0.98, 0.5) for k in range(100)])
        res, seconds, mb = timed(["score", path])
        self.assertEqual(res.returncode, 2, res.stdout)
        self.assertIn("not a plausible body", res.stderr)
        self.assertBounded(seconds, mb, "the 200 m body")

    def test_a_stretched_boundary_point_does_not_flood_every_stamp(self):
        samples = [(k * 1e-3, 0.3 + 0.4 * ((k * 7919) % 1000) / 1000.0, 0.3 + 0.4 * ((k * 104729) % 997) / 997.0)
                   for k in range(10000)]
        path = os.path.join(self.tmp.name, "stretched.palpa")
        session_with(path, flat_body(0.1, pulled=0.45), samples)
        res, seconds, mb = timed(["score", path])
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertBounded(seconds, mb, "10 000 stamps beside a cell stretched 0.45 m")
        # Pulled 50 m out (9.2 s and 1.8 GB before): not a plausible body.
        far = os.path.join(self.tmp.name, "spike.palpa")
        session_with(far, flat_body(0.1, pulled=50.0), samples)
        res, seconds, mb = timed(["score", far])
        self.assertEqual(res.returncode, 2, res.stdout)
        self.assertIn("not a plausible body", res.stderr)
        self.assertBounded(seconds, mb, "the 50 m spike")

    def test_two_strips_of_jumps_score_in_n_log_n(self):
        n = 100000
        lines = [(k * 1e-3, 0.02 if k % 2 else 0.98, 0.3) for k in range(n)]
        lines += [((n + k) * 1e-3, 0.02 if k % 2 else 0.98, 0.7) for k in range(n)]
        path = os.path.join(self.tmp.name, "strips.palpa")
        session_with(path, flat_body(0.1), lines)
        res, seconds, mb = timed(["score", path, "--json"])
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertBounded(seconds, mb, "two strips of 100 000 jumps")
        # The strips lie 0.4 of the 0.1 m body apart, on a flat top: 40 mm.
        spacing = json.loads(res.stdout)["pattern"]["strip_spacing_mm"]
        self.assertAlmostEqual(spacing, 40.0, delta=0.5)


class LongSessions(unittest.TestCase):
    """Memory per sample is bounded: a million samples in contact (16 minutes at 1 kHz)
    score in under 300 MB, whether the finger rasters slowly over the body or jumps to a
    random point of it every tick (two search-pattern segments a sample)."""

    def score_a_million(self, what, sample):
        def samples():  # generated as written: this process stays small, and so its forked child
            for k in range(1000000):
                yield (k * 1e-3,) + sample(k)
        with tempfile.TemporaryDirectory(prefix="palpa_long_") as d:
            path = os.path.join(d, "million.palpa")
            session_with(path, flat_body(0.1), samples())
            res, seconds, mb = timed(["score", path])
            print("a million samples, %s: %.2f s of CPU, %.0f MB" % (what, seconds, mb), file=sys.stderr)
            self.assertEqual(res.returncode, 0, res.stderr)
            self.assertLess(mb, LONG_MEGABYTES)

    def test_a_million_samples_score_in_under_300_mb(self):
        def raster(k):
            along = (k * 0.0005) % 2.0  # 0.05 mm a tick along u, back and forth
            row = int(k * 0.0005 / 2.0)
            return 0.2 + 0.6 * (along if along < 1.0 else 2.0 - along), 0.2 + (row * 0.03) % 0.6
        self.score_a_million("a slow raster", raster)

    def test_memory_does_not_grow_with_the_ticks_of_alternating_jumps(self):
        # Two points 96 mm apart every tick: a stamp, and so a path point, per tick. The path
        # keeps at most 2^20 points and thins past that, so twice the ticks cost no more.
        peaks = []
        with tempfile.TemporaryDirectory(prefix="palpa_long_") as d:
            for n in (1100000, 2200000):
                path = os.path.join(d, "jumps%d.palpa" % n)
                session_with(path, flat_body(0.1), ((k * 1e-3, 0.02 if k % 2 else 0.98, 0.5) for k in range(n)))
                # The scorer's own peak: a fresh parent whose only child it is.
                probe = ("import resource, subprocess, sys; r = subprocess.run(sys.argv[1:], capture_output=True); "
                         "print(r.returncode, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)")
                res = subprocess.run([sys.executable, "-c", probe, CLI, "score", path], capture_output=True,
                                     text=True, timeout=120)
                code, kb = res.stdout.split()
                self.assertEqual(code, "0", res.stderr)
                print("%d alternating jumps: %.0f MB" % (n, int(kb) / 1024.0), file=sys.stderr)
                peaks.append(int(kb) / 1024.0)
                os.remove(path)
        self.assertLess(peaks[1], peaks[0] + 25.0, peaks)

    def test_a_million_random_jumps_score_in_under_300_mb(self):
        rnd = random.Random(7)
        self.score_a_million("a random jump every tick", lambda k: (rnd.uniform(0.02, 0.98), rnd.uniform(0.02, 0.98)))


def main():
    global CLI, REPO
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cli", required=True)
    ap.add_argument("--repo", required=True)
    ap.add_argument("--sanitized", action="store_true",
                    help="the command is built with ASan + UBSan: allow 8 times the CPU time and twice the memory")
    args, rest = ap.parse_known_args()
    if args.sanitized:
        global SECONDS, MEGABYTES, LONG_MEGABYTES
        SECONDS *= 8
        MEGABYTES *= 2
        LONG_MEGABYTES *= 2
    CLI = os.path.abspath(args.cli)
    REPO = os.path.abspath(args.repo)
    prog = unittest.main(argv=[sys.argv[0]] + rest, exit=False)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
