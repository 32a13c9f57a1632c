#!/usr/bin/python3
"""Checks of the finite-element indentation reference (tools/fem/indent.py).

Run: /usr/bin/python3 -m unittest discover -s tests/reference/fem -v
(needs numpy; the FEM cases need gmsh and ccx on PATH and are skipped
without them). Each FEM case is one small solve (a few seconds).

What is checked, against closed-form results:
  * flat punch on a very thick layer vs Sneddon's half-space stiffness
    2 a E / (1 - nu^2), within 5 %, and vs Hayes' kappa within 2 %;
  * bonded 20 and 40 mm layers: stiffer than Sneddon, in the right order,
    and within 2 % of Sneddon x kappa(a/h, nu) (Hayes et al. 1972) on a wide
    layer; the 60 mm-radius Palpa slab within 3 %;
  * mesh convergence: two mesh sizes agree within 1 %;
  * neo-Hookean + NLGEOM at small depth matches the linear stiffness
    (checks C10 = E / (4 (1 + nu)), D1 = 6 (1 - 2 nu) / E);
  * rigid sphere vs Hertz 4/3 E / (1 - nu^2) sqrt(R) d^1.5 within 10 %;
  * an on-axis stiff inclusion raises the force, its ratio-1 twin does not;
  * the command line rejects bad options and fails cleanly.
"""

import csv
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
TOOLS = os.path.normpath(os.path.join(HERE, "..", "..", "..", "tools", "fem"))
INDENT = os.path.join(TOOLS, "indent.py")
sys.path.insert(0, TOOLS)
sys.dont_write_bytecode = True   # leave no __pycache__ in tools/fem

try:
    import numpy  # noqa: F401
    import hayes
    HAVE_NUMPY = True
except ImportError:  # pragma: no cover - depends on the machine
    HAVE_NUMPY = False

HAVE_FEM = HAVE_NUMPY and shutil.which("gmsh") is not None and shutil.which("ccx") is not None

A = 0.0075       # punch radius (m)
NU = 0.49
E = 5000.0       # Pa
SNEDDON = 2.0 * A * E / (1.0 - NU * NU)   # N/m


def run_indent(*args, expect_ok=True):
    """Run indent.py; returns (rows, completed process)."""
    with tempfile.TemporaryDirectory(prefix="palpa_fem_test_") as tmp:
        out = os.path.join(tmp, "curve.csv")
        cmd = [sys.executable, INDENT, "--out", out, "--quiet", *map(str, args)]
        res = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             timeout=600)  # generous: a loaded machine runs a 30 s solve for minutes
        if expect_ok and res.returncode != 0:
            raise AssertionError(f"indent.py failed: {res.stderr.strip()}")
        rows = []
        if os.path.exists(out):
            with open(out) as f:
                rows = [(float(r["depth_m"]), float(r["force_n"])) for r in csv.DictReader(f)]
        return rows, res


def flat_stiffness(thickness, *extra, depth=2e-4):
    """Secant stiffness F/d (N/m) of the linear flat punch at a small depth."""
    rows, _ = run_indent("--thickness", thickness, "--modulus", E, "--poisson", NU,
                         "--max-depth", depth, "--steps", 1, *extra)
    d, F = rows[-1]
    return F / d


@unittest.skipUnless(HAVE_NUMPY, "numpy missing")
class HayesFactorTest(unittest.TestCase):
    """The layer factor solver on its own (no FEM)."""

    def test_half_space_limit(self):
        self.assertAlmostEqual(hayes.kappa(0.0, NU), 1.0, places=12)
        self.assertLess(abs(hayes.kappa(0.01, NU) - 1.0), 0.02)

    def test_monotone_in_thickness_and_poisson(self):
        ks = [hayes.kappa(r, NU) for r in (0.1, 0.2, 0.4, 0.8)]
        self.assertEqual(ks, sorted(ks))
        self.assertLess(hayes.kappa(0.4, 0.3), hayes.kappa(0.4, 0.45))

    def test_thin_compressible_layer_limit(self):
        # for a/h >> 1 the layer is in uniaxial strain under the punch
        for r in (10.0, 20.0):
            ratio = hayes.kappa(r, 0.3, n=200) / hayes.thin_layer_kappa(r, 0.3)
            self.assertLess(abs(ratio - 1.0), 0.05 * 10.0 / r)

    def test_the_column_kernel_of_equal_layers_is_the_layers(self):
        for u in (0.05, 1.0, 5.0, 15.0):
            self.assertAlmostEqual(hayes.column_kernel_weight(u, [(0.01, 5e3), (0.02, 5e3)], NU),
                                   hayes.layer_kernel_weight(u, NU), places=10)
        self.assertAlmostEqual(hayes.column_modulus(A, [(0.01, 5e3), (0.02, 5e3)], NU), 5e3, places=5)

    def test_quadrature_converged(self):
        k1 = hayes.kappa(0.375, NU)
        k2 = hayes.kappa(0.375, NU, n=96, n_u=60000, u_max=60.0)
        self.assertLess(abs(k1 - k2), 1e-5)


@unittest.skipUnless(HAVE_FEM, "gmsh/ccx or numpy missing")
class FlatPunchTest(unittest.TestCase):

    def test_thick_layer_matches_sneddon(self):
        k = flat_stiffness(0.3, "--radius", 0.6)
        self.assertLess(abs(k / SNEDDON - 1.0), 0.05, f"k/Sneddon = {k / SNEDDON:.4f}")
        kappa = hayes.kappa(A / 0.3, NU)
        self.assertLess(abs(k / (SNEDDON * kappa) - 1.0), 0.02)

    def test_bonded_layers_against_hayes(self):
        k20 = flat_stiffness(0.02, "--radius", 0.18)
        k40 = flat_stiffness(0.04, "--radius", 0.18)
        self.assertGreater(k20, k40)
        self.assertGreater(k40, 1.1 * SNEDDON)
        for h, k in ((0.02, k20), (0.04, k40)):
            kappa = hayes.kappa(A / h, NU)
            self.assertLess(abs(k / (SNEDDON * kappa) - 1.0), 0.02,
                            f"h={h}: FEM/Sneddon {k / SNEDDON:.4f}, kappa {kappa:.4f}")

    def test_palpa_slab_stiffness_per_kpa(self):
        # 60 mm radius slab, per kPa of E: about 24.5 (40 mm) and 31.7 (20 mm) N/m
        k40 = flat_stiffness(0.04) / (E / 1000.0)
        k20 = flat_stiffness(0.02) / (E / 1000.0)
        s = SNEDDON / (E / 1000.0)
        self.assertLess(abs(k40 / (s * hayes.kappa(A / 0.04, NU)) - 1.0), 0.03)
        self.assertLess(abs(k20 / (s * hayes.kappa(A / 0.02, NU)) - 1.0), 0.03)
        self.assertGreater(k20, k40)

    def test_mesh_convergence(self):
        fine = flat_stiffness(0.04, "--mesh-size", A / 24.0)
        coarse = flat_stiffness(0.04, "--mesh-size", A / 12.0)
        self.assertLess(abs(coarse / fine - 1.0), 0.01)

    def test_neo_hookean_small_depth_matches_linear(self):
        mesh = ("--mesh-size", 0.0008)
        lin = flat_stiffness(0.04, *mesh)
        rows, _ = run_indent("--thickness", 0.04, "--modulus", E, "--poisson", NU,
                             "--material", "neohookean", "--nlgeom", "--max-depth", 2e-4,
                             "--steps", 2, *mesh)
        d, F = rows[-1]
        self.assertEqual(len(rows), 3)
        self.assertLess(abs(F / d / lin - 1.0), 0.02)

    def test_stiff_inclusion_raises_force(self):
        inc = ("--inclusion-radius", 0.005, "--inclusion-depth", 0.01)
        plain = flat_stiffness(0.04)
        twin = flat_stiffness(0.04, *inc, "--inclusion-ratio", 1)
        lump = flat_stiffness(0.04, *inc, "--inclusion-ratio", 5)
        self.assertLess(abs(twin / plain - 1.0), 0.01)
        self.assertGreater(lump / twin, 1.02)

    def test_a_stiffer_layer_scales_the_force_exactly(self):
        # Both material models are homogeneous of degree 1 in E (linear elasticity, and the
        # neo-Hookean energy with C10 and 1/D1 proportional to E): 20 kPa pushes back four
        # times 5 kPa at every depth. So the 5 kPa curves of data/reference stand for every
        # modulus, and the reference needs no 20 kPa files.
        for material in ((), ("--material", "neohookean", "--nlgeom", "--mesh-size", 0.0008)):
            forces = []
            for modulus in (5000.0, 20000.0):
                rows, _ = run_indent("--thickness", 0.04, "--modulus", modulus, "--poisson", NU, *material,
                                     "--max-depth", 0.001, "--steps", 2)
                forces.append(rows[-1][1])
            self.assertLess(abs(forces[1] / forces[0] - 4.0), 4e-4, material)


@unittest.skipUnless(HAVE_FEM, "gmsh/ccx or numpy missing")
class SphereTest(unittest.TestCase):

    def test_hertz(self):
        R = 0.008
        rows, _ = run_indent("--indenter", "sphere", "--thickness", 0.06, "--modulus", E,
                             "--poisson", NU, "--max-depth", 4e-4, "--steps", 2)
        for d, F in rows[1:]:
            hertz = 4.0 / 3.0 * E / (1.0 - NU * NU) * math.sqrt(R) * d ** 1.5
            self.assertLess(abs(F / hertz - 1.0), 0.10, f"d={d}: F/Hertz = {F / hertz:.3f}")
        (d1, F1), (d2, F2) = rows[1], rows[2]
        exponent = math.log(F2 / F1) / math.log(d2 / d1)
        self.assertLess(abs(exponent - 1.5), 0.1)


@unittest.skipUnless(HAVE_FEM, "gmsh/ccx or numpy missing")
class ContrastSweepTest(unittest.TestCase):
    """The committed on-axis contrast sweep (data/reference/contrast_slab40_E5k_linear.csv)."""

    @classmethod
    def setUpClass(cls):
        path = os.path.join(HERE, "..", "..", "..", "data", "reference", "contrast_slab40_E5k_linear.csv")
        with open(path) as f:
            cls.rows = list(csv.DictReader(f))

    def row(self, radius, depth, ratio):
        for r in self.rows:
            if (abs(float(r["inclusion_radius_m"]) - radius) < 1e-9 and abs(float(r["inclusion_depth_m"]) - depth) < 1e-9
                    and float(r["modulus_ratio"]) == ratio):
                return r
        self.fail(f"no row for r={radius} s={depth} q={ratio}")

    def test_one_point_agrees_with_the_committed_inclusion_curves_and_a_fresh_solve(self):
        ref = os.path.join(HERE, "..", "..", "..", "data", "reference")
        with open(os.path.join(ref, "slab40_E5k_flat_linear_incl5x.csv")) as f5, \
                open(os.path.join(ref, "slab40_E5k_flat_linear_incl1x.csv")) as f1:
            curve = float(list(csv.DictReader(f5))[-1]["force_n"]) / float(list(csv.DictReader(f1))[-1]["force_n"])
        committed = float(self.row(0.005, 0.010, 5.0)["contrast"])
        self.assertLess(abs(committed / curve - 1.0), 1e-3)  # linear: the same at every press depth
        args = ("--thickness", 0.04, "--modulus", E, "--poisson", NU, "--inclusion-radius", 0.003,
                "--inclusion-depth", 0.015, "--max-depth", 5e-4, "--steps", 1)
        stiff, _ = run_indent(*args, "--inclusion-ratio", 10)
        twin, _ = run_indent(*args, "--inclusion-ratio", 1)
        self.assertLess(abs(stiff[-1][1] / twin[-1][1] - float(self.row(0.003, 0.015, 10.0)["contrast"])), 1e-4)

    def test_contrast_grows_with_size_and_ratio_and_fades_with_depth(self):
        for r in self.rows:
            self.assertGreater(float(r["contrast"]), 1.0, r)
        for radius in (0.003, 0.005, 0.010):
            for depth in (0.010, 0.015, 0.020, 0.025):
                cs = [self.row(radius, depth, q) for q in (3.0, 5.0, 10.0)
                      if any(abs(float(x["inclusion_radius_m"]) - radius) < 1e-9
                             and abs(float(x["inclusion_depth_m"]) - depth) < 1e-9 for x in self.rows)]
                values = [float(c["contrast"]) for c in cs]
                self.assertEqual(values, sorted(values), f"r={radius} s={depth}")
        for q in (3.0, 5.0, 10.0):
            deeper = [float(self.row(0.005, s, q)["contrast"]) for s in (0.010, 0.015, 0.020, 0.025)]
            self.assertEqual(deeper, sorted(deeper, reverse=True))
            bigger = [float(self.row(r, 0.015, q)["contrast"]) for r in (0.003, 0.005, 0.010)]
            self.assertEqual(bigger, sorted(bigger))


try:
    import scipy  # noqa: F401
    HAVE_SCIPY = True
except ImportError:  # pragma: no cover - depends on the machine
    HAVE_SCIPY = False


@unittest.skipUnless(HAVE_FEM, "gmsh/ccx or numpy missing")
class LateralTest(unittest.TestCase):
    """tools/fem/lateral.py, the 3-D model of an inclusion beside the pad's axis, and its
    committed sweep (data/reference/lateral_slab40_E5k_linear.csv)."""

    REF = os.path.join(HERE, "..", "..", "..", "data", "reference")

    def axisymmetric(self, radius, depth, ratio):
        with open(os.path.join(self.REF, "contrast_slab40_E5k_linear.csv")) as f:
            for r in csv.DictReader(f):
                if (abs(float(r["inclusion_radius_m"]) - radius) < 1e-9 and abs(float(r["inclusion_depth_m"]) - depth) < 1e-9
                        and float(r["modulus_ratio"]) == ratio):
                    return float(r["contrast"])
        self.fail(f"no axisymmetric row for r={radius} s={depth} q={ratio}")

    def test_a_coarse_solve_on_the_axis_agrees_with_the_axisymmetric_model_and_sneddon_hayes(self):
        with tempfile.TemporaryDirectory(prefix="palpa_lateral_test_") as tmp:
            out = os.path.join(tmp, "lateral.csv")
            res = subprocess.run([sys.executable, os.path.join(TOOLS, "lateral.py"), "--radius", "0.005", "--depth",
                                  "0.010", "--offsets", "0", "--fine", "0.0016", "--coarse", "0.012", "--out", out],
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=600)
            self.assertEqual(res.returncode, 0, res.stderr)
            with open(out) as f:
                row = next(csv.DictReader(f))
        extra = self.axisymmetric(0.005, 0.010, 5.0) - 1.0
        self.assertLess(abs(float(row["contrast"]) - 1.0 - extra), 0.05 * extra)
        # The twin is the plain layer: Sneddon x kappa (Hayes) for a 40 mm layer, within 5 %.
        stiffness = float(row["twin_force_n"]) / 5e-4
        self.assertLess(abs(stiffness / (SNEDDON * hayes.kappa(A / 0.040, NU)) - 1.0), 0.05)

    def test_the_committed_sweep_fades_beside_the_axis_from_the_axisymmetric_value(self):
        with open(os.path.join(self.REF, "lateral_slab40_E5k_linear.csv")) as f:
            rows = list(csv.DictReader(f))
        groups = {}
        for r in rows:
            groups.setdefault((r["inclusion_radius_m"], r["inclusion_depth_m"], r["modulus_ratio"]), []).append(r)
        self.assertEqual(len(groups), 2)
        for (radius, depth, ratio), g in groups.items():
            g.sort(key=lambda r: float(r["offset_m"]))
            contrast = [float(r["contrast"]) for r in g]
            self.assertEqual(float(g[0]["offset_m"]), 0.0)
            extra = self.axisymmetric(float(radius), float(depth), float(ratio)) - 1.0
            self.assertLess(abs(contrast[0] - 1.0 - extra), 0.03 * extra, (radius, depth))
            self.assertEqual(contrast, sorted(contrast, reverse=True), (radius, depth))
            self.assertLess(contrast[-1] - 1.0, 0.25 * (contrast[0] - 1.0), "well beyond the pad, little is left")


class ToolsTest(unittest.TestCase):
    """Where the tools are part of the build (ctest sets PALPA_REQUIRE_FEM=1, install-deps.sh
    installs them), a missing one fails here rather than skipping the whole suite unseen."""

    @unittest.skipUnless(os.environ.get("PALPA_REQUIRE_FEM") == "1", "PALPA_REQUIRE_FEM is not 1")
    def test_gmsh_calculix_numpy_and_scipy_are_installed(self):
        missing = [name for name, ok in (("gmsh", shutil.which("gmsh")), ("ccx", shutil.which("ccx")),
                                         ("numpy", HAVE_NUMPY), ("scipy", HAVE_SCIPY)) if not ok]
        self.assertEqual(missing, [], "run scripts/install-deps.sh")


@unittest.skipUnless(HAVE_NUMPY and HAVE_SCIPY, "numpy or scipy missing")
class ContrastFitTest(unittest.TestCase):
    """tools/fem/fit_contrast.py: the reduced contrast model against the 20, 30 and 40 mm sweeps."""

    def test_the_model_predicts_every_inclusion_and_every_layer_left_out_within_twenty_percent(self):
        import fit_contrast
        self.assertEqual(sorted(fit_contrast.thickness_of(p) for p in fit_contrast.DATA), [0.020, 0.030, 0.040])
        cols = fit_contrast.load(fit_contrast.DATA)
        self.assertEqual(len(cols[0]), 72)
        self.assertLess(fit_contrast.leave_one_out(*cols), 0.20)
        for thickness, worst in fit_contrast.leave_thickness_out(*cols).items():
            self.assertLess(worst, 0.20, f"the {thickness} m layer left out")
        theta = fit_contrast.fit(*cols)
        # No contrast without a contrast in modulus, and a stiffer inclusion is felt more.
        self.assertAlmostEqual(math.exp(fit_contrast.log_extra(theta, 0.005, 0.010, 1.0 + 1e-12, 0.04)), 0.0, places=9)
        self.assertLess(fit_contrast.log_extra(theta, 0.005, 0.010, 3.0, 0.04),
                        fit_contrast.log_extra(theta, 0.005, 0.010, 10.0, 0.04))


@unittest.skipUnless(HAVE_NUMPY and HAVE_SCIPY, "numpy or scipy missing")
class FingerContrastFitTest(unittest.TestCase):
    """tools/fem/fit_finger_contrast.py: the pad's contrast model read under the rounded finger."""

    # contact::TumourContrast::Finger (core/include/palpa/contact/force.hpp): alpha, n, beta, kappa, e_f.
    SHIPPED = (0.8791, 0.7054, 0.5496, 0.3214, -0.4256)

    def test_the_fit_gives_the_shipped_numbers_and_every_press_within_the_mark(self):
        import fit_finger_contrast as fit
        rows = fit.load()
        self.assertEqual(len(rows), 49)
        pad = fit.pad_parameters()
        theta = fit.fit(pad, rows)
        for fitted, shipped in zip(theta, self.SHIPPED):
            self.assertAlmostEqual(fitted, shipped, delta=2e-3 * abs(shipped))
        self.assertLess(max(abs(e) for e in fit.errors(self.SHIPPED, pad, rows)), 1.0)

    def test_sneddons_contact_radius(self):
        import fit_finger_contrast as fit
        # d = (c / 2) ln((R + c) / (R - c)) by hand at c = R / 2: d = R ln(3) / 4.
        self.assertAlmostEqual(fit.contact_radius(0.008 * math.log(3.0) / 4.0), 0.004, places=9)
        self.assertAlmostEqual(fit.contact_radius(0.0), 0.0, places=12)


@unittest.skipUnless(HAVE_NUMPY, "numpy missing")
class CommandLineTest(unittest.TestCase):

    def check_rejected(self, *args, message):
        rows, res = run_indent(*args, expect_ok=False)
        self.assertEqual(res.returncode, 2)
        self.assertIn(message, res.stderr)
        self.assertEqual(rows, [])

    def test_bad_options(self):
        self.check_rejected("--thickness", -1, "--modulus", E, message="positive")
        self.check_rejected("--thickness", 0.04, "--modulus", E, "--poisson", 0.5,
                            message="[0, 0.5)")
        self.check_rejected("--thickness", 0.04, "--modulus", E, "--max-depth", 0.05,
                            message="smaller than --thickness")
        self.check_rejected("--thickness", 0.04, "--modulus", E, "--material", "neohookean",
                            message="needs --nlgeom")
        self.check_rejected("--thickness", 0.04, "--modulus", E, "--inclusion-radius", 0.005,
                            message="all three")
        self.check_rejected("--thickness", 0.04, "--modulus", E, "--indenter", "cone",
                            message="invalid choice")

    def test_bad_layers(self):
        self.check_rejected("--layers", "0.01:3250,0.02", message="thickness:modulus")
        self.check_rejected("--layers", "0.01:3250,0.02:-1", message="positive")
        self.check_rejected("--layers", "0.01:3250,0.02:13000", "--modulus", E,
                            message="either --modulus or --layers")
        self.check_rejected("--layers", "0.01:3250,0.02:13000", "--thickness", 0.04,
                            message="differs from the sum")
        self.check_rejected("--layers", "0.01:3250,0.02:13000", "--material", "neohookean",
                            "--nlgeom", message="linear only")
        self.check_rejected("--modulus", E, message="required: --thickness")

    def test_layers_are_meshed_apart_with_a_material_each(self):
        # no solve: the .geo has a surface per layer on shared interface lines, and the
        # plain slab's .geo is unchanged by the option's existence
        import indent
        parser = indent.build_parser()

        def geo(*args):
            o = parser.parse_args([*map(str, args), "--out", "unused.csv"])
            indent.check_options(parser, o)
            o.mesh_size = indent.default_mesh_size(o)
            return o, indent.geo_text(o, o.mesh_size)
        o, text = geo("--layers", "0.002:56000,0.01:3250,0.018:13000")
        self.assertAlmostEqual(o.thickness, 0.030)
        self.assertEqual(o.modulus, 56000.0)
        for tag in (1, 11, 12):
            self.assertIn(f"Physical Surface({tag})", text)
        self.assertEqual([e[2:] for e in indent.layer_elsets(o)],
                         [("TISSUE2", 3250.0), ("TISSUE3", 13000.0)])
        _, plain = geo("--thickness", 0.03, "--modulus", E)
        self.assertNotIn("Physical Surface(11)", plain)

    @unittest.skipUnless(HAVE_FEM, "gmsh/ccx missing")
    def test_non_convergence_is_reported(self):
        # St Venant-Kirchhoff (linear + NLGEOM) at nu = 0.49 collapses under
        # a flat punch well before 30 % of the thickness on this mesh
        rows, res = run_indent("--thickness", 0.04, "--modulus", E, "--nlgeom",
                               "--max-depth", 0.012, "--steps", 3, "--mesh-size", 0.0015,
                               expect_ok=False)
        self.assertEqual(res.returncode, 1)
        self.assertIn("CalculiX stopped at depth", res.stderr)
        self.assertEqual(rows, [])


if __name__ == "__main__":
    unittest.main()
