#!/usr/bin/python3
"""Tumour contrast on the axis of a flat fingertip pad: a linear sweep of inclusions.

For every inclusion of the sweep (a sphere of radius r, centre s below the skin, modulus
ratio q times the layer's, on the axis under the 7.5 mm flat punch of a layer of 5 kPa,
40 mm thick unless --thickness says otherwise, bonded to a rigid base), tools/fem/indent.py solves the linear problem at a small
depth twice on the same mesh: with the inclusion at q and at 1 (its twin, no contrast).
The contrast is C = F(q) / F(1). In linear elasticity C does not depend on the press
depth, so one small depth (0.5 mm) gives it.

    /usr/bin/python3 tools/fem/contrast_sweep.py                 # the committed 40 mm CSV
    /usr/bin/python3 tools/fem/contrast_sweep.py --thickness 0.020  # contrast_slab20_E5k_linear.csv
    /usr/bin/python3 tools/fem/contrast_sweep.py --out OTHER.csv

The model is axisymmetric, so the inclusion is always on the pad's axis: lateral offsets
need a 3-D model (data/reference/README.md says so). Inclusions within 5 % of the
thickness (2 mm of 40) of the skin or of the base are left out, as indent.py requires.
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
INDENT = os.path.join(HERE, "indent.py")


def default_out(thickness):
    """The committed file of a thickness: contrast_slab40_E5k_linear.csv for 40 mm."""
    return os.path.join(ROOT, "data", "reference", f"contrast_slab{round(thickness * 1e3)}_E5k_linear.csv")


RADII = (0.003, 0.005, 0.010)
DEPTHS = (0.005, 0.010, 0.015, 0.020, 0.025)
RATIOS = (3.0, 5.0, 10.0)
CLEARANCE = 0.05  # share of the thickness: more tissue than this between the inclusion and the skin or base
PRESS = 0.0005     # m: the press depth the forces are solved at


def force(thickness, radius, depth, ratio, tmp):
    """The linear FEM force (N) at PRESS with the given inclusion."""
    out = os.path.join(tmp, "f.csv")
    cmd = ["nice", "-n", "19", sys.executable, INDENT, "--thickness", str(thickness), "--modulus", "5000",
           "--poisson", "0.49", "--inclusion-radius", str(radius), "--inclusion-depth", str(depth),
           "--inclusion-ratio", str(ratio), "--max-depth", str(PRESS), "--steps", "1", "--quiet", "--out", out]
    subprocess.run(cmd, check=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    with open(out) as f:
        return float(f.read().split()[-1].split(",")[1])


def sweep(thickness):
    """Yields (radius, depth, ratio, force, twin force) for every inclusion of the sweep."""
    gap = CLEARANCE * thickness
    with tempfile.TemporaryDirectory(prefix="palpa_contrast_") as tmp:
        for r in RADII:
            for s in DEPTHS:
                if s - r <= gap or s + r >= thickness - gap:
                    continue
                twin = force(thickness, r, s, 1.0, tmp)
                for q in RATIOS:
                    yield r, s, q, force(thickness, r, s, q, tmp), twin


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--thickness", type=float, default=0.040, help="layer thickness h (m, default 0.040)")
    p.add_argument("--out", help="CSV to write (default: the committed data/reference file of the thickness)")
    o = p.parse_args(argv)
    if not 0.005 <= o.thickness <= 0.300:
        p.error("--thickness must be between 0.005 and 0.300 m")
    out_path = o.out or default_out(o.thickness)
    start = time.monotonic()
    rows = []
    for r, s, q, f, twin in sweep(o.thickness):
        rows.append(f"{r:.4f},{s:.4f},{q:g},{f:.6e},{twin:.6e},{f / twin:.5f}")
        print(f"r {r * 1e3:4.1f} mm, centre {s * 1e3:4.1f} mm deep, ratio {q:4g}: contrast {f / twin:.4f}",
              flush=True)
    with open(out_path, "w") as f:
        f.write("inclusion_radius_m,inclusion_depth_m,modulus_ratio,force_n,twin_force_n,contrast\n")
        f.write("\n".join(rows) + "\n")
    print(f"wrote {out_path}: {len(rows)} inclusions in {time.monotonic() - start:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
