#!/usr/bin/python3
"""Regenerate the committed reference curves in data/reference/.

Runs tools/fem/indent.py once per case, at the lowest CPU priority and with
single-threaded CalculiX, and prints one line per case with the wall and
CPU time and the depth reached. Cases that stop before their final depth
(neo-Hookean runs on a flat punch) keep the converged part of the curve.

    /usr/bin/python3 tools/fem/make_reference.py            # all cases
    /usr/bin/python3 tools/fem/make_reference.py --only slab40_E5k_flat_linear
    /usr/bin/python3 tools/fem/make_reference.py --list

It also prints the small-depth stiffness table of the README
(--stiffness-table), which re-solves the linear cases at two mesh sizes.
"""

import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
OUT_DIR = os.path.join(ROOT, "data", "reference")
INDENT = os.path.join(HERE, "indent.py")

E5K = ["--modulus", "5000", "--poisson", "0.49"]
NEO = ["--material", "neohookean", "--nlgeom", "--mesh-size", "0.0008", "--allow-partial"]
INCLUSION = ["--inclusion-radius", "0.005", "--inclusion-depth", "0.010"]
# Twins that tell how the contrast grows with the press: a larger, deeper inclusion on the
# 40 mm layer, and the first inclusion under a 20 mm layer.
INCLUSION_R10D20 = ["--inclusion-radius", "0.010", "--inclusion-depth", "0.020"]
# The rounded finger (8 mm sphere on a cylinder, penalty contact): finer contact meshes, and
# the 40 mm layer's on a 0.5 mm mesh (0.4 mm stops converging after 1 mm there).
FINGER = ["--indenter", "sphere", "--material", "neohookean", "--nlgeom", "--allow-partial", "--steps", "23"]



def twins(name, args):
    """An inclusion at 5 x E and its 1 x twin on the same mesh: NAME_incl5x and NAME_incl1x
    (their force ratio is the inclusion's contrast)."""
    return {f"{name}_incl{q}x": [*args, "--inclusion-ratio", str(q)] for q in (5, 1)}


# name: indent.py arguments (flat punch a = 7.5 mm, slab radius 60 mm)
CASES = {
    "slab40_E5k_flat_linear": ["--thickness", "0.040", *E5K, "--max-depth", "0.016", "--steps", "16"],
    "slab20_E5k_flat_linear": ["--thickness", "0.020", *E5K, "--max-depth", "0.008", "--steps", "16"],
    "slab40_E5k_flat_neohooke": ["--thickness", "0.040", *E5K, *NEO, "--max-depth", "0.016",
                                 "--steps", "16"],
    "slab20_E5k_flat_neohooke": ["--thickness", "0.020", *E5K, *NEO, "--max-depth", "0.008",
                                 "--steps", "16"],
    "slab30_E5k_flat_linear": ["--thickness", "0.030", *E5K, "--max-depth", "0.012", "--steps", "16"],
    "slab30_E5k_flat_neohooke_pinned": ["--thickness", "0.030", *E5K, *NEO, "--pin-edge",
                                        "--max-depth", "0.012", "--steps", "16"],
    "slab40_E5k_flat_neohooke_pinned": ["--thickness", "0.040", *E5K, *NEO, "--pin-edge",
                                        "--max-depth", "0.016", "--steps", "16"],
    "slab20_E5k_flat_neohooke_pinned": ["--thickness", "0.020", *E5K, *NEO, "--pin-edge",
                                        "--max-depth", "0.008", "--steps", "16"],
    **twins("slab40_E5k_flat_linear", ["--thickness", "0.040", *E5K, *INCLUSION, "--max-depth", "0.016",
                                       "--steps", "16"]),
    **twins("slab40_E5k_flat_neohooke_pinned", ["--thickness", "0.040", *E5K, *NEO, "--pin-edge", *INCLUSION,
                                                "--max-depth", "0.016", "--steps", "16"]),
    **twins("slab40_E5k_flat_neohooke_pinned_r10d20", ["--thickness", "0.040", *E5K, *NEO, "--pin-edge",
                                                       *INCLUSION_R10D20, "--max-depth", "0.016", "--steps", "16"]),
    **twins("slab20_E5k_flat_neohooke_pinned", ["--thickness", "0.020", *E5K, *NEO, "--pin-edge", *INCLUSION,
                                                "--max-depth", "0.008", "--steps", "16"]),
    **twins("slab40_E5k_finger8_neohooke", ["--thickness", "0.040", *E5K, *FINGER, "--mesh-size", "0.0005",
                                            *INCLUSION, "--max-depth", "0.008"]),
    **twins("slab40_E5k_finger8_neohooke_r10d20", ["--thickness", "0.040", *E5K, *FINGER, "--mesh-size", "0.0005",
                                                   *INCLUSION_R10D20, "--max-depth", "0.008"]),
    **twins("slab20_E5k_finger8_neohooke", ["--thickness", "0.020", *E5K, *FINGER, "--mesh-size", "0.0004",
                                            *INCLUSION, "--max-depth", "0.008"]),
    "slab40_E5k_finger8_neohooke": ["--thickness", "0.040", *E5K, *FINGER, "--mesh-size", "0.0005",
                                    "--max-depth", "0.0115"],
    "slab20_E5k_finger8_neohooke": ["--thickness", "0.020", *E5K, *FINGER, "--mesh-size", "0.0004",
                                    "--max-depth", "0.008"],
}


def run_case(name, args, out_dir):
    """Solve one case; returns a one-line summary."""
    out = os.path.join(out_dir, name + ".csv")
    cmd = ["nice", "-n", "19", sys.executable, INDENT, *args, "--out", out]
    res = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if res.returncode != 0:
        return f"{name}: FAILED: {res.stderr.strip().splitlines()[-1]}"
    times = re.search(r"wall ([\d.]+) s, cpu ([\d.]+) s", res.stderr)
    stop = re.search(r"stopped at depth ([\d.eE+-]+) m", res.stderr)
    text = f"{name}: wall {times.group(1)} s, cpu {times.group(2)} s"
    if stop:
        text += f", stopped after depth {float(stop.group(1)) * 1000:.2f} mm"
    return text


def stiffness_table():
    """Small-depth stiffness per kPa of the linear flat punch, two meshes."""
    sys.path.insert(0, HERE)
    import hayes
    import tempfile
    a, nu, E = 0.0075, 0.49, 5000.0
    sneddon = 2.0 * a / (1.0 - nu * nu)   # N/m per Pa, times 1000 for per kPa
    print("| h (mm) | layer radius (mm) | mesh at punch (mm) | FEM (N/m per kPa) | "
          "Sneddon | Sneddon x kappa | FEM / Sneddon | kappa |")
    print("|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for h, R in ((0.04, 0.06), (0.02, 0.06), (0.04, 0.18), (0.02, 0.18), (0.3, 0.6)):
            for lc in (a / 24.0, a / 12.0):
                out = os.path.join(tmp, "k.csv")
                subprocess.run(["nice", "-n", "19", sys.executable, INDENT, "--thickness", str(h),
                                "--radius", str(R), "--modulus", str(E), "--poisson", str(nu),
                                "--max-depth", "2e-4", "--steps", "1", "--mesh-size", str(lc),
                                "--quiet", "--out", out], check=True)
                d, F = map(float, open(out).read().split()[-1].split(","))
                k = F / d / (E / 1000.0)
                kap = hayes.kappa(a / h, nu)
                print(f"| {h * 1000:g} | {R * 1000:g} | {lc * 1000:.3g} | {k:.2f} | "
                      f"{sneddon * 1000:.2f} | {sneddon * 1000 * kap:.2f} | "
                      f"{k / (sneddon * 1000):.4f} | {kap:.4f} |")


def main(argv=None):
    p = argparse.ArgumentParser(description="Regenerate data/reference/*.csv")
    p.add_argument("--only", action="append", choices=sorted(CASES), help="run only this case")
    p.add_argument("--list", action="store_true", help="print the cases and their arguments")
    p.add_argument("--stiffness-table", action="store_true",
                   help="print the small-depth stiffness table instead")
    p.add_argument("--out-dir", default=OUT_DIR)
    o = p.parse_args(argv)
    if o.list:
        for name, args in CASES.items():
            print(f"{name}: indent.py {' '.join(args)}")
        return 0
    if o.stiffness_table:
        stiffness_table()
        return 0
    failed = False
    for name in o.only or CASES:
        line = run_case(name, CASES[name], o.out_dir)
        failed |= "FAILED" in line
        print(line, flush=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
