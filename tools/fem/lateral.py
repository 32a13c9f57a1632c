#!/usr/bin/python3
"""Tumour contrast beside the fingertip pad's axis: a 3-D linear finite-element model.

The axisymmetric model of indent.py can only place an inclusion on the pad's axis. Here
the same problem is solved in 3-D: a slab 120 mm wide and h thick bonded to a rigid base,
a rigid frictionless flat pad of radius a = 7.5 mm pressed into the middle of its top
(the skin nodes with x^2 + y^2 <= a^2 moved down, their in-plane motion free), and a stiff
sphere of radius r whose centre lies s below the skin and `offset` beside the pad's axis.
Only the half y >= 0 is modelled (the plane y = 0 through the axis and the inclusion's
centre is a plane of symmetry: u_y = 0 there).

gmsh (OpenCASCADE kernel) meshes it with second-order tetrahedra (CalculiX C3D10), the
pad's rim embedded in the top face; CalculiX solves it linearly. Every inclusion is solved
twice on the same mesh, at its modulus ratio q and at 1 (its twin); the contrast is
C = F(q) / F(1), which in linear elasticity does not depend on the press depth.

    /usr/bin/python3 tools/fem/lateral.py --radius 0.005 --depth 0.010 --ratio 5 \\
        --offsets 0,0.005,0.010 [--thickness 0.040] [--out FILE.csv]

writes `inclusion_radius_m,inclusion_depth_m,modulus_ratio,offset_m,force_n,twin_force_n,
contrast` rows; `--sweep` writes the committed data/reference/lateral_slab40_E5k_linear.csv.
Units are SI (m, Pa, N).
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
SWEEP_OUT = os.path.join(ROOT, "data", "reference", "lateral_slab40_E5k_linear.csv")

HALF_WIDTH = 0.060   # m: the 120 mm slab, as the axisymmetric model's 60 mm disc
PAD = 0.0075         # m: the fingertip pad's radius
MODULUS = 5000.0     # Pa (linear: the contrast does not depend on it)
POISSON = 0.49
PRESS = 0.0005       # m: the press depth solved at
TOL = 1e-7           # m: geometric tolerance when picking nodes

# The committed sweep: two inclusions of the on-axis sweep, moved sideways from under the
# pad's centre to well beyond its rim.
SWEEP = ((0.005, 0.010, 5.0), (0.010, 0.020, 5.0))
SWEEP_OFFSETS = (0.0, 0.0025, 0.005, 0.0075, 0.010, 0.0125, 0.015, 0.020, 0.025)


def geo_text(h, r, s, offset, fine, coarse):
    """gmsh script: the half slab with the inclusion and the pad's disc fragmented in."""
    cx, cz = offset, -s
    return f"""SetFactory("OpenCASCADE");
Box(1) = {{{-HALF_WIDTH}, 0, {-h}, {2 * HALF_WIDTH}, {HALF_WIDTH}, {h}}};
Sphere(2) = {{{cx}, 0, {cz}, {r}}};
Disk(100) = {{0, 0, 0, {PAD}, {PAD}}};
Box(3) = {{{-2 * HALF_WIDTH}, 0, {-2 * h}, {4 * HALF_WIDTH}, {2 * HALF_WIDTH}, {4 * h}}};
BooleanIntersection{{ Volume{{2}}; Delete; }}{{ Volume{{3}}; }}
BooleanIntersection{{ Surface{{100}}; Delete; }}{{ Volume{{3}}; Delete; }}
v() = BooleanFragments{{ Volume{{1}}; Delete; }}{{ Volume{{2}}; Surface{{100}}; Delete; }};
Physical Volume(1) = {{Volume{{:}}}};
Field[1] = Ball;
Field[1].Radius = {PAD + 3 * fine};
Field[1].Thickness = {4 * PAD};
Field[1].VIn = {fine};
Field[1].VOut = {coarse};
Field[1].XCenter = 0; Field[1].YCenter = 0; Field[1].ZCenter = 0;
Field[2] = Ball;
Field[2].Radius = {r * 1.05};
Field[2].Thickness = {2 * r};
Field[2].VIn = {max(fine, r / 4)};
Field[2].VOut = {coarse};
Field[2].XCenter = {cx}; Field[2].YCenter = 0; Field[2].ZCenter = {cz};
Field[3] = Min;
Field[3].FieldsList = {{1, 2}};
Background Field = 3;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.ElementOrder = 2;
Mesh.SecondOrderLinear = 1;
"""


def read_tets(path):
    """Nodes {id: (x, y, z)} and 10-node tetrahedra [(id, [nodes])] of a v2.2 .msh file."""
    nodes, tets = {}, []
    with open(path) as f:
        lines = iter(f.read().splitlines())
    for line in lines:
        if line == "$Nodes":
            for _ in range(int(next(lines))):
                p = next(lines).split()
                nodes[int(p[0])] = (float(p[1]), float(p[2]), float(p[3]))
        elif line == "$Elements":
            for _ in range(int(next(lines))):
                p = [int(v) for v in next(lines).split()]
                if p[1] == 11:  # 10-node tetrahedron
                    tets.append((p[0], p[3 + p[2]:]))
    if not tets:
        raise RuntimeError("gmsh produced no second-order tetrahedra")
    return nodes, tets


def ccx_order(conn):
    """gmsh's tet10 node order to CalculiX's C3D10 (the last two mid-edge nodes swap)."""
    return conn[:8] + [conn[9], conn[8]]


def inside_sphere(nodes, conn, centre, r):
    """True if the tetrahedron's centroid lies in the inclusion."""
    c = [sum(nodes[n][k] for n in conn[:4]) / 4.0 for k in range(3)]
    return sum((c[k] - centre[k]) ** 2 for k in range(3)) < r * r


def deck(nodes, tets, h, r, s, offset, ratio):
    """The CalculiX input for one solve at PRESS."""
    centre = (offset, 0.0, -s)
    incl = [(e, c) for e, c in tets if inside_sphere(nodes, c, centre, r)]
    layer = [(e, c) for e, c in tets if not inside_sphere(nodes, c, centre, r)]
    if not incl:
        raise RuntimeError("no element of the mesh lies in the inclusion")
    used = sorted({n for _, c in tets for n in c})
    base = [n for n in used if abs(nodes[n][2] + h) < TOL]
    sym = [n for n in used if abs(nodes[n][1]) < TOL]
    pad = [n for n in used if abs(nodes[n][2]) < TOL and nodes[n][0] ** 2 + nodes[n][1] ** 2 <= (PAD + TOL) ** 2]
    L = ["*NODE, NSET=NALL"] + [f"{n}, {nodes[n][0]:.10e}, {nodes[n][1]:.10e}, {nodes[n][2]:.10e}" for n in used]
    for name, rows in (("LAYER", layer), ("INCL", incl)):
        L.append(f"*ELEMENT, TYPE=C3D10, ELSET={name}")
        L += [f"{e}, " + ", ".join(map(str, ccx_order(c))) for e, c in rows]
    for name, ids in (("BASE", base), ("SYM", sym), ("PAD", pad)):
        L.append(f"*NSET, NSET={name}")
        L += [", ".join(map(str, ids[i:i + 12])) for i in range(0, len(ids), 12)]
    for name, e in (("TISSUE", MODULUS), ("STIFF", ratio * MODULUS)):
        L += [f"*MATERIAL, NAME={name}", "*ELASTIC", f"{e:.10e}, {POISSON}"]
    L += ["*SOLID SECTION, ELSET=LAYER, MATERIAL=TISSUE", "*SOLID SECTION, ELSET=INCL, MATERIAL=STIFF",
          "*BOUNDARY", "BASE, 1, 3, 0.", "SYM, 2, 2, 0.",
          "*STEP", "*STATIC", "*BOUNDARY", f"PAD, 3, 3, {-PRESS:.10e}",
          "*NODE PRINT, NSET=PAD, TOTALS=ONLY", "RF", "*END STEP"]
    return "\n".join(L) + "\n", len(pad)


def solve_force(workdir, text):
    """The pad's force (N, on the whole slab: twice the half model's)."""
    with open(os.path.join(workdir, "model.inp"), "w") as f:
        f.write(text)
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1")
    res = subprocess.run(["ccx", "-i", "model"], cwd=workdir, env=env, stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, text=True)
    errors = [line.strip() for line in res.stdout.splitlines() if "*ERROR" in line]
    if res.returncode != 0 or errors:
        raise RuntimeError(f"CalculiX failed: {errors[0] if errors else res.returncode}")
    with open(os.path.join(workdir, "model.dat")) as f:
        text = f.read()
    m = re.search(r"total force \(fx,fy,fz\) for set PAD and time\s+\S+\s+(\S+)\s+(\S+)\s+(\S+)", text)
    if not m:
        raise RuntimeError("CalculiX printed no pad force")
    return -2.0 * float(m.group(3))


def contrast(h, r, s, q, offset, fine, coarse, workdir):
    """(force at q, twin force at 1, nodes, elements) of one inclusion."""
    if not (s - r > 0.05 * h and s + r < 0.95 * h and offset + r < HALF_WIDTH - 0.01):
        raise RuntimeError("the inclusion must leave 5 % of the thickness to the skin and the base")
    geo, msh = os.path.join(workdir, "model.geo"), os.path.join(workdir, "model.msh")
    with open(geo, "w") as f:
        f.write(geo_text(h, r, s, offset, fine, coarse))
    res = subprocess.run(["gmsh", "-3", "-format", "msh22", "-o", msh, geo], stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, text=True)
    if res.returncode != 0 or not os.path.exists(msh):
        raise RuntimeError(f"gmsh failed: {res.stdout.strip().splitlines()[-1:]}")
    nodes, tets = read_tets(msh)
    stiff, npad = deck(nodes, tets, h, r, s, offset, q)
    twin, _ = deck(nodes, tets, h, r, s, offset, 1.0)
    if npad < 20:
        raise RuntimeError("too few nodes under the pad: refine --fine")
    return solve_force(workdir, stiff), solve_force(workdir, twin), len(nodes), len(tets)


def run(h, cases, fine, coarse, out, verbose=True):
    rows = []
    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="palpa_lateral_") as tmp:
        for r, s, q, offset in cases:
            t0 = time.monotonic()
            f, twin, nn, ne = contrast(h, r, s, q, offset, fine, coarse, tmp)
            rows.append(f"{r:.4f},{s:.4f},{q:g},{offset:.4f},{f:.6e},{twin:.6e},{f / twin:.5f}")
            if verbose:
                print(f"r {r * 1e3:g} mm, centre {s * 1e3:g} mm deep, ratio {q:g}, {offset * 1e3:5.2f} mm beside the "
                      f"axis: contrast {f / twin:.4f} ({nn} nodes, {ne} tetrahedra, {time.monotonic() - t0:.0f} s)",
                      flush=True)
    with open(out, "w") as f:
        f.write("inclusion_radius_m,inclusion_depth_m,modulus_ratio,offset_m,force_n,twin_force_n,contrast\n")
        f.write("\n".join(rows) + "\n")
    if verbose:
        print(f"wrote {out}: {len(rows)} inclusions in {time.monotonic() - start:.0f} s")


def numbers(text):
    try:
        return [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected comma-separated numbers, got {text}")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--thickness", type=float, default=0.040, help="layer thickness h (m, default 0.040)")
    p.add_argument("--radius", type=float, help="inclusion radius r (m)")
    p.add_argument("--depth", type=float, help="depth of its centre below the skin s (m)")
    p.add_argument("--ratio", type=float, default=5.0, help="its modulus over the layer's (default 5)")
    p.add_argument("--offsets", type=numbers, default=[0.0], help="offsets beside the axis (m, comma-separated)")
    p.add_argument("--sweep", action="store_true", help="the committed sweep (40 mm, two inclusions, 0-25 mm)")
    p.add_argument("--fine", type=float, default=0.0008, help="element size under the pad (m, default 0.0008)")
    p.add_argument("--coarse", type=float, default=0.008, help="element size far away (m, default 0.008)")
    p.add_argument("--out", help="CSV to write")
    o = p.parse_args(argv)
    if o.sweep:
        cases = [(r, s, q, d) for r, s, q in SWEEP for d in SWEEP_OFFSETS]
        o.thickness, out = 0.040, o.out or SWEEP_OUT
    else:
        if o.radius is None or o.depth is None or not o.out:
            p.error("give --radius, --depth and --out (or --sweep)")
        if not (o.radius > 0 and o.depth > 0 and o.ratio > 0 and o.thickness > 0 and o.fine > 0 and o.coarse > 0):
            p.error("sizes, depth and ratio must be positive")
        cases = [(o.radius, o.depth, o.ratio, d) for d in o.offsets]
        out = o.out
    try:
        run(o.thickness, cases, o.fine, o.coarse, out)
    except RuntimeError as e:
        print(f"lateral.py: error: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
