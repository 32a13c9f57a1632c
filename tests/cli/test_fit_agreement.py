#!/usr/bin/python3
"""Agreement of `palpa-cli fit --eval` with the independent Python reference.

Run:
    /usr/bin/python3 tests/cli/test_fit_agreement.py --cli PATH/palpa-cli --repo REPO [--long]
        [any unittest arguments, e.g. -v or a test name]

The reference is tests/reference/a94_reference.py (pure Python, Cox-de Boor
basis, dense Gaussian elimination with partial pivoting, plain double-sum
evaluation, derivative-formula normals).  Standard library only.

Cases
-----
* Synthetic cases written to a temporary directory (always run): grids 2xN,
  Nx2, 3xN, Nx3, 3x3, 4x4, 7x9, 12x10, 40x30; uniform and non-uniform
  spacing; flat, wavy (z = 0.02 sin cos over a 0.1 m patch), cylinder-arc,
  dome with a pole row, dome with a pole column, a body far from the origin,
  a near-duplicate column; smooth non-constant stiffness; some with explicit
  damping and/or mass, some without (defaults); one file with two bodies.
  All are valid per the case format v1 (radius exactly 0 on the grid
  boundary).  --long adds 30 pseudo-random grids (fixed seed) up to 24x24.
* Every data/cases/*.json of the repository that `palpa-cli validate`
  accepts (all its bodies; an empty or missing folder is fine; for grids
  with more than 2500 points a strided subset of the data sites is used
  unless --long).

For every case, body and surface (skeleton, top, bottom) a UV.csv is written
with: all data-site parameters (ubar_i, vbar_j) in row-major order as the
reference computes them, the four corners, points on the four edges (u or v
exactly 0 or 1; the other parameter at data sites and random values), and 50
pseudo-random points (fixed seed per case).  The CLI runs as
    palpa-cli fit CASE --body ID --surface S --eval UV.csv
(timeout 30 s) and the reference evaluates the same points.

Tolerance rule (exact)
----------------------
For each (case, body, surface) and each output channel c:
    scale_c = 1e-12 + max( max over the data grid |d_c|, max over the evaluated points |ref_c| )
where d is what the surface interpolates at the data sites (skeleton: the case
data with defaults filled in; top/bottom: R = P + rN, S = P - rN from the
reference), and ref the reference values at the UV points.  For the position
channels x, y, z the maximum is pooled over all three coordinates (one scale
for the position vector: rounding in a position scales with |P|, so a flat
patch at z = 0 is judged against the body's size, not against z = 0).
Then every value must satisfy  |cli - ref| <= 1e-9 * scale_c.
The u and v columns must equal the UV.csv values to 1e-15.
Header and row count must match exactly.

Pass-through: at the data-site parameters, the CLI's skeleton must equal the
case data (x, y, z, radius, stiffness, damping, mass; defaults mass = 1e-3,
damping = 2*0.7*sqrt(k*m) where absent) to |cli - data| <= 1e-9 * scale_c
(same scale).

On failure the worst mismatch is printed: case, body, surface, u, v, channel,
CLI value, reference value, the tolerance, and the command.
"""

import argparse
import glob
import json
import math
import os
import random
import subprocess
import sys
import tempfile
import unittest
import zlib

CLI = None
REPO = None
LONG = False
REF = None          # the a94_reference module
TIMEOUT = 30
REL_TOL = 1e-9
MAX_SITES = 2500


# ---------------------------------------------------------------------------
# Synthetic cases
# ---------------------------------------------------------------------------

def grid_params(n, warp=0.0, jitter=0.0, seed=0):
    """n increasing values in [0,1], first 0 and last 1; optional warp/jitter."""
    rnd = random.Random(seed)
    out = []
    for k in range(n):
        s = k / (n - 1)
        s = s + warp * s * (1 - s) * (s - 0.3)
        if 0 < k < n - 1 and jitter:
            s += jitter * (rnd.random() - 0.5) / (n - 1)
        out.append(s)
    return out


def make_body(bid, rows, cols, xyz, radius=None, stiffness=None, damping=None, mass=None,
              su=None, sv=None):
    """Body dict: xyz(s,t) -> 3 floats with s, t in [0,1] (grid coordinates, possibly warped).

    radius(s,t) is used in the interior only (exactly 0 on the boundary)."""
    su = su or grid_params(rows)
    sv = sv or grid_params(cols)
    med, rad, stf, dmp, mas = [], [], [], [], []
    for i in range(rows):
        for j in range(cols):
            s, t = su[i], sv[j]
            med.append([float(c) for c in xyz(s, t)])
            boundary = i in (0, rows - 1) or j in (0, cols - 1)
            rad.append(0.0 if boundary or radius is None else float(radius(s, t)))
            stf.append(500.0 if stiffness is None else float(stiffness(s, t)))
            if damping is not None:
                dmp.append(float(damping(s, t)))
            if mass is not None:
                mas.append(float(mass(s, t)))
    b = {"id": bid, "rows": rows, "cols": cols, "medial": med, "radius": rad, "stiffness": stf}
    if damping is not None:
        b["damping"] = dmp
    if mass is not None:
        b["mass"] = mas
    return b


def case_of(title, *bodies):
    return {"format": "palpa-case", "version": 1, "title": title, "bodies": list(bodies)}


def bump(s, t):
    return math.sin(math.pi * s) * math.sin(math.pi * t)


def wavy(s, t):
    x, y = 0.1 * s, 0.1 * t
    return x, y, 0.02 * math.sin(2.0 * math.pi * x / 0.1) * math.cos(math.pi * y / 0.1)


def tilted(s, t):
    return 0.1 * s, 0.06 * t, 0.01 + 0.02 * s - 0.01 * t


def cylinder(s, t):
    a = -1.0 + 2.0 * t                 # arc of 2 rad on a 4 cm cylinder, 12 cm long
    return 0.04 * math.sin(a), 0.12 * s, 0.04 * math.cos(a)


def saddle(s, t):
    x, y = 0.08 * (s - 0.5), 0.05 * (t - 0.5)
    return x, y, 10.0 * (x * x - y * y)


def dome_pole_row(s, t):
    a = 2.5 * t
    return 0.05 * s * math.cos(a), 0.05 * s * math.sin(a), 0.03 * (1.0 - s * s)


def dome_pole_col(s, t):
    return dome_pole_row(t, s)


def stiff_smooth(s, t):
    return 800.0 + 300.0 * math.cos(2.0 * s + 1.3 * t)


def synthetic_cases(long_mode):
    r1 = lambda s, t: 0.004 + 0.006 * bump(s, t)
    cases = [
        ("flat_2x5", case_of("flat 2x5", make_body(
            "b", 2, 5, tilted, stiffness=lambda s, t: 300.0 + 100.0 * t))),
        ("flat_5x2", case_of("flat 5x2", make_body(
            "b", 5, 2, tilted, stiffness=lambda s, t: 300.0 + 100.0 * s, mass=lambda s, t: 0.002))),
        ("wavy_2x9", case_of("wavy 2x9", make_body(
            "b", 2, 9, wavy, stiffness=stiff_smooth, sv=grid_params(9, warp=1.0)))),
        ("wavy_3x3", case_of("wavy 3x3", make_body("b", 3, 3, wavy, radius=r1, stiffness=stiff_smooth))),
        ("wavy_3x8_damping", case_of("wavy 3x8", make_body(
            "b", 3, 8, wavy, radius=r1, stiffness=stiff_smooth,
            damping=lambda s, t: 2.0 + s * t, sv=grid_params(8, jitter=0.6, seed=3)))),
        ("wavy_8x3_mass", case_of("wavy 8x3", make_body(
            "b", 8, 3, wavy, radius=r1, stiffness=stiff_smooth,
            mass=lambda s, t: 0.001 + 0.004 * s, su=grid_params(8, warp=1.5)))),
        ("saddle_3x12", case_of("saddle 3x12", make_body(
            "b", 3, 12, saddle, radius=r1, stiffness=stiff_smooth, sv=grid_params(12, jitter=0.8, seed=4)))),
        ("saddle_11x3", case_of("saddle 11x3", make_body(
            "b", 11, 3, saddle, radius=r1, stiffness=stiff_smooth,
            damping=lambda s, t: 1.0, mass=lambda s, t: 0.01))),
        ("tilted_4x4", case_of("tilted 4x4", make_body(
            "b", 4, 4, tilted, radius=r1, stiffness=stiff_smooth))),
        ("wavy_7x9", case_of("wavy 7x9", make_body(
            "b", 7, 9, wavy, radius=r1, stiffness=stiff_smooth,
            su=grid_params(7, warp=1.2), sv=grid_params(9, jitter=0.5, seed=9)))),
        ("cylinder_12x10_damping_mass", case_of("cylinder 12x10", make_body(
            "b", 12, 10, cylinder, radius=lambda s, t: 0.01 * bump(s, t) ** 0.5 + 0.001,
            stiffness=lambda s, t: 1500.0 + 1000.0 * s * s - 500.0 * t,
            damping=lambda s, t: 3.0 + math.sin(3 * s + t), mass=lambda s, t: 0.002 + 0.001 * t,
            su=grid_params(12, warp=-0.8), sv=grid_params(10, jitter=0.4, seed=12)))),
        ("nonuniform_9x7_damping", case_of("non-uniform 9x7", make_body(
            "b", 9, 7, saddle, radius=r1, stiffness=lambda s, t: 1e5 * (1 + s * t),
            damping=lambda s, t: 50.0 * (1 + s), su=grid_params(9, jitter=0.9, seed=5),
            sv=grid_params(7, jitter=0.9, seed=6)))),
        ("dome_pole_row_6x8", case_of("dome, pole row", make_body(
            "b", 6, 8, dome_pole_row, radius=lambda s, t: 0.005, stiffness=stiff_smooth))),
        ("dome_pole_col_8x6", case_of("dome, pole column", make_body(
            "b", 8, 6, dome_pole_col, radius=lambda s, t: 0.005, stiffness=stiff_smooth,
            mass=lambda s, t: 0.003))),
        ("offset_far_8x6", case_of("far from origin", make_body(
            "b", 8, 6, lambda s, t: tuple(a + o for a, o in zip(wavy(s, t), (20.0, -30.0, 5.0))),
            radius=r1, stiffness=stiff_smooth))),
        ("near_duplicate_6x6", case_of("near-duplicate column", make_body(
            "b", 6, 6, wavy, radius=r1, stiffness=stiff_smooth,
            sv=[0.0, 0.2, 0.4, 0.4 + 1e-4, 0.7, 1.0]))),
        ("zero_stiffness_region_5x6", case_of("stiffness 0 in places", make_body(
            "b", 5, 6, tilted, radius=r1, stiffness=lambda s, t: max(0.0, 1000.0 * (s - 0.5))))),
        ("two_bodies", case_of("two bodies",
                               make_body("first", 4, 5, wavy, radius=r1, stiffness=stiff_smooth),
                               make_body("second", 6, 4, cylinder, radius=r1,
                                         stiffness=lambda s, t: 200.0 + 50 * s,
                                         damping=lambda s, t: 0.5))),
        ("wavy_40x30", case_of("wavy 40x30", make_body(
            "b", 40, 30, wavy, radius=r1, stiffness=stiff_smooth, su=grid_params(40, warp=0.7)))),
    ]
    if long_mode:
        rnd = random.Random(20240501)
        for k in range(30):
            rows, cols = rnd.randint(2, 24), rnd.randint(2, 24)
            a, b, c, d = [rnd.uniform(0.5, 3.0) for _ in range(4)]
            amp = rnd.uniform(0.0, 0.03)
            sx, sy = rnd.uniform(0.03, 0.2), rnd.uniform(0.03, 0.2)

            def xyz(s, t, a=a, b=b, c=c, d=d, amp=amp, sx=sx, sy=sy):
                return (sx * s + 0.2 * amp * math.sin(c * t), sy * t + 0.1 * amp * s * s,
                        amp * math.sin(a * s + 0.3) * math.cos(b * t - 0.2) + 0.01 * d * s * t)

            kw = {}
            if rnd.random() < 0.5:
                kw["damping"] = lambda s, t, c=c: c * (1.0 + 0.5 * s * t)
            if rnd.random() < 0.5:
                kw["mass"] = lambda s, t, d=d: 0.001 * d * (1.0 + t)
            body = make_body("r%d" % k, rows, cols, xyz,
                             radius=lambda s, t, a=a: 0.002 + 0.003 * a * bump(s, t),
                             stiffness=lambda s, t, a=a, b=b: 100.0 * a + 900.0 * b * s * (1 - t),
                             su=grid_params(rows, warp=rnd.uniform(-1.5, 1.5), jitter=rnd.uniform(0, 0.9),
                                            seed=rnd.randint(0, 10 ** 6)),
                             sv=grid_params(cols, warp=rnd.uniform(-1.5, 1.5), jitter=rnd.uniform(0, 0.9),
                                            seed=rnd.randint(0, 10 ** 6)),
                             **kw)
            cases.append(("random_%02d_%dx%d" % (k, rows, cols), case_of("random %d" % k, body)))
    return cases


# ---------------------------------------------------------------------------
# Helpers
# ---------------------------------------------------------------------------

def run_cli(args, timeout=TIMEOUT):
    return subprocess.run([CLI] + args, capture_output=True, text=True, timeout=timeout)


def site_indices(n, limit_points):
    if limit_points:
        step = max(1, int(math.ceil(n / 50.0)))
        idx = list(range(0, n, step))
        if idx[-1] != n - 1:
            idx.append(n - 1)
        return idx
    return list(range(n))


def uv_points(f, seed, subsample):
    """(points, sites): points to evaluate; sites = [(k, i, j)] rows k of the data sites."""
    rnd = random.Random(seed)
    ii = site_indices(f.rows, subsample)
    jj = site_indices(f.cols, subsample)
    pts, sites = [], []
    for i in ii:
        for j in jj:
            sites.append((len(pts), i, j))
            pts.append((f.ubar[i], f.vbar[j]))
    pts += [(0.0, 0.0), (0.0, 1.0), (1.0, 0.0), (1.0, 1.0)]
    for e in (0.0, 1.0):
        for v in [f.vbar[j] for j in jj[:8]] + [rnd.random() for _ in range(6)]:
            pts.append((e, v))
        for u in [f.ubar[i] for i in ii[:8]] + [rnd.random() for _ in range(6)]:
            pts.append((u, e))
    pts += [(rnd.random(), rnd.random()) for _ in range(50)]
    return pts, sites


def write_uv(path, pts):
    with open(path, "w", encoding="utf-8") as fh:
        fh.write("u,v\n")
        for u, v in pts:
            fh.write("%r,%r\n" % (u, v))


def parse_csv(text):
    lines = [ln for ln in text.splitlines() if ln.strip() != ""]
    if not lines:
        return None, []
    rows = []
    for ln in lines[1:]:
        rows.append([float(x) for x in ln.split(",")])
    return lines[0].strip(), rows


def channel_scales(f, surface, refvals):
    grid = REF.data_grid(f, surface)
    C = len(grid[0][0])
    mx = [0.0] * C
    for row in grid:
        for pt in row:
            for c in range(C):
                mx[c] = max(mx[c], abs(pt[c]))
    for vals in refvals:
        for c in range(C):
            mx[c] = max(mx[c], abs(vals[c]))
    pos = max(mx[0], mx[1], mx[2])
    mx[0] = mx[1] = mx[2] = pos
    return [1e-12 + m for m in mx]


def slug(name):
    return "".join(ch if ch.isalnum() else "_" for ch in name)


# ---------------------------------------------------------------------------
# The check of one (case file, body)
# ---------------------------------------------------------------------------

OVERALL_WORST = [0.0, ""]   # largest |cli - ref| / tolerance over the whole run, and where


class Mismatch:
    def __init__(self):
        self.worst = None        # (ratio, text)
        self.count = 0

    def add(self, ratio, text):
        if ratio > 1.0:
            self.count += 1
        if self.worst is None or ratio > self.worst[0]:
            self.worst = (ratio, text)
        if ratio > OVERALL_WORST[0]:
            OVERALL_WORST[0], OVERALL_WORST[1] = ratio, text


# Channels derived from the tissue's modulus in a body given by "modulus" (Pa): the
# stiffness comes from the bonded-layer factor of contact mechanics, and the default
# damping from that stiffness. The reference fits geometry from the file alone, so those
# two are left out here; the derivation has its own tests (core.LayerStiffness.*,
# core.TissueInKpa.*), against Hayes et al.'s kappa and the finite-element reference.
DERIVED_FROM_MODULUS = ("stiffness", "damping")


def check_body(tc, label, case_path, body_json, workdir, subsample, centripetal=False):
    skip = ()
    if "modulus" in body_json and "stiffness" not in body_json:
        body_json = dict(body_json, stiffness=[1.0] * len(body_json["modulus"]))  # any: not compared
        skip = DERIVED_FROM_MODULUS
    body = REF.body_from_json(body_json)
    f = REF.fit(body, centripetal=centripetal)
    bid = body["id"]
    seed0 = zlib.crc32(("%s/%s" % (label, bid)).encode())
    for surface in REF.SURFACES:
        with tc.subTest(case=label, body=bid, surface=surface):
            if surface != "skeleton" and f.degenerate_normals:
                tc.skipTest("%s/%s: Su x Sv vanishes at data sites with radius > 0 %s; "
                            "the spec leaves that normal undefined" % (label, bid, f.degenerate_normals[:4]))
            pts, sites = uv_points(f, seed0 + REF.SURFACES.index(surface), subsample)
            uv_path = os.path.join(workdir, "%s_%s_%s_uv.csv" % (slug(label), slug(bid), surface))
            write_uv(uv_path, pts)
            cmd = ["fit", case_path, "--body", bid, "--surface", surface, "--eval", uv_path]
            if centripetal:
                cmd += ["--parameterization", "centripetal"]
            cmd_text = " ".join([CLI] + cmd)
            try:
                res = run_cli(cmd)
            except subprocess.TimeoutExpired:
                tc.fail("timeout (%d s): %s" % (TIMEOUT, cmd_text))
            tc.assertEqual(res.returncode, 0, "exit %d: %s\nstderr: %s" % (res.returncode, cmd_text,
                                                                         res.stderr.strip()[:2000]))
            try:
                head, rows = parse_csv(res.stdout)
            except ValueError as e:
                tc.fail("unparsable CSV from %s: %s\n%s" % (cmd_text, e, res.stdout[:500]))
            want_head = REF.header(surface)
            tc.assertEqual(head, want_head, "header: %s" % cmd_text)
            tc.assertEqual(len(rows), len(pts), "row count: %s" % cmd_text)
            refvals = [REF.evaluate(f, surface, u, v) for u, v in pts]
            scales = channel_scales(f, surface, refvals)
            names = want_head.split(",")[2:]
            mm = Mismatch()
            uvbad = []
            for k, ((u, v), got, want) in enumerate(zip(pts, rows, refvals)):
                tc.assertEqual(len(got), 2 + len(want), "column count at output row %d: %s" % (k + 2, cmd_text))
                if not (abs(got[0] - u) <= 1e-15 and abs(got[1] - v) <= 1e-15):
                    uvbad.append((k + 2, got[:2], (u, v)))
                for c, (g, w) in enumerate(zip(got[2:], want)):
                    if names[c] in skip:
                        continue
                    tol = REL_TOL * scales[c]
                    d = abs(g - w)
                    ratio = d / tol if math.isfinite(d) else math.inf
                    mm.add(ratio, "case %s body %s surface %s u=%r v=%r channel %s: cli=%r ref=%r "
                                  "|diff|=%.3g tol=%.3g" % (label, bid, surface, u, v, names[c], g, w, d, tol))
            tc.assertEqual(uvbad, [], "u,v columns differ from UV.csv (line, cli, uv): %s" % cmd_text)
            if mm.count:
                tc.fail("%d value(s) out of tolerance; worst (%.3g x tol): %s\ncommand: %s"
                        % (mm.count, mm.worst[0], mm.worst[1], cmd_text))
            if surface == "skeleton":
                pm = Mismatch()
                for k, i, j in sites:
                    data = f.data[i][j]
                    for c, (g, w) in enumerate(zip(rows[k][2:], data)):
                        if names[c] in skip:
                            continue
                        tol = REL_TOL * scales[c]
                        d = abs(g - w)
                        ratio = d / tol if math.isfinite(d) else math.inf
                        pm.add(ratio, "case %s body %s data site (%d,%d) u=%r v=%r channel %s: cli=%r "
                                      "data=%r |diff|=%.3g tol=%.3g" % (label, bid, i, j, f.ubar[i], f.vbar[j],
                                                                        names[c], g, w, d, tol))
                if pm.count:
                    tc.fail("skeleton does not pass through the data at %d value(s); worst (%.3g x tol): %s\n"
                            "command: %s" % (pm.count, pm.worst[0], pm.worst[1], cmd_text))


# ---------------------------------------------------------------------------
# Test classes
# ---------------------------------------------------------------------------

class SyntheticFitAgreement(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls._tmp = tempfile.TemporaryDirectory(prefix="palpa_fit_agree_")
        cls.workdir = cls._tmp.name

    @classmethod
    def tearDownClass(cls):
        cls._tmp.cleanup()

    def _write(self, name, case):
        path = os.path.join(self.workdir, name + ".json")
        with open(path, "w", encoding="utf-8") as fh:
            json.dump(case, fh)
        return path

    def _run_case(self, name, case):
        path = self._write(name, case)
        for b in case["bodies"]:
            check_body(self, name, path, b, self.workdir, subsample=False)


class CentripetalAgreement(unittest.TestCase):
    """`fit --parameterization centripetal` against the reference's centripetal option."""

    @classmethod
    def setUpClass(cls):
        cls._tmp = tempfile.TemporaryDirectory(prefix="palpa_fit_centripetal_")
        cls.workdir = cls._tmp.name

    @classmethod
    def tearDownClass(cls):
        cls._tmp.cleanup()

    _write = SyntheticFitAgreement._write

    def test_centripetal(self):
        wanted = {"near_duplicate_6x6", "two_bodies", "wavy_40x30"}
        cases = [c for c in synthetic_cases(False) if c[0] in wanted]
        self.assertEqual(len(cases), len(wanted), "synthetic case names changed")
        for name, case in cases:
            path = self._write(name + "_centripetal", case)
            for b in case["bodies"]:
                check_body(self, name + " (centripetal)", path, b, self.workdir, subsample=False, centripetal=True)


class SyntheticCasesAreValid(unittest.TestCase):
    """The synthetic cases are valid per the spec; `palpa-cli validate` must say so."""

    def test_validate_synthetic(self):
        with tempfile.TemporaryDirectory(prefix="palpa_fit_valid_") as d:
            bad = []
            for name, case in synthetic_cases(LONG):
                path = os.path.join(d, name + ".json")
                with open(path, "w", encoding="utf-8") as fh:
                    json.dump(case, fh)
                res = run_cli(["validate", path])
                if res.returncode != 0:
                    bad.append("%s: exit %d: %s" % (name, res.returncode, res.stderr.strip()[:500]))
            self.assertEqual(bad, [], "valid synthetic cases rejected:\n" + "\n".join(bad))


class DefaultsOfFitCommand(unittest.TestCase):
    def test_default_body_and_surface(self):
        """Without --body/--surface: the first body's skeleton."""
        name, case = [c for c in synthetic_cases(False) if c[0] == "two_bodies"][0]
        with tempfile.TemporaryDirectory(prefix="palpa_fit_def_") as d:
            path = os.path.join(d, "two.json")
            with open(path, "w", encoding="utf-8") as fh:
                json.dump(case, fh)
            uv = os.path.join(d, "uv.csv")
            write_uv(uv, [(0.0, 0.0), (0.3, 0.7), (1.0, 1.0)])
            a = run_cli(["fit", path, "--eval", uv])
            b = run_cli(["fit", path, "--body", "first", "--surface", "skeleton", "--eval", uv])
            self.assertEqual(a.returncode, 0, a.stderr)
            self.assertEqual(b.returncode, 0, b.stderr)
            self.assertEqual(a.stdout, b.stdout)
            self.assertEqual(a.stdout.splitlines()[0], REF.header("skeleton"))


class DataCasesFitAgreement(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls._tmp = tempfile.TemporaryDirectory(prefix="palpa_fit_data_")
        cls.workdir = cls._tmp.name

    @classmethod
    def tearDownClass(cls):
        cls._tmp.cleanup()

    def _run_file(self, path):
        res = run_cli(["validate", path])
        if res.returncode != 0:
            self.skipTest("%s is not valid per palpa-cli validate: %s" % (path, res.stderr.strip()[:300]))
        with open(path, "r", encoding="utf-8") as fh:
            case = json.load(fh)
        label = "data/cases/" + os.path.basename(path)
        for b in case["bodies"]:
            big = (not LONG) and b["rows"] * b["cols"] > MAX_SITES
            check_body(self, label, path, b, self.workdir, subsample=big)


def data_case_files():
    d = os.path.join(REPO, "data", "cases")
    return sorted(glob.glob(os.path.join(d, "*.json")))


def build_tests():
    for name, case in synthetic_cases(LONG):
        def t(self, name=name, case=case):
            self._run_case(name, case)
        t.__doc__ = "synthetic case %s" % name
        setattr(SyntheticFitAgreement, "test_" + slug(name), t)
    files = data_case_files()
    if not files:
        def t(self):
            self.skipTest("no data/cases/*.json in %s" % REPO)
        setattr(DataCasesFitAgreement, "test_no_data_cases", t)
    for path in files:
        def t(self, path=path):
            self._run_file(path)
        t.__doc__ = "data case %s" % os.path.basename(path)
        setattr(DataCasesFitAgreement, "test_" + slug(os.path.basename(path)), t)


def main():
    global CLI, REPO, LONG, REF
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cli", required=True, help="path to the palpa-cli binary")
    ap.add_argument("--repo", required=True, help="repository root (for tests/reference and data/cases)")
    ap.add_argument("--long", action="store_true", help="more random grids, all data sites of big cases")
    args, rest = ap.parse_known_args()
    CLI = os.path.abspath(args.cli)
    REPO = os.path.abspath(args.repo)
    LONG = args.long
    if not (os.path.isfile(CLI) and os.access(CLI, os.X_OK)):
        print("test_fit_agreement: error: not an executable file: %s" % CLI, file=sys.stderr)
        return 2
    sys.path.insert(0, os.path.join(REPO, "tests", "reference"))
    import a94_reference
    REF = a94_reference
    build_tests()
    prog = unittest.main(argv=[sys.argv[0]] + rest, exit=False)
    # The figure BENCHMARKS.md quotes: the largest disagreement relative to a channel's scale.
    print("worst agreement: %.3g of the channel's scale (%.3g x the tolerance %g) at %s"
          % (OVERALL_WORST[0] * REL_TOL, OVERALL_WORST[0], REL_TOL, OVERALL_WORST[1]), file=sys.stderr)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
