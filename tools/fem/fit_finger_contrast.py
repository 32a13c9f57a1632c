#!/usr/bin/python3
"""Fits how the reduced contrast model is read under the rounded finger.

The reduced model of fit_contrast.py gives a tumour's contrast C under the 7.5 mm flat pad.
Under the 8 mm rounded finger the contact is a disc of Sneddon's radius c(d), a few
millimetres across at a shallow press: its strain field is concentrated near the axis, so
a small, shallow inclusion stands out more than under the pad and a large, deep one less,
until the contact has widened. The pad's model is read with an effective pad radius and a
compression of its own:

    a_f = alpha a (c / a)^n            the pad radius the finger's contact acts like
    s' = s - kappa d,  h' = h - kappa d   the tissue over and under the inclusion, pressed
    C - 1 = beta * [the pad model at (r, s', q, h') with a_f for a and e_f for e]

alpha, n, beta, kappa and e_f are fitted to the three neo-Hookean finger twins of
data/reference (an inclusion at 5x and its 1x twin, divided row by row), after the pad's
eight are refitted to the linear sweeps exactly as fit_contrast.py does. The loss is the
cube of each row's error over the bench's mark, max(0.2 (C - 1), 0.02), so the worst row
counts most (about a minimax fit).

    /usr/bin/python3 tools/fem/fit_finger_contrast.py

Three twins fix five parameters, so the fit is a calibration, not a validation: it also
refits without each twin in turn and reports how far off the left-out twin is.
"""

import csv
import math
import os
import sys

import numpy as np
from scipy.optimize import least_squares

import fit_contrast

HERE = os.path.dirname(os.path.abspath(__file__))
REFERENCE = fit_contrast.REFERENCE
PAD = fit_contrast.PAD
FINGER = 0.008  # m, the reference sphere's radius
# (file stem, inclusion radius, centre depth below the skin, layer thickness), all m.
TWINS = (("slab40_E5k_finger8_neohooke_incl", 0.005, 0.010, 0.040),
         ("slab40_E5k_finger8_neohooke_r10d20_incl", 0.010, 0.020, 0.040),
         ("slab20_E5k_finger8_neohooke_incl", 0.005, 0.010, 0.020))
RATIO = 5.0
NAMES = ("alpha", "n", "beta", "kappa", "e_f")
START = (1.0, 0.7, 1.0, 0.2, -0.75)
BOUNDS = ([0.2, 0.1, 0.05, 0.0, -3.0], [5.0, 2.0, 20.0, 3.0, 3.0])


def contact_radius(depth, radius=FINGER):
    """Sneddon's contact radius c of a rigid sphere pressed `depth` deep: d = (c/2) ln((R+c)/(R-c))."""
    lo, hi = 0.0, radius
    for _ in range(200):
        c = 0.5 * (lo + hi)
        if 0.5 * c * math.log((radius + c) / (radius - c)) > depth:
            hi = c
        else:
            lo = c
    return lo


def read_curve(stem):
    with open(os.path.join(REFERENCE, stem)) as f:
        return [(float(x["depth_m"]), float(x["force_n"])) for x in csv.DictReader(f)]


def load():
    """Rows (r, s, h, press, FEM contrast, twin index) of every finger twin, first touch on."""
    rows = []
    for index, (stem, r, s, h) in enumerate(TWINS):
        plain = dict(read_curve(stem + "1x.csv"))
        rows += [(r, s, h, d, f / plain[d], index) for d, f in read_curve(stem + "5x.csv") if d > 0.0 and d in plain]
    return rows


def pad_extra(pad, r, s, q, h, a, e):
    """C - 1 of the pad's model (the C++ clamps included) with pad radius a and layer power e."""
    log_a, g, m, p, d, _, k, c = pad
    depth = min(max(s, 0.0), 0.95 * h)
    gap = max(s - r, 0.05 * h)
    return (math.exp(log_a) * (q - 1.0) / (q + g) * (r / a) ** m * (1.0 + (depth / (k * a)) ** 2) ** (-p)
            * ((h - depth) / h) ** d * (h / a) ** e * (gap / a) ** (-c))


def finger_extra(theta, pad, r, s, h, press):
    alpha, n, beta, kappa, e_f = theta
    a_f = alpha * PAD * (contact_radius(press) / PAD) ** n
    return beta * pad_extra(pad, r, s - kappa * press, RATIO, h - kappa * press, a_f, e_f)


def mark(contrast):
    return max(0.2 * (contrast - 1.0), 0.02)


def errors(theta, pad, rows):
    """Each row's error over its mark (1 = on the mark)."""
    return [(finger_extra(theta, pad, r, s, h, d) - (C - 1.0)) / mark(C) for r, s, h, d, C, _ in rows]


def fit(pad, rows):
    res = least_squares(lambda t: np.array(errors(t, pad, rows)) ** 3, START, bounds=BOUNDS)
    return res.x.copy()


def pad_parameters():
    return fit_contrast.fit(*fit_contrast.load(fit_contrast.DATA))


def main(argv=None):
    pad = pad_parameters()
    rows = load()
    theta = fit(pad, rows)
    print("fitted: " + ", ".join(f"{k} = {v:.4g}" for k, v in zip(NAMES, theta)))
    for index, (stem, r, s, h) in enumerate(TWINS):
        mine = [x for x in rows if x[5] == index]
        others = [x for x in rows if x[5] != index]
        worst = max(abs(e) for e in errors(theta, pad, mine))
        left_out = max(abs(e) for e in errors(fit(pad, others), pad, mine))
        print(f"{stem}: {len(mine)} presses, worst {worst:.2f} of the mark; fitted without it: {left_out:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
