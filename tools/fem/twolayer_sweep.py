#!/usr/bin/python3
"""Two-layer columns under the flat fingertip pad: linear FEM stiffness, and the rules.

Each column is a soft layer over a stiffer one or the reverse (3.25 kPa fat and 13 kPa
glandular tissue, ratio 0.25 and 4), or 2 mm of 56 kPa skin over fat, bonded to a rigid
base, under the 7.5 mm flat punch, nu = 0.49 (tools/fem/indent.py --layers). One linear
solve per column at a small depth gives its stiffness k = F / d (N/m), which does not
depend on the depth.

    /usr/bin/python3 tools/fem/twolayer_sweep.py            # data/reference/twolayer_linear.csv
    /usr/bin/python3 tools/fem/twolayer_sweep.py --out OTHER.csv
    /usr/bin/python3 tools/fem/twolayer_sweep.py --compare  # the committed file against the rules

--compare reads the CSV and prints, per column, the stiffness of a homogeneous layer of
the column's equivalent modulus under two rules, k = 2 a E_eff kappa(a/h, nu) / (1 - nu^2)
(Hayes et al. 1972, tools/fem/hayes.py), and its error against the FEM:

  compliance-weighted  1/E_eff = sum_i (c(z_i+1) - c(z_i)) / (c(h) E_i), with
                       c(z) = (1 - nu^2) / (2 a kappa(a/z, nu)) the compliance per unit
                       modulus of a bonded layer z thick (c(0) = 0);
  series               1/E_eff = sum_i t_i / (h E_i), thickness-weighted springs in series;

and under the column's own kappa (hayes.column_modulus, which palpa::mat::column_modulus
computes the same way): Hayes et al.'s integral equation with the layered column's surface
compliance in place of the homogeneous layer's.
"""

import argparse
import csv
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
INDENT = os.path.join(HERE, "indent.py")
DEFAULT_OUT = os.path.join(ROOT, "data", "reference", "twolayer_linear.csv")

A = 0.0075         # m, the pad radius
NU = 0.49
PRESS = 0.0005     # m: the depth each linear solve is made at
FAT, GLAND, SKIN = 3250.0, 13000.0, 56000.0   # Pa
COLUMNS = ([(h, top, e_top, e_bottom)
            for h in (0.030, 0.040) for top in (0.005, 0.010, 0.020)
            for e_top, e_bottom in ((FAT, GLAND), (GLAND, FAT))]
           + [(h, 0.002, SKIN, FAT) for h in (0.030, 0.040)])
HEADER = "total_m,top_m,top_modulus_pa,bottom_modulus_pa,stiffness_n_per_m"


def stiffness(h, top, e_top, e_bottom, tmp):
    """The linear FEM stiffness F / d (N/m) of one two-layer column."""
    out = os.path.join(tmp, "f.csv")
    layers = f"{top!r}:{e_top!r},{h - top!r}:{e_bottom!r}"
    cmd = ["nice", "-n", "19", sys.executable, INDENT, "--layers", layers, "--poisson", str(NU),
           "--max-depth", str(PRESS), "--steps", "1", "--quiet", "--out", out]
    subprocess.run(cmd, check=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    with open(out) as f:
        return float(f.read().split()[-1].split(",")[1]) / PRESS


def run(out_path):
    start = time.monotonic()
    rows = []
    with tempfile.TemporaryDirectory(prefix="palpa_twolayer_") as tmp:
        for h, top, e_top, e_bottom in COLUMNS:
            k = stiffness(h, top, e_top, e_bottom, tmp)
            rows.append(f"{h:.4f},{top:.4f},{e_top:g},{e_bottom:g},{k:.6e}")
            print(f"h {h * 1e3:g} mm, top {top * 1e3:g} mm at {e_top:g} Pa over {e_bottom:g} Pa: "
                  f"{k:.4f} N/m", flush=True)
    with open(out_path, "w") as f:
        f.write(HEADER + "\n" + "\n".join(rows) + "\n")
    print(f"wrote {out_path}: {len(rows)} columns in {time.monotonic() - start:.0f} s")


def compliance(z):
    """c(z): compliance of a bonded layer z thick per unit modulus (m/N times Pa)."""
    import hayes
    return 0.0 if z <= 0.0 else (1.0 - NU * NU) / (2.0 * A * hayes.kappa(A / z, NU))


def compare(path):
    import hayes
    print("h_mm,top_mm,ratio,fem_n_per_m,column_n_per_m,column_err_pct,"
          "compliance_weighted_n_per_m,compliance_weighted_err_pct,series_n_per_m,series_err_pct")
    worst = [0.0, 0.0, 0.0]
    with open(path) as f:
        for r in csv.DictReader(f):
            h, top = float(r["total_m"]), float(r["top_m"])
            e1, e2, k = float(r["top_modulus_pa"]), float(r["bottom_modulus_pa"]), float(r["stiffness_n_per_m"])
            ch, c1 = compliance(h), compliance(top)
            per_pa = 2.0 * A * hayes.kappa(A / h, NU) / (1.0 - NU * NU)
            moduli = (hayes.column_modulus(A, [(top, e1), (h - top, e2)], NU),
                      1.0 / (c1 / (ch * e1) + (ch - c1) / (ch * e2)),
                      1.0 / (top / (h * e1) + (h - top) / (h * e2)))
            line = f"{h * 1e3:g},{top * 1e3:g},{e1 / e2:g},{k:.3f}"
            for i, E in enumerate(moduli):
                err = 100 * (E * per_pa / k - 1)
                worst[i] = max(worst[i], abs(err))
                line += f",{E * per_pa:.3f},{err:+.1f}"
            print(line, flush=True)
    print(f"worst error: column {worst[0]:.1f} %, compliance-weighted {worst[1]:.1f} %, "
          f"series {worst[2]:.1f} %")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--out", default=DEFAULT_OUT, help="CSV to write (default: the committed file)")
    p.add_argument("--compare", action="store_true", help="compare the CSV with the rules, no solve")
    o = p.parse_args(argv)
    if o.compare:
        sys.path.insert(0, HERE)
        sys.dont_write_bytecode = True
        compare(o.out)
    else:
        run(o.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
