#!/usr/bin/python3
"""Self-tests of the pure-Python A9.4 reference (tests/reference/a94_reference.py).

Run: /usr/bin/python3 tests/reference/test_a94_reference.py   (standard library only)

Checks: partition of unity / non-negativity / end values of the Cox-de Boor
basis including u == 1 exactly, agreement with an independent A2.2 triangular
evaluation written here, the derivative formula against finite differences,
the NURBS Book example 9.1 parameters and knots, exact reproduction of
polynomials of degree <= (p, q) in (u, v), interpolation of the data to 1e-12,
normals of a plane, the defaults for damping and mass, the pole rule of the
chord-length parameters, and the command line.
"""

import io
import json
import math
import os
import random
import sys
import tempfile
import unittest
from contextlib import redirect_stdout, redirect_stderr

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import a94_reference as ref  # noqa: E402


def a22_basis(U, p, u):
    """The NURBS Book A2.1 + A2.2 (span search + triangular scheme), for cross-checking."""
    n = len(U) - p - 2
    if u >= U[n + 1]:
        span = n
    else:
        lo, hi = p, n + 1
        mid = (lo + hi) // 2
        while u < U[mid] or u >= U[mid + 1]:
            if u < U[mid]:
                hi = mid
            else:
                lo = mid
            mid = (lo + hi) // 2
        span = mid
    N = [1.0] + [0.0] * p
    left = [0.0] * (p + 1)
    right = [0.0] * (p + 1)
    for j in range(1, p + 1):
        left[j] = u - U[span + 1 - j]
        right[j] = U[span + j] - u
        saved = 0.0
        for r in range(j):
            temp = N[r] / (right[r + 1] + left[j - r])
            N[r] = saved + right[r + 1] * temp
            saved = left[j - r] * temp
        N[j] = saved
    full = [0.0] * (n + 1)
    for r in range(p + 1):
        full[span - p + r] = N[r]
    return full


KNOT_VECTORS = [
    ([0.0, 0.0, 1.0, 1.0], 1),
    ([0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 2),
    ([0.0] * 4 + [1.0] * 4, 3),
    ([0.0, 0.0, 0.3, 0.55, 1.0, 1.0], 1),
    ([0.0, 0.0, 0.0, 0.2, 0.7, 1.0, 1.0, 1.0], 2),
    ([0.0] * 4 + [0.1, 0.35, 0.36, 0.8] + [1.0] * 4, 3),
    ([0.0] * 4 + [28.0 / 51.0] + [1.0] * 4, 3),
]


def sample_params(U, count=97, seed=1):
    rnd = random.Random(seed)
    ts = [0.0, 1.0, 1.0 - 1e-16, 5e-17, 0.5] + [rnd.random() for _ in range(count)]
    ts += sorted(set(U))
    ts += [min(1.0, k + 1e-15) for k in U] + [max(0.0, k - 1e-15) for k in U]
    return ts


class BasisTests(unittest.TestCase):
    def test_partition_of_unity_nonnegative_and_ends(self):
        for U, p in KNOT_VECTORS:
            n = len(U) - p - 1
            for u in sample_params(U):
                N, dN = ref.basis_and_derivative(U, p, u)
                self.assertEqual(len(N), n)
                self.assertAlmostEqual(sum(N), 1.0, delta=1e-14, msg=(U, p, u))
                self.assertTrue(all(x >= 0.0 for x in N), (U, p, u, N))
                self.assertAlmostEqual(sum(dN), 0.0, delta=1e-9 * (1 + max(abs(x) for x in dN)),
                                       msg=(U, p, u))
            N0 = ref.basis(U, p, 0.0)
            N1 = ref.basis(U, p, 1.0)
            self.assertEqual(N0[0], 1.0)
            self.assertEqual(sum(N0[1:]), 0.0)
            self.assertEqual(N1[-1], 1.0, (U, p))      # closed right end
            self.assertEqual(sum(N1[:-1]), 0.0)

    def test_matches_triangular_scheme(self):
        for U, p in KNOT_VECTORS:
            for u in sample_params(U, seed=2):
                a = ref.basis(U, p, u)
                b = a22_basis(U, p, u)
                for x, y in zip(a, b):
                    self.assertAlmostEqual(x, y, delta=1e-14, msg=(U, p, u))

    def test_derivative_formula_vs_finite_differences(self):
        h = 1e-6
        for U, p in KNOT_VECTORS:
            knots = set(U)
            for u in sample_params(U, count=40, seed=3):
                if any(abs(u - k) < 3 * h for k in knots):
                    continue            # derivative may jump at a knot (p = 1)
                _, dN = ref.basis_and_derivative(U, p, u)
                Np = ref.basis(U, p, u + h)
                Nm = ref.basis(U, p, u - h)
                for i in range(len(dN)):
                    fd = (Np[i] - Nm[i]) / (2 * h)
                    self.assertAlmostEqual(dN[i], fd, delta=1e-5 * (1 + abs(fd)), msg=(U, p, u, i))

    def test_left_derivative_at_one(self):
        # cubic Bezier: N_3(u) = u^3 -> derivative 3 at u = 1; N_2 = 3u^2(1-u) -> 3*2 - 9 = -3
        U = [0.0] * 4 + [1.0] * 4
        N, dN = ref.basis_and_derivative(U, 3, 1.0)
        self.assertEqual(N, [0.0, 0.0, 0.0, 1.0])
        self.assertAlmostEqual(dN[3], 3.0, delta=1e-15)
        self.assertAlmostEqual(dN[2], -3.0, delta=1e-15)
        self.assertAlmostEqual(dN[0], 0.0, delta=1e-15)

    def test_outside_domain_rejected(self):
        with self.assertRaises(ref.ReferenceError_):
            ref.basis([0.0, 0.0, 1.0, 1.0], 1, 1.0000000000000002)
        with self.assertRaises(ref.ReferenceError_):
            ref.basis([0.0, 0.0, 1.0, 1.0], 1, -1e-300)


class ParameterTests(unittest.TestCase):
    def test_nurbs_book_example_9_1(self):
        pts = [[0, 0, 0], [3, 4, 0], [-1, 4, 0], [-4, 0, 0], [-4, -3, 0]]
        t = ref.chord_parameters([pts])
        for a, b in zip(t, [0.0, 5 / 17, 9 / 17, 14 / 17, 1.0]):
            self.assertAlmostEqual(a, b, delta=1e-15)
        self.assertEqual(t[0], 0.0)
        self.assertEqual(t[-1], 1.0)
        U = ref.averaged_knots(t, 3)
        self.assertEqual(len(U), 9)
        self.assertAlmostEqual(U[4], 28 / 51, delta=1e-15)
        self.assertEqual(U[:4], [0.0] * 4)
        self.assertEqual(U[5:], [1.0] * 4)
        self.assertEqual(ref.averaged_knots([0.0, 0.4, 1.0], 2), [0.0] * 3 + [1.0] * 3)
        self.assertEqual(ref.averaged_knots([0.0, 1.0], 1), [0.0, 0.0, 1.0, 1.0])
        U2 = ref.averaged_knots([0.0, 0.1, 0.5, 0.6, 1.0], 2)
        self.assertEqual(len(U2), 8)
        self.assertAlmostEqual(U2[3], 0.3, delta=1e-16)
        self.assertAlmostEqual(U2[4], 0.55, delta=1e-16)

    def test_average_and_zero_length_skipped(self):
        a = [[0, 0, 0], [1, 0, 0], [3, 0, 0]]           # 1/3
        b = [[0, 1, 0], [3, 1, 0], [4, 1, 0]]           # 3/4
        pole = [[5, 5, 5]] * 3                          # skipped
        t = ref.chord_parameters([a, pole, b])
        self.assertAlmostEqual(t[1], (1 / 3 + 3 / 4) / 2, delta=1e-16)
        self.assertEqual((t[0], t[2]), (0.0, 1.0))
        c = ref.chord_parameters([a], centripetal=True)
        self.assertAlmostEqual(c[1], 1 / (1 + math.sqrt(2)), delta=1e-16)


class SolverTests(unittest.TestCase):
    def test_needs_pivoting(self):
        A = [[0.0, 1.0, 2.0], [1.0, 0.0, 3.0], [4.0, -3.0, 8.0]]
        X = [[1.0, -2.0], [2.0, 0.5], [-1.0, 3.0]]
        B = [[sum(A[i][k] * X[k][c] for k in range(3)) for c in range(2)] for i in range(3)]
        Y = ref.solve_dense(A, B)
        for i in range(3):
            for c in range(2):
                self.assertAlmostEqual(Y[i][c], X[i][c], delta=1e-14)
        with self.assertRaises(ref.ReferenceError_):
            ref.solve_dense([[1.0, 2.0], [2.0, 4.0]], [[1.0], [2.0]])


def make_body(rows, cols, fxyz, fr=None, fk=None, damping=None, mass=None, bid="b"):
    med, rad, stf = [], [], []
    for i in range(rows):
        for j in range(cols):
            s, t = i / (rows - 1), j / (cols - 1)
            med.append(list(fxyz(s, t)))
            boundary = i in (0, rows - 1) or j in (0, cols - 1)
            rad.append(0.0 if (fr is None or boundary) else fr(s, t))
            stf.append(100.0 if fk is None else fk(s, t))
    b = {"id": bid, "rows": rows, "cols": cols, "medial": med, "radius": rad, "stiffness": stf}
    if damping is not None:
        b["damping"] = [damping(i / (rows - 1), j / (cols - 1)) for i in range(rows) for j in range(cols)]
    if mass is not None:
        b["mass"] = [mass(i / (rows - 1), j / (cols - 1)) for i in range(rows) for j in range(cols)]
    return b


def curved_xyz(s, t):
    x = 0.1 * (s + 0.15 * s * s)
    y = 0.08 * (t + 0.3 * t * t * t)
    return x, y, 0.02 * math.sin(3.0 * x / 0.1) * math.cos(2.0 * y / 0.08)


class FitTests(unittest.TestCase):
    def _check_interpolates(self, f, tol=1e-12):
        for surf in ref.SURFACES:
            grid = ref.data_grid(f, surf)
            C = len(grid[0][0])
            scale = [1e-300 + max(abs(grid[i][j][c]) for i in range(f.rows) for j in range(f.cols))
                     for c in range(C)]
            for i, u in enumerate(f.ubar):
                for j, v in enumerate(f.vbar):
                    val = ref.evaluate(f, surf, u, v)
                    for c in range(C):
                        self.assertLessEqual(abs(val[c] - grid[i][j][c]), tol * scale[c],
                                             msg=(surf, i, j, c, val[c], grid[i][j][c]))

    def test_polynomial_reproduction(self):
        # For each grid size, put a polynomial of degree <= (p, q) in (u, v) into the
        # radius/stiffness/damping/mass channels, using the reference's own parameters.
        rnd = random.Random(7)
        for rows, cols in [(2, 2), (2, 5), (3, 3), (3, 7), (6, 3), (4, 4), (7, 9), (12, 10)]:
            base = ref.body_from_json(make_body(rows, cols, curved_xyz))
            f0 = ref.fit(base)
            p, q = f0.p, f0.q
            coeffs = [[[rnd.uniform(-2, 2) for _ in range(q + 1)] for _ in range(p + 1)]
                      for _ in range(4)]

            def poly(ch, u, v):
                return sum(coeffs[ch][a][b] * u ** a * v ** b
                           for a in range(p + 1) for b in range(q + 1))

            def dpoly(ch, u, v, du):
                if du:
                    return sum(a * coeffs[ch][a][b] * u ** (a - 1) * v ** b
                               for a in range(1, p + 1) for b in range(q + 1))
                return sum(b * coeffs[ch][a][b] * u ** a * v ** (b - 1)
                           for a in range(p + 1) for b in range(1, q + 1))

            body = dict(base)
            keys = ["radius", "stiffness", "damping", "mass"]
            for ch, key in enumerate(keys):
                body[key] = [poly(ch, f0.ubar[i], f0.vbar[j]) for i in range(rows) for j in range(cols)]
            f = ref.fit(body)
            self.assertEqual(f.ubar, f0.ubar)
            self._check_interpolates(f)
            pts = [(0.0, 0.0), (1.0, 1.0), (0.0, 1.0), (1.0, 0.0)] + \
                  [(rnd.random(), rnd.random()) for _ in range(40)]
            for u, v in pts:
                S, Su, Sv = f.skeleton.eval_with_derivatives(u, v, (3, 4, 5, 6))
                for ch in range(4):
                    self.assertAlmostEqual(S[ch], poly(ch, u, v), delta=1e-12 * 20,
                                           msg=(rows, cols, u, v, ch))
                    self.assertAlmostEqual(Su[ch], dpoly(ch, u, v, True), delta=1e-9 * 20,
                                           msg=(rows, cols, u, v, ch, "Su"))
                    self.assertAlmostEqual(Sv[ch], dpoly(ch, u, v, False), delta=1e-9 * 20,
                                           msg=(rows, cols, u, v, ch, "Sv"))

    def test_interpolates_data_curved_with_defaults(self):
        for rows, cols in [(2, 6), (6, 2), (3, 5), (5, 3), (4, 4), (7, 9), (12, 10)]:
            b = ref.body_from_json(make_body(
                rows, cols, curved_xyz,
                fr=lambda s, t: 0.01 * math.sin(math.pi * s) * math.sin(math.pi * t) + 0.001,
                fk=lambda s, t: 800.0 + 300.0 * math.cos(2 * s + t)))
            f = ref.fit(b)
            self._check_interpolates(f)
            self.assertEqual(f.degenerate_normals, [])
            self.assertEqual(f.p, min(3, rows - 1))
            self.assertEqual(f.q, min(3, cols - 1))

    def test_defaults(self):
        b = ref.body_from_json(make_body(3, 3, curved_xyz, fk=lambda s, t: 400.0 + s))
        self.assertEqual(b["mass"], [1e-3] * 9)
        for k, d in zip(b["stiffness"], b["damping"]):
            self.assertAlmostEqual(d, 2 * 0.7 * math.sqrt(k * 1e-3), delta=1e-15)
        b = ref.body_from_json(make_body(3, 3, curved_xyz, mass=lambda s, t: 0.5 + s))
        for k, m, d in zip(b["stiffness"], b["mass"], b["damping"]):
            self.assertAlmostEqual(d, 1.4 * math.sqrt(k * m), delta=1e-13)
        b = ref.body_from_json(make_body(3, 3, curved_xyz, damping=lambda s, t: 7.0))
        self.assertEqual(b["damping"], [7.0] * 9)
        self.assertEqual(b["mass"], [1e-3] * 9)

    def test_plane_normals_and_contours(self):
        b = ref.body_from_json(make_body(
            5, 6, lambda s, t: (0.1 * s + 0.02 * s * s, 0.07 * t, 0.03),
            fr=lambda s, t: 0.01 + 0.002 * s))
        f = ref.fit(b)
        for i in range(5):
            for j in range(6):
                n = f.normals[i][j]
                self.assertAlmostEqual(n[2], 1.0, delta=1e-14)
                P = f.data[i][j]
                self.assertAlmostEqual(f.top_data[i][j][2], 0.03 + P[3], delta=1e-16)
                self.assertAlmostEqual(f.bottom_data[i][j][2], 0.03 - P[3], delta=1e-16)
        self.assertAlmostEqual(ref.evaluate_skeleton(f, 0.37, 0.81)[2], 0.03, delta=1e-16)

    def test_cylinder_normals_radial(self):
        R0 = 0.05

        def cyl(s, t):
            a = -0.6 + 1.2 * t
            return R0 * math.sin(a), 0.1 * s, R0 * math.cos(a)

        b = ref.body_from_json(make_body(8, 12, cyl, fr=lambda s, t: 0.005))
        f = ref.fit(b)
        for i in range(8):
            for j in range(12):
                P = f.data[i][j]
                radial = [P[0] / R0, 0.0, P[2] / R0]
                n = f.normals[i][j]
                dot = sum(a * c for a, c in zip(n, radial))
                self.assertGreater(abs(dot), 0.999, (i, j, n))

    def test_pole_row(self):
        # row 0 collapses to a point: skipped in the v-parameters, normal irrelevant (r = 0)
        def dome(s, t):
            a = 2.0 * t
            return 0.05 * s * math.cos(a), 0.05 * s * math.sin(a), 0.03 * (1 - s * s)

        b = ref.body_from_json(make_body(6, 7, dome, fr=lambda s, t: 0.004))
        f = ref.fit(b)
        self._check_interpolates(f)
        self.assertEqual(f.degenerate_normals, [])
        rows_only = ref.chord_parameters([[f.data[i][j][:3] for j in range(7)] for i in range(1, 6)])
        self.assertEqual(f.vbar, rows_only)
        for j in range(7):
            self.assertEqual(f.top_data[0][j], f.data[0][j][:3])


class CliTests(unittest.TestCase):
    def test_cli_output(self):
        case = {"format": "palpa-case", "version": 1, "title": "t",
                "bodies": [make_body(4, 5, curved_xyz, fr=lambda s, t: 0.003, bid="a"),
                           make_body(3, 3, curved_xyz, bid="second")]}
        with tempfile.TemporaryDirectory() as d:
            cp = os.path.join(d, "c.json")
            uv = os.path.join(d, "uv.csv")
            with open(cp, "w") as fh:
                json.dump(case, fh)
            with open(uv, "w") as fh:
                fh.write("u,v\n0,0\n1,1\n0.25,0.5\n")
            for surf, ncols in [("skeleton", 9), ("top", 5), ("bottom", 5)]:
                out = io.StringIO()
                with redirect_stdout(out):
                    rc = ref.main(["fit", cp, "--surface", surf, "--eval", uv])
                self.assertEqual(rc, 0)
                lines = out.getvalue().splitlines()
                self.assertEqual(lines[0], ref.header(surf))
                self.assertEqual(len(lines), 4)
                self.assertTrue(all(len(l.split(",")) == ncols for l in lines))
            out = io.StringIO()
            with redirect_stdout(out):
                self.assertEqual(ref.main([cp, "--body", "second", "--eval", uv]), 0)
            first = out.getvalue().splitlines()[1].split(",")
            self.assertEqual([float(x) for x in first[2:5]], case["bodies"][1]["medial"][0])
            err = io.StringIO()
            with redirect_stderr(err):
                self.assertEqual(ref.main([cp, "--body", "nosuch", "--eval", uv]), 2)
            self.assertIn("nosuch", err.getvalue())


if __name__ == "__main__":
    unittest.main()
