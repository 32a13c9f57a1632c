#!/usr/bin/python3
"""Fits a reduced model of on-axis tumour contrast to the committed FEM sweep.

    C - 1 = A * (q - 1) / (q + g) * (r / a)^m * exp(-b * s / h) * ((s - r) / a)^(-c)

r: inclusion radius, s: depth of its centre below the skin, q: its modulus over the
layer's, a: the pad radius (7.5 mm), h: the layer thickness (40 mm in the sweep, so the
s / h term is calibrated for that thickness only). The factor (q - 1) / (q + g) is the
dilute-inclusion form (0 at q = 1, saturating for a rigid sphere); (r / a)^m the volume
effect (m near 3); the exponential the fading of the pad's strain field with depth over a
rigid base; the gap term the tissue left between the inclusion's top and the skin.
Fitted by least squares on log(C - 1) (relative error of the extra force), with numpy and
scipy (Debian's python3-numpy and python3-scipy).

    /usr/bin/python3 tools/fem/fit_contrast.py [--data CSV]

It also refits without each inclusion in turn and reports the worst error on the one left
out (how well the model predicts an inclusion it was not fitted to).
"""

import argparse
import csv
import math
import os
import sys

import numpy as np
from scipy.optimize import least_squares

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.normpath(os.path.join(HERE, "..", "..", "data", "reference", "contrast_slab40_E5k_linear.csv"))
PAD = 0.0075
THICKNESS = 0.040
NAMES = ("A", "g", "m", "b", "c")


def log_extra(theta, r, s, q):
    """log(C - 1) of the model."""
    log_a, g, m, b, c = theta
    return (log_a + np.log((q - 1.0) / (q + g)) + m * np.log(r / PAD) - b * s / THICKNESS
            - c * np.log((s - r) / PAD))


def fit(r, s, q, contrast):
    """Least-squares parameters (log A, g, m, b, c)."""
    res = least_squares(lambda t: log_extra(t, r, s, q) - np.log(contrast - 1.0), [0.0, 1.0, 3.0, 5.0, 0.1],
                        bounds=([-10.0, -0.99, 0.0, -20.0, -5.0], [10.0, 50.0, 6.0, 30.0, 5.0]))
    return res.x.copy()


def leave_one_out(r, s, q, contrast):
    """The largest error (share of C - 1) on an inclusion left out of the fit."""
    worst = 0.0
    for k in range(len(r)):
        keep = np.arange(len(r)) != k
        theta = fit(r[keep], s[keep], q[keep], contrast[keep])
        predicted = math.exp(log_extra(theta, r[k], s[k], q[k]))
        worst = max(worst, abs(predicted / (contrast[k] - 1.0) - 1.0))
    return worst


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--data", default=DATA)
    o = p.parse_args(argv)
    with open(o.data) as f:
        rows = list(csv.DictReader(f))
    r = np.array([float(x["inclusion_radius_m"]) for x in rows])
    s = np.array([float(x["inclusion_depth_m"]) for x in rows])
    q = np.array([float(x["modulus_ratio"]) for x in rows])
    contrast = np.array([float(x["contrast"]) for x in rows])
    theta = fit(r, s, q, contrast)
    model = np.exp(log_extra(theta, r, s, q)) + 1.0
    rel = (model - 1.0) / (contrast - 1.0) - 1.0
    params = dict(zip(NAMES, [math.exp(theta[0]), *theta[1:]]))
    print("fitted: " + ", ".join(f"{k} = {v:.4g}" for k, v in params.items()))
    print(f"{len(rows)} inclusions: largest error {100 * np.max(np.abs(rel)):.1f} % of C - 1, "
          f"{np.max(np.abs(model - contrast)):.4f} absolute")
    print(f"left out of the fit in turn: largest error {100 * leave_one_out(r, s, q, contrast):.1f} % of C - 1")
    worst = int(np.argmax(np.abs(rel)))
    print(f"worst: r {r[worst] * 1e3:g} mm, centre {s[worst] * 1e3:g} mm, ratio {q[worst]:g}: "
          f"FEM {contrast[worst]:.4f}, model {model[worst]:.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
