#!/usr/bin/python3
"""Fits a reduced model of on-axis tumour contrast to the committed FEM sweeps.

    C - 1 = A (q - 1) / (q + g) (r / a)^m (1 + (s / (k a))^2)^(-p) ((h - s) / h)^d (h / a)^e
            ((s - r) / a)^(-c)

r: inclusion radius, s: depth of its centre below the skin, q: its modulus over the
layer's, a: the pad radius (7.5 mm), h: the layer thickness. The factors, in order: the
dilute-inclusion form (0 at q = 1, saturating for a rigid sphere); the volume effect
(m near 3); the pad's strain field along its axis, about flat for the first few millimetres
and decaying as a power beyond k a (the way a flat punch's stresses spread under it); the
rigid base, which shields an inclusion near it; a thinner layer carrying its load through
less tissue, so an inclusion is a larger part of it; and the tissue left between the
inclusion's top and the skin (fitted with c < 0: the size effect saturates for an inclusion
that nearly reaches the skin). Fitted by least squares on log(C - 1) (relative error of the
extra force) to the sweeps of 20, 30 and 40 mm layers (data/reference/contrast_slab*_E5k_
linear.csv; the thickness is read from the file name), with numpy and scipy (Debian's
python3-numpy and python3-scipy).

    /usr/bin/python3 tools/fem/fit_contrast.py [--data CSV ...]

It also refits without each inclusion in turn, and without each thickness in turn, and
reports the worst error on what was left out (how well the model predicts an inclusion, or
a layer, it was not fitted to).
"""

import argparse
import csv
import glob
import math
import os
import re
import sys

import numpy as np
from scipy.optimize import least_squares

HERE = os.path.dirname(os.path.abspath(__file__))
REFERENCE = os.path.normpath(os.path.join(HERE, "..", "..", "data", "reference"))
DATA = sorted(glob.glob(os.path.join(REFERENCE, "contrast_slab*_E5k_linear.csv")))
PAD = 0.0075
NAMES = ("A", "g", "m", "p", "d", "e", "k", "c")
START = [1.0, 1.0, 3.0, 3.0, 0.3, -0.7, 2.0, -0.4]


def thickness_of(path):
    """The layer thickness (m) in a sweep's file name: contrast_slab40_... is 0.040."""
    m = re.search(r"contrast_slab(\d+)_", os.path.basename(path))
    if not m:
        raise ValueError(f"{path}: no thickness in the file name (contrast_slabNN_...)")
    return int(m.group(1)) / 1000.0


def load(paths):
    """Columns r, s, q, h, contrast of every inclusion of the sweeps."""
    rows = []
    for path in paths:
        h = thickness_of(path)
        with open(path) as f:
            rows += [(float(x["inclusion_radius_m"]), float(x["inclusion_depth_m"]), float(x["modulus_ratio"]), h,
                      float(x["contrast"])) for x in csv.DictReader(f)]
    return [np.array(col) for col in zip(*rows)]


def log_extra(theta, r, s, q, h):
    """log(C - 1) of the model."""
    log_a, g, m, p, d, e, k, c = theta
    return (log_a + np.log((q - 1.0) / (q + g)) + m * np.log(r / PAD) - p * np.log(1.0 + (s / (k * PAD)) ** 2)
            + d * np.log((h - s) / h) + e * np.log(h / PAD) - c * np.log((s - r) / PAD))


def fit(r, s, q, h, contrast):
    """Least-squares parameters (log A, g, m, p, d, e, k, c)."""
    res = least_squares(lambda t: log_extra(t, r, s, q, h) - np.log(contrast - 1.0), START,
                        bounds=([-10.0, -0.99, 0.0, 0.0, -5.0, -5.0, 0.1, -5.0], [10.0, 50.0, 6.0, 20.0, 5.0, 5.0, 20.0, 5.0]))
    return res.x.copy()


def worst_left_out(r, s, q, h, contrast, groups):
    """The largest error (share of C - 1) on a group left out of the fit in turn."""
    worst = 0.0
    for out in groups:
        keep = ~out
        theta = fit(r[keep], s[keep], q[keep], h[keep], contrast[keep])
        predicted = np.exp(log_extra(theta, r[out], s[out], q[out], h[out]))
        worst = max(worst, float(np.max(np.abs(predicted / (contrast[out] - 1.0) - 1.0))))
    return worst


def leave_one_out(r, s, q, h, contrast):
    n = len(r)
    return worst_left_out(r, s, q, h, contrast, [np.arange(n) == k for k in range(n)])


def leave_thickness_out(r, s, q, h, contrast):
    return {t: worst_left_out(r, s, q, h, contrast, [h == t]) for t in sorted(set(h))}


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--data", nargs="+", default=DATA, help="sweep CSVs (default: every committed one)")
    o = p.parse_args(argv)
    r, s, q, h, contrast = load(o.data)
    theta = fit(r, s, q, h, contrast)
    model = np.exp(log_extra(theta, r, s, q, h)) + 1.0
    rel = (model - 1.0) / (contrast - 1.0) - 1.0
    params = dict(zip(NAMES, [math.exp(theta[0]), *theta[1:]]))
    print("fitted: " + ", ".join(f"{k} = {v:.4g}" for k, v in params.items()))
    print(f"{len(r)} inclusions on {len(set(h))} layers: largest error {100 * np.max(np.abs(rel)):.1f} % of C - 1, "
          f"{np.max(np.abs(model - contrast)):.4f} absolute")
    print(f"left out of the fit in turn: largest error {100 * leave_one_out(r, s, q, h, contrast):.1f} % of C - 1")
    for t, e in leave_thickness_out(r, s, q, h, contrast).items():
        print(f"the {t * 1e3:.0f} mm layer left out: largest error on it {100 * e:.1f} % of C - 1")
    worst = int(np.argmax(np.abs(rel)))
    print(f"worst: {h[worst] * 1e3:g} mm layer, r {r[worst] * 1e3:g} mm, centre {s[worst] * 1e3:g} mm, ratio "
          f"{q[worst]:g}: FEM {contrast[worst]:.4f}, model {model[worst]:.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
