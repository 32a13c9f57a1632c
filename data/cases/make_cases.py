#!/usr/bin/env python3
"""Writes the bundled Palpa cases (format v1) into this directory.

Deterministic: every value is computed from closed-form profiles, with no
randomness, so running it again reproduces the committed files byte for byte.
Usage: python3 data/cases/make_cases.py [--out DIR]

Conventions shared by all cases (see docs/case-format.md):
- point (i, j) is stored at index i*cols + j; u runs along the rows (i), v along
  the columns (j);
- the grids are oriented so that Su x Sv points towards the "top" contour
  (upwards, or outwards on curved skeletons);
- the radius is exactly 0 on the grid boundary (the paper's closure condition).
"""

import argparse
import json
import math
import os

M_DIGITS = 6  # lengths rounded to 1e-6 m
K_DIGITS = 3  # stiffness rounded to 1e-3 N/m
B_DIGITS = 6  # damping rounded to 1e-6 N s/m
MASS_DIGITS = 6  # mass rounded to 1e-6 kg


def rnd(x, digits):
    y = round(float(x), digits)
    return 0.0 if y == 0 else y  # no "-0.0" in the files


def unit(n, k):
    """k-th of n evenly spaced values on [-1, 1]: exactly -1 and 1 at the ends and
    antisymmetric, so symmetric profiles give bit-identical mirrored values."""
    return (2 * k - (n - 1)) / (n - 1)


def lin(a, b, n, k):
    """k-th of n evenly spaced values from a to b."""
    return (a + b) / 2 + (b - a) / 2 * unit(n, k)


def bump(s, t):
    """Smooth profile on [-1, 1]^2: 1 at the centre, exactly 0 on the boundary."""
    return (1.0 - s * s) * (1.0 - t * t)


def body(body_id, rows, cols, point, radius, stiffness, damping=None, mass=None, extra=None, modulus=None):
    """Builds a body dict from per-site functions f(i, j); with `modulus` (Pa) the tissue
    is given by its Young's modulus instead of the stiffness (docs/case-format.md)."""
    sites = [(i, j) for i in range(rows) for j in range(cols)]
    b = {"id": body_id, "rows": rows, "cols": cols}
    if extra:
        b.update(extra)
    b["medial"] = [[rnd(c, M_DIGITS) for c in point(i, j)] for i, j in sites]
    b["radius"] = [rnd(radius(i, j), M_DIGITS) for i, j in sites]
    if modulus is not None:
        b["modulus"] = [rnd(modulus(i, j), K_DIGITS) for i, j in sites]
    else:
        b["stiffness"] = [rnd(stiffness(i, j), K_DIGITS) for i, j in sites]
    if damping is not None:
        b["damping"] = [rnd(damping(i, j), B_DIGITS) for i, j in sites]
    if mass is not None:
        b["mass"] = [rnd(mass(i, j), MASS_DIGITS) for i, j in sites]
    for i, j in sites:
        if i in (0, rows - 1) or j in (0, cols - 1):
            assert b["radius"][i * cols + j] == 0.0, (body_id, i, j)
    return b


def case(title, bodies, tumors=None, **extra):
    c = {"format": "palpa-case", "version": 1, "title": title}
    c.update(extra)  # fields unknown to v1 (description, notes, ...): preserved by Palpa
    c["bodies"] = bodies
    if tumors is not None:
        c["tumors"] = tumors
    return c


# --- default.json: a breast-like body with one palpable mass ----------------

BREAST_ROWS, BREAST_COLS = 9, 11
BREAST_LX, BREAST_LY = 0.14, 0.16  # base extent along x (rows) and y (cols), m
BREAST_H = 0.05  # projection from the chest wall, m
# The default breast in kPa (docs/case-authoring.md, "Tissue materials"): fibroglandular
# tissue at small strain, 3.24 kPa (Samani, Zubovits and Plewes 2007), stiffening with
# b = ln(48 / 28) / 0.15 (Krouskop et al. 1998, glandular tissue at 5 % and 20 %); an
# invasive ductal carcinoma six times as stiff at small strain (Samani: 3-6 times)
# stiffening with b = ln(558 / 106) / 0.15 (Krouskop).
GLAND_E, GLAND_B = 3240.0, 3.593
CARCINOMA_E, CARCINOMA_B = 19440.0, 11.073


def breast_st(i, j):
    return unit(BREAST_ROWS, i), unit(BREAST_COLS, j)


def breast_profile_xy(x, y):
    return bump(2.0 * x / BREAST_LX, 2.0 * y / BREAST_LY)


def make_default():
    def point(i, j):
        s, t = breast_st(i, j)
        # The skeleton is the mid-surface: z_s = H/2 f, radius = H/2 f, so the
        # bottom contour lies near z = 0 (chest wall) and the top is a dome of height H.
        return (s * BREAST_LX / 2, t * BREAST_LY / 2, BREAST_H / 2 * bump(s, t))

    def radius(i, j):
        return BREAST_H / 2 * bump(*breast_st(i, j))

    # The breast lies on the chest wall: only its top contour (the skin) can be touched.
    b = body("breast", BREAST_ROWS, BREAST_COLS, point, radius, None, extra={"support": "bottom"},
             modulus=lambda i, j: GLAND_E)
    b["stiffening"] = GLAND_B

    # One mass in the upper-outer region, off the apex, at mid-depth (on the
    # skeleton, halfway between chest wall and skin).
    cx, cy = 0.35 * BREAST_LX / 2, 0.25 * BREAST_LY / 2
    cz = BREAST_H / 2 * breast_profile_xy(cx, cy)
    tumor = {
        "body": "breast",
        "center": [rnd(cx, M_DIGITS), rnd(cy, M_DIGITS), rnd(cz, M_DIGITS)],
        "radius": 0.007,
        "modulus": CARCINOMA_E,
        "stiffening": CARCINOMA_B,
        # Seeded exercises move the centre (docs/case-format.md, "placement"): anywhere
        # over the breast's interior, its centre 40-50 % of the thickness below the skin
        # (about on the skeleton). A light press (a fifth of the thickness) feels it at most
        # about 1.15 times firmer, less than a finger tells apart; a press to half the
        # thickness more than 1.2 times (docs/user-guide.md, "Cases in kPa";
        # tests/core/scripted/scripted_placement_test.cpp).
        "placement": {"u": [0.3, 0.7], "v": [0.3, 0.7], "depth": [0.4, 0.5]},
    }
    check_tumor_inside(b, tumor)
    return case(
        "Breast, left, one palpable mass",
        [b],
        description=(
            "Breast-like dome on the chest wall (z = 0): base 0.14 m x 0.16 m, "
            "projection 0.05 m, of fibroglandular tissue (3.24 kPa, stiffening with strain "
            "as glandular tissue does). One 14 mm invasive carcinoma (19.4 kPa at small "
            "strain, stiffening much faster) at mid-depth in the upper-outer region: a "
            "light press hardly feels it, a deep one does. Seeded exercises place it at "
            "random over the interior, 40-50 % of the thickness below the skin."
        ),
        notes="damping and mass are omitted: the defaults apply (mass 1e-3 kg, damping ratio 0.7 per point).",
        tumors=[tumor],
    )


def check_tumor_inside(b, tumor):
    """Asserts the tumour sphere lies strictly inside the body."""
    rows, cols = b["rows"], b["cols"]
    c, rt = tumor["center"], tumor["radius"]
    # Nearest grid site in the plane.
    best = min(range(rows * cols),
               key=lambda k: (b["medial"][k][0] - c[0]) ** 2 + (b["medial"][k][1] - c[1]) ** 2)
    p, r = b["medial"][best], b["radius"][best]
    # Linear approximation at the grid: the centre lies between bottom and top there.
    assert abs(c[2] - p[2]) < r, "tumour centre outside the body at the nearest site"
    # The whole tumour sphere inside that site's medial sphere, hence inside the body
    # (the body is the union of its medial spheres).
    assert math.dist(c, p) + rt < r, "tumour sphere not inside the nearest medial sphere"
    # And between chest wall (z = 0) and skin (z = H f) with the analytic profile,
    # sampled over the tumour's surface.
    for a in range(0, 360, 15):
        for e in range(-90, 91, 15):
            x = c[0] + rt * math.cos(math.radians(e)) * math.cos(math.radians(a))
            y = c[1] + rt * math.cos(math.radians(e)) * math.sin(math.radians(a))
            z = c[2] + rt * math.sin(math.radians(e))
            assert 0.0 < z < BREAST_H * breast_profile_xy(x, y), "tumour crosses the body surface"


# --- ladder-N.json: the same breast in kPa, one mass harder to find at each rung ----

# Breast fat and fibroglandular tissue are about equally stiff at small strain, 3.25 kPa
# (Samani, Zubovits and Plewes, Phys. Med. Biol. 52, 2007); invasive carcinoma is 3-13
# times that, about 10-45 kPa (the same study). The contrast is what Palpa gives pressed
# 10 mm straight down over the mass (`palpa-cli probe`, against the same case with the
# mass at the tissue's modulus), from the finite-element fit of docs/model.md
# ("Tumours in Pa"); the fitted skin lies about 2 mm above this script's analytic dome,
# so the centres are about 2 mm deeper than `below` says.
BREAST_E = 3250.0
LADDER = (
    # (diameter m, centre below the analytic skin m, modulus Pa, title, contrast in Palpa)
    (0.020, 0.015, 45000.0, "superficial hard mass", 1.57),
    (0.015, 0.012, 30000.0, "mid-size mass", 1.31),
    (0.012, 0.012, 30000.0, "small mass", 1.18),
    (0.010, 0.010, 30000.0, "a 1 cm mass: expert", 1.12),
)


def make_ladder(rung):
    diameter, below, modulus, what, contrast = LADDER[rung - 1]

    def point(i, j):
        s, t = breast_st(i, j)
        return (s * BREAST_LX / 2, t * BREAST_LY / 2, BREAST_H / 2 * bump(s, t))

    def radius(i, j):
        return BREAST_H / 2 * bump(*breast_st(i, j))

    b = body("breast", BREAST_ROWS, BREAST_COLS, point, radius, None, extra={"support": "bottom"},
             modulus=lambda i, j: BREAST_E)
    # The default case's spot in the upper-outer region, `below` under the skin.
    cx, cy = 0.35 * BREAST_LX / 2, 0.25 * BREAST_LY / 2
    cz = BREAST_H * breast_profile_xy(cx, cy) - below
    tumor = {
        "body": "breast",
        "center": [rnd(cx, M_DIGITS), rnd(cy, M_DIGITS), rnd(cz, M_DIGITS)],
        "radius": diameter / 2,
        "modulus": modulus,
    }
    check_tumor_inside(b, tumor)
    return case(
        f"Breast in kPa, ladder {rung} of {len(LADDER)}: {what}",
        [b],
        description=(
            f"The default breast's shape (base 0.14 m x 0.16 m, projection 0.05 m, on the chest wall) "
            f"in tissue of {BREAST_E / 1000:g} kPa, with one {diameter * 1000:g} mm mass of "
            f"{modulus / 1000:g} kPa whose centre lies about {below * 1000 + 2:g} mm under the skin "
            f"in the upper-outer region: {contrast:.2f} times the force over it (pressed 10 mm; "
            f"the finite-element fit of docs/model.md). Rungs 1-4 go from a mass the scripted "
            f"expert finds to ones only a careful examiner can tell from the tissue."
        ),
        tumors=[tumor],
    )


# --- small cases used by the tests ---------------------------------------------

def make_flat():
    n, half = 5, 0.05

    def point(i, j):
        return (lin(-half, half, n, i), lin(-half, half, n, j), 0.0)

    return case(
        "Flat 5x5: plane skeleton, polynomial radius",
        [body("flat", n, n, point,
              lambda i, j: 0.02 * bump(unit(n, i), unit(n, j)),
              lambda i, j: 200.0)],
        description=(
            "Skeleton: the plane z = 0 on a uniform 5x5 grid over [-0.05, 0.05]^2 m. "
            "Radius 0.02 (1 - s^2)(1 - t^2) m with s = x/0.05, t = y/0.05: a bicubic "
            "polynomial that a bicubic spline reproduces exactly on a uniform grid. "
            "Stiffness 200 N/m."
        ),
    )


def make_cylinder():
    rows, cols, rc, length = 7, 9, 0.1, 0.12

    def point(i, j):
        theta = math.radians(lin(-45.0, 45.0, rows, i))
        return (rc * math.sin(theta), lin(-length / 2, length / 2, cols, j), rc * math.cos(theta))

    return case(
        "Cylinder 7x9: curved skeleton",
        [body("cylinder", rows, cols, point,
              lambda i, j: 0.015 * bump(unit(rows, i), unit(cols, j)),
              lambda i, j: 300.0)],
        description=(
            "Skeleton on a cylinder of radius 0.1 m with its axis along y: 7 rows over "
            "a 90 degree arc (u), 9 columns over 0.12 m along the axis (v). The top "
            "contour is on the outer side. Radius 0.015 (1 - s^2)(1 - t^2) m."
        ),
    )


def make_strip(rows, cols):
    lx, ly = (0.04, 0.16) if rows < cols else (0.16, 0.04)

    def point(i, j):
        x, y = lin(-lx / 2, lx / 2, rows, i), lin(-ly / 2, ly / 2, cols, j)
        return (x, y, 0.01 - 0.5 * (x * x + y * y))  # gently curved: 1 m radius of curvature

    def stiffness(i, j):
        return 150.0 + 100.0 * bump(unit(rows, i), unit(cols, j))

    name = f"strip-{rows}x{cols}"
    return case(
        f"Strip {rows}x{cols}: three sites across",
        [body("strip", rows, cols, point,
              lambda i, j: 0.008 * bump(unit(rows, i), unit(cols, j)),
              stiffness)],
        description=(
            f"{name}: only 3 sites in one direction, so the middle line is the only "
            "interior one and carries all the non-zero radii (degree 2 across). "
            "Gently curved skeleton z = 0.01 - (x^2 + y^2)/2 m."
        ),
    )


def make_pole():
    rows, cols, rs = 5, 6, 0.08
    phi_max, az_max = 60.0, 180.0

    def point(i, j):
        phi = math.radians(lin(0.0, phi_max, rows, i))
        az = math.radians(lin(0.0, az_max, cols, j))
        if i == 0:
            return (0.0, 0.0, rs)  # every column meets at the pole
        return (rs * math.sin(phi) * math.cos(az), rs * math.sin(phi) * math.sin(az), rs * math.cos(phi))

    return case(
        "Pole 5x6: spherical cap with a collapsed row",
        [body("cap", rows, cols, point,
              lambda i, j: 0.01 * bump(unit(rows, i), unit(cols, j)),
              lambda i, j: 250.0)],
        description=(
            "Half of a spherical cap (sphere radius 0.08 m, polar angle 0-60 degrees "
            "along the rows, azimuth 0-180 degrees along the columns). Row 0 is the "
            "pole: all its sites coincide, which is legal. Radius 0 on the boundary."
        ),
    )


def make_two_bodies():
    n = 5

    def dome(x0, height):
        def point(i, j):
            s, t = unit(n, i), unit(n, j)
            return (x0 + 0.04 * s, 0.04 * t, height / 2 * bump(s, t))
        return point

    def radius(height):
        return lambda i, j: height / 2 * bump(unit(n, i), unit(n, j))

    left = body("left", n, n, dome(-0.06, 0.03), radius(0.03), lambda i, j: 200.0,
                extra={"support": "bottom", "comment": "defaults apply for damping and mass"})
    right = body("right", n, n, dome(0.06, 0.02), radius(0.02),
                 lambda i, j: 400.0 + 200.0 * bump(unit(n, i), unit(n, j)),
                 damping=lambda i, j: 1.5, mass=lambda i, j: 2e-3,
                 extra={"support": "bottom", "comment": "explicit damping (N s/m) and mass (kg)"})
    return case(
        "Two bodies: separate domes",
        [left, right],
        author="Palpa project",
        description=(
            "Two separated 5x5 domes on a table (support \"bottom\"), ids \"left\" and \"right\"; \"right\" has explicit "
            "damping and mass arrays. The \"author\" and \"comment\" fields are unknown to "
            "format v1 and must be preserved on load and save."
        ),
    )


CASES = {
    "default.json": make_default,
    "flat-5x5.json": make_flat,
    "cylinder-7x9.json": make_cylinder,
    "strip-3x9.json": lambda: make_strip(3, 9),
    "strip-9x3.json": lambda: make_strip(9, 3),
    "pole-5x6.json": make_pole,
    "two-bodies.json": make_two_bodies,
    **{f"ladder-{k}.json": (lambda k=k: make_ladder(k)) for k in range(1, len(LADDER) + 1)},
}


# --- output ------------------------------------------------------------------

def fmt(v):
    if isinstance(v, bool) or v is None:
        return json.dumps(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        assert math.isfinite(v)
        return repr(0.0 if v == 0 else v)
    return json.dumps(v, ensure_ascii=False)


PER_POINT = ("radius", "stiffness", "modulus", "damping", "mass")


def dump(v, ind=0, wrap=None):
    """Pretty JSON: one medial point per line, per-point arrays one grid row per line."""
    pad, pad2 = " " * ind, " " * (ind + 2)
    if isinstance(v, dict):
        cols = v.get("cols") if isinstance(v.get("cols"), int) else None
        items = [f"{pad2}{json.dumps(k)}: {dump(x, ind + 2, cols if k in PER_POINT else None)}"
                 for k, x in v.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(v, list):
        if all(not isinstance(x, (dict, list)) for x in v):
            if wrap and len(v) > wrap:
                lines = [", ".join(fmt(x) for x in v[k:k + wrap]) for k in range(0, len(v), wrap)]
                return "[\n" + ",\n".join(pad2 + line for line in lines) + "\n" + pad + "]"
            return "[" + ", ".join(fmt(x) for x in v) + "]"
        return "[\n" + ",\n".join(pad2 + dump(x, ind + 2) for x in v) + "\n" + pad + "]"
    return fmt(v)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=os.path.dirname(os.path.abspath(__file__)))
    args = ap.parse_args()
    for name, make in CASES.items():
        text = dump(make()) + "\n"
        assert json.loads(text) is not None
        with open(os.path.join(args.out, name), "w", encoding="utf-8", newline="\n") as f:
            f.write(text)
        print(f"wrote {name} ({len(text)} bytes)")


if __name__ == "__main__":
    main()
