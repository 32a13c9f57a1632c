#!/usr/bin/python3
"""Finite-element reference for indentation of a bonded elastic layer (Palpa).

Model
-----
An elastic layer of thickness h and radius R (default 60 mm, standing in for
a 120 x 120 mm slab) lies on a rigid base. The bottom face is bonded (both
displacement components fixed), the outer rim is traction free and the axis
carries the symmetry condition u_r = 0. The problem is solved as
axisymmetric (CalculiX CAX8 quadrilaterals, or CAX6 triangles) with a mesh
made by gmsh; both programs are called on the command line.

Indenters (both rigid and frictionless):
  flat    a flat-ended cylinder of radius a (default 7.5 mm). Displacement
          controlled: the top-surface nodes with r <= a (in the undeformed
          state) get u_z = -depth, u_r stays free (frictionless). The set of
          nodes in contact is therefore fixed; with --nlgeom, nodes at the
          punch edge can slide a little past r = a (reported on stderr).
  sphere  a sphere of radius Rs (default 8 mm), made of a material 1000x
          stiffer than the layer, pressed on with frictionless penalty
          contact (surface to surface). Its top edge is displaced.

Optional: one stiffer spherical inclusion centred on the axis
(--inclusion-radius, --inclusion-depth of its centre below the skin,
--inclusion-ratio of the moduli, same Poisson's ratio). A ratio of 1 gives
the "twin" model: the same mesh without any stiffness contrast.

Materials: linear elastic (E, nu) or compressible neo-Hookean through
CalculiX *HYPERELASTIC, NEO HOOKE with U = C10 (I1bar - 3) + (J - 1)^2 / D1,
so that the initial shear modulus is 2 C10 and the bulk modulus 2 / D1:
C10 = E / (4 (1 + nu)) and D1 = 6 (1 - 2 nu) / E.

Units: SI throughout (m, Pa, N); the model itself is written in metres.
CalculiX reports forces of axisymmetric elements for a 2 degree segment;
they are multiplied by 180 to give the force of the whole indenter.

Output: CSV with columns depth_m,force_n (force on the indenter, positive
in compression), one row per load step, starting at 0,0.
"""

import argparse
import csv
import math
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

AXI_FORCE_FACTOR = 180.0  # CAX results are for 2 degrees of the 360
SPHERE_STIFFNESS_RATIO = 1000.0
TOL = 1e-9  # geometric tolerance in metres


class SolveError(RuntimeError):
    """The solver or mesher failed; the message says where."""


# --------------------------------------------------------------------------
# options

def positive(text):
    value = float(text)
    if not value > 0.0 or not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be a positive number, got {text}")
    return value


def poisson(text):
    value = float(text)
    if not 0.0 <= value < 0.5:
        raise argparse.ArgumentTypeError(f"must be in [0, 0.5), got {text}")
    return value


def count(text):
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be an integer >= 1, got {text}")
    return value


def build_parser():
    p = argparse.ArgumentParser(
        description="Axisymmetric CalculiX model of a rigid frictionless indenter "
                    "on an elastic layer bonded to a rigid base (SI units).")
    p.add_argument("--thickness", type=positive, required=True, help="layer thickness h (m)")
    p.add_argument("--modulus", type=positive, required=True, help="Young's modulus E (Pa)")
    p.add_argument("--poisson", type=poisson, default=0.49, help="Poisson's ratio (default 0.49)")
    p.add_argument("--radius", type=positive, default=0.060, help="layer radius R (m, default 0.060)")
    p.add_argument("--indenter", choices=("flat", "sphere"), default="flat")
    p.add_argument("--punch-radius", type=positive, default=0.0075,
                   help="flat punch radius a (m, default 0.0075)")
    p.add_argument("--sphere-radius", type=positive, default=0.008,
                   help="sphere radius (m, default 0.008)")
    p.add_argument("--material", choices=("linear", "neohookean"), default="linear")
    p.add_argument("--nlgeom", action="store_true", help="geometrically nonlinear analysis")
    p.add_argument("--max-depth", type=positive, default=0.001, help="final depth (m, default 0.001)")
    p.add_argument("--steps", type=count, default=10, help="number of output depths (default 10)")
    p.add_argument("--mesh-size", type=positive, default=None,
                   help="element size at the indenter (m); default a/24 (flat) "
                        "or contact radius/12 (sphere)")
    p.add_argument("--element", choices=("quad", "tri"), default="quad",
                   help="CAX8 quadrilaterals (default) or CAX6 triangles")
    p.add_argument("--inclusion-radius", type=positive, default=None, help="inclusion radius (m)")
    p.add_argument("--inclusion-depth", type=positive, default=None,
                   help="depth of the inclusion centre below the skin (m)")
    p.add_argument("--inclusion-ratio", type=positive, default=None,
                   help="inclusion modulus / layer modulus (1 = same mesh, no contrast)")
    p.add_argument("--contact-stiffness", type=positive, default=None,
                   help="sphere penalty stiffness (Pa/m); default 20 E / mesh size")
    p.add_argument("--out", required=True, help="CSV file to write (depth_m,force_n)")
    p.add_argument("--keep", metavar="DIR", default=None,
                   help="keep the mesh and CalculiX files in DIR")
    p.add_argument("--allow-partial", action="store_true",
                   help="if CalculiX stops early, write the converged part and exit 0")
    p.add_argument("--quiet", action="store_true", help="print nothing on success")
    return p


def check_options(p, o):
    """Reject inconsistent options with a one-line argparse error."""
    if o.max_depth >= o.thickness:
        p.error("--max-depth must be smaller than --thickness")
    if o.indenter == "flat" and o.punch_radius >= o.radius:
        p.error("--punch-radius must be smaller than --radius")
    if o.indenter == "sphere" and o.max_depth >= 0.5 * o.sphere_radius:
        p.error("--max-depth must be below half the sphere radius")
    if o.material == "neohookean" and not o.nlgeom:
        p.error("--material neohookean needs --nlgeom")
    given = [o.inclusion_radius, o.inclusion_depth, o.inclusion_ratio]
    if any(v is not None for v in given) and not all(v is not None for v in given):
        p.error("give all three of --inclusion-radius, --inclusion-depth, --inclusion-ratio")
    if o.inclusion_radius is not None:
        top = o.inclusion_depth - o.inclusion_radius
        if top <= 0.05 * o.thickness:
            p.error("the inclusion must lie below the skin (depth - radius > 5% of thickness)")
        if o.inclusion_depth + o.inclusion_radius >= 0.95 * o.thickness:
            p.error("the inclusion must stay clear of the base")
        if o.inclusion_radius >= 0.5 * o.radius:
            p.error("--inclusion-radius is too large for the layer radius")


# --------------------------------------------------------------------------
# geometry and mesh (gmsh .geo, built-in kernel; x = r, y = z, skin at y = 0)

def default_mesh_size(o):
    if o.indenter == "flat":
        return o.punch_radius / 24.0
    return contact_zone(o) / 12.0


def contact_zone(o):
    """Radius of the skin region that may touch the sphere (m)."""
    c = math.sqrt(2.0 * o.sphere_radius * o.max_depth)
    return min(1.5 * c, 0.9 * o.sphere_radius)


class Geo:
    """Tiny writer for gmsh's built-in geometry language."""

    def __init__(self):
        self.lines = []
        self.n = 0

    def _next(self):
        self.n += 1
        return self.n

    def point(self, x, y, lc):
        i = self._next()
        self.lines.append(f"Point({i}) = {{{x!r}, {y!r}, 0, {lc!r}}};")
        return i

    def line(self, a, b):
        i = self._next()
        self.lines.append(f"Line({i}) = {{{a}, {b}}};")
        return i

    def arc(self, a, centre, b):
        i = self._next()
        self.lines.append(f"Circle({i}) = {{{a}, {centre}, {b}}};")
        return i

    def surface(self, curves):
        loop = self._next()
        self.lines.append(f"Curve Loop({loop}) = {{{', '.join(map(str, curves))}}};")
        s = self._next()
        self.lines.append(f"Plane Surface({s}) = {{{loop}}};")
        return s

    def add(self, text):
        self.lines.append(text)


def layer_geometry(g, o, lc_far):
    """Layer outline, split at the punch edge / contact zone and the inclusion.

    Returns (matrix surface, inclusion surface or None, refinement curves,
    refinement points, inclusion boundary curves)."""
    h, R = o.thickness, o.radius
    edge_r = o.punch_radius if o.indenter == "flat" else contact_zone(o)
    p_base_axis = g.point(0.0, -h, lc_far)
    p_base_rim = g.point(R, -h, lc_far)
    p_top_rim = g.point(R, 0.0, lc_far)
    p_edge = g.point(edge_r, 0.0, lc_far)
    p_top_axis = g.point(0.0, 0.0, lc_far)
    outer = [g.line(p_base_axis, p_base_rim), g.line(p_base_rim, p_top_rim),
             g.line(p_top_rim, p_edge)]
    zone = g.line(p_edge, p_top_axis)
    outer.append(zone)
    inclusion, arcs = None, []
    if o.inclusion_radius is None:
        outer.append(g.line(p_top_axis, p_base_axis))
    else:
        ri, di = o.inclusion_radius, o.inclusion_depth
        q_top = g.point(0.0, -di + ri, lc_far)
        q_mid = g.point(0.0, -di, lc_far)
        q_rim = g.point(ri, -di, lc_far)
        q_bot = g.point(0.0, -di - ri, lc_far)
        a1, a2 = g.arc(q_top, q_mid, q_rim), g.arc(q_rim, q_mid, q_bot)
        arcs = [a1, a2]
        outer += [g.line(p_top_axis, q_top), a1, a2, g.line(q_bot, p_base_axis)]
        inclusion = g.surface([-a2, -a1, g.line(q_top, q_mid), g.line(q_mid, q_bot)])
    matrix = g.surface(outer)
    points = [p_edge] if o.indenter == "flat" else []
    return matrix, inclusion, [zone], points, arcs


def sphere_geometry(g, o, lc_far):
    """Quarter disc of the sphere touching the skin at the origin."""
    Rs = o.sphere_radius
    c_bot = g.point(0.0, 0.0, lc_far)
    c_mid = g.point(0.0, Rs, lc_far)
    c_rim = g.point(Rs, Rs, lc_far)
    arc = g.arc(c_rim, c_mid, c_bot)
    surf = g.surface([arc, g.line(c_bot, c_mid), g.line(c_mid, c_rim)])
    return surf, arc


GROWTH = 0.25  # element size increase per unit distance away from the indenter


def threshold(field, source, size_min, size_max, dist_min):
    """gmsh Threshold field: size_min near the source, graded to size_max."""
    dist_max = dist_min + (size_max - size_min) / GROWTH
    return (f"Field[{field}] = Threshold; Field[{field}].InField = {source};"
            f" Field[{field}].SizeMin = {size_min!r}; Field[{field}].SizeMax = {size_max!r};"
            f" Field[{field}].DistMin = {dist_min!r}; Field[{field}].DistMax = {dist_max!r};")


def geo_text(o, lc):
    """The whole .geo script: geometry, size fields, mesh options."""
    g = Geo()
    lc_far = max(min(o.thickness, o.radius) / 4.0, lc)
    matrix, inclusion, zone_curves, edge_points, inclusion_curves = layer_geometry(g, o, lc_far)
    phys = [(1, [matrix])]
    if inclusion is not None:
        phys.append((2, [inclusion]))
    if o.indenter == "sphere":
        sphere, arc = sphere_geometry(g, o, lc_far)
        phys.append((3, [sphere]))
        zone_curves = zone_curves + [arc]
    fields = [2]
    g.add(f"Field[1] = Distance; Field[1].CurvesList = {{{', '.join(map(str, zone_curves))}}};"
          " Field[1].NumPointsPerCurve = 400;")
    g.add(threshold(2, 1, lc, lc_far, 2.0 * lc))
    if edge_points:
        g.add(f"Field[3] = Distance; Field[3].PointsList = {{{', '.join(map(str, edge_points))}}};")
        g.add(threshold(4, 3, lc / 3.0, lc_far, 0.5 * lc))
        fields.append(4)
    if inclusion is not None:
        size_inc = min(lc_far, max(lc, o.inclusion_radius / 8.0))
        g.add(f"Field[5] = Distance; Field[5].CurvesList = {{{', '.join(map(str, inclusion_curves))}}};"
              " Field[5].NumPointsPerCurve = 200;")
        g.add(threshold(6, 5, size_inc, lc_far, 0.0))
        fields.append(6)
    g.add(f"Field[9] = Min; Field[9].FieldsList = {{{', '.join(map(str, fields))}}};")
    g.add("Background Field = 9;")
    for tag, surfs in phys:
        g.add(f"Physical Surface({tag}) = {{{', '.join(map(str, surfs))}}};")
        if o.element == "quad":
            g.add(f"Recombine Surface {{{', '.join(map(str, surfs))}}};")
    g.add("Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0;"
          " Mesh.MeshSizeFromCurvature = 0;")
    # Algorithm 8 crashes in gmsh 4.8; 6 (Frontal-Delaunay) + Blossom works.
    g.add("Mesh.Algorithm = 6; Mesh.RecombinationAlgorithm = 1;")
    g.add("Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;")
    return "\n".join(g.lines) + "\n"


def run_gmsh(geo_path, msh_path):
    cmd = ["gmsh", "-2", "-format", "msh22", "-o", msh_path, geo_path]
    res = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if res.returncode != 0 or not os.path.exists(msh_path):
        tail = res.stdout.strip().splitlines()[-1:] or ["no output"]
        raise SolveError(f"gmsh failed (exit {res.returncode}): {tail[0]}")


GMSH_TYPES = {9: "tri6", 16: "quad8"}


def read_msh22(path):
    """Nodes {id: (x, y)} and elements [(id, kind, phys, [nodes])] of a v2.2 file."""
    nodes, elements = {}, []
    with open(path) as f:
        lines = iter(f.read().splitlines())
    for line in lines:
        if line == "$Nodes":
            for _ in range(int(next(lines))):
                parts = next(lines).split()
                nodes[int(parts[0])] = (float(parts[1]), float(parts[2]))
        elif line == "$Elements":
            for _ in range(int(next(lines))):
                parts = [int(v) for v in next(lines).split()]
                etype, ntags = parts[1], parts[2]
                if etype in GMSH_TYPES:
                    phys = parts[3]
                    elements.append((parts[0], GMSH_TYPES[etype], phys, parts[3 + ntags:]))
                elif etype not in (1, 8, 15, 2, 3):
                    raise SolveError(f"unexpected gmsh element type {etype}")
    if not elements:
        raise SolveError("gmsh produced no second-order surface elements")
    return nodes, elements


def counter_clockwise(kind, conn, nodes):
    """Return the connectivity ordered counter-clockwise in the (r, z) plane."""
    ncorner = 3 if kind == "tri6" else 4
    xy = np.array([nodes[n] for n in conn[:ncorner]])
    x, y = xy[:, 0], xy[:, 1]
    area = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
    if area > 0:
        return list(conn)
    if kind == "tri6":
        c = conn
        return [c[0], c[2], c[1], c[5], c[4], c[3]]
    c = conn
    return [c[0], c[3], c[2], c[1], c[7], c[6], c[5], c[4]]


def element_edges(kind, conn):
    """(face label, corner a, corner b, mid node) of each element edge."""
    if kind == "tri6":
        pairs = [(0, 1, 3), (1, 2, 4), (2, 0, 5)]
    else:
        pairs = [(0, 1, 4), (1, 2, 5), (2, 3, 6), (3, 0, 7)]
    return [(f"S{i + 1}", conn[a], conn[b], conn[m]) for i, (a, b, m) in enumerate(pairs)]


# --------------------------------------------------------------------------
# CalculiX input

class Mesh:
    """Nodes and elements split into layer, inclusion and sphere parts."""

    def __init__(self, nodes, elements):
        self.nodes = nodes
        self.elements = [(eid, kind, phys, counter_clockwise(kind, conn, nodes))
                         for eid, kind, phys, conn in elements]

    def nodes_of(self, phys_tags):
        out = set()
        for _, _, phys, conn in self.elements:
            if phys in phys_tags:
                out.update(conn)
        return out

    def select(self, ids, pred):
        return sorted(n for n in ids if pred(*self.nodes[n]))

    def faces(self, phys_tags, pred):
        """Element faces of the given parts whose three nodes satisfy pred(x, y)."""
        out = []
        for eid, kind, phys, conn in self.elements:
            if phys not in phys_tags:
                continue
            for label, a, b, m in element_edges(kind, conn):
                if all(pred(*self.nodes[n]) for n in (a, b, m)):
                    out.append((eid, label))
        return out


def id_lines(ids, per_line=12):
    ids = list(ids)
    return [", ".join(map(str, ids[i:i + per_line])) for i in range(0, len(ids), per_line)]


def material_block(name, o, modulus):
    lines = [f"*MATERIAL, NAME={name}"]
    nu = o.poisson
    if o.material == "linear" or name == "INDENTER":
        lines += ["*ELASTIC", f"{modulus:.10e}, {nu:.10e}"]
    else:
        c10 = modulus / (4.0 * (1.0 + nu))
        d1 = 6.0 * (1.0 - 2.0 * nu) / modulus
        lines += ["*HYPERELASTIC, NEO HOOKE", f"{c10:.10e}, {d1:.10e}"]
    return lines


def inp_text(o, mesh):
    """CalculiX input deck and the name of the node set that carries the load."""
    h, R = o.thickness, o.radius
    L = ["*HEADING", "Palpa indentation reference (tools/fem/indent.py), SI units"]
    L.append("*NODE, NSET=NALL")
    used = mesh.nodes_of({1, 2, 3})
    for n in sorted(used):
        x, y = mesh.nodes[n]
        L.append(f"{n}, {x:.12e}, {y:.12e}")
    sets = {1: "LAYER", 2: "INCL", 3: "INDENTER"}
    for kind, ctype in (("quad8", "CAX8"), ("tri6", "CAX6")):
        for phys, name in sets.items():
            rows = [(eid, conn) for eid, k, p, conn in mesh.elements if k == kind and p == phys]
            if rows:
                L.append(f"*ELEMENT, TYPE={ctype}, ELSET={name}")
                L += [f"{eid}, " + ", ".join(map(str, conn)) for eid, conn in rows]
    body = mesh.nodes_of({1, 2})
    nsets = {
        "BASE": mesh.select(body, lambda x, y: abs(y + h) < TOL),
        "AXIS": mesh.select(body, lambda x, y: abs(x) < TOL and y > -h + TOL),
    }
    if o.indenter == "flat":
        load_set = "PUNCH"
        nsets["PUNCH"] = mesh.select(body, lambda x, y: abs(y) < TOL and x <= o.punch_radius + TOL)
        edge = mesh.select(body, lambda x, y: abs(y) < TOL and abs(x - o.punch_radius) < TOL)
        nsets["EDGE"] = edge
    else:
        load_set = "DRIVE"
        tool = mesh.nodes_of({3})
        Rs = o.sphere_radius
        nsets["DRIVE"] = mesh.select(tool, lambda x, y: abs(y - Rs) < TOL)
        nsets["TOOLAXIS"] = mesh.select(tool, lambda x, y: abs(x) < TOL and y < Rs - TOL)
    for name, ids in nsets.items():
        if not ids:
            raise SolveError(f"empty node set {name}: mesh and geometry disagree")
        L.append(f"*NSET, NSET={name}")
        L += id_lines(ids)
    L += material_block("TISSUE", o, o.modulus)
    L += ["*SOLID SECTION, ELSET=LAYER, MATERIAL=TISSUE"]
    if o.inclusion_radius is not None:
        L += material_block("LUMP", o, o.modulus * o.inclusion_ratio)
        L += ["*SOLID SECTION, ELSET=INCL, MATERIAL=LUMP"]
    if o.indenter == "sphere":
        L += material_block("INDENTER", o, o.modulus * SPHERE_STIFFNESS_RATIO)
        L += ["*SOLID SECTION, ELSET=INDENTER, MATERIAL=INDENTER"]
        L += contact_block(o, mesh)
    L += ["*BOUNDARY", "BASE, 1, 2, 0.", "AXIS, 1, 1, 0."]
    if o.indenter == "sphere":
        L += ["TOOLAXIS, 1, 1, 0.", "DRIVE, 1, 1, 0."]
    dt = 1.0 / o.steps
    L += ["*TIME POINTS, NAME=TP, GENERATE", f"0., 1., {dt:.10e}"]
    nonlinear = o.nlgeom or o.indenter == "sphere"
    L.append("*STEP, NLGEOM, INC=10000" if o.nlgeom else "*STEP, INC=10000")
    if nonlinear:
        L += ["*STATIC", f"{dt:.10e}, 1., {dt * 1e-4:.10e}, {dt:.10e}"]
    else:
        L += ["*STATIC"]
    L += ["*BOUNDARY", f"{load_set}, 2, 2, {-o.max_depth:.10e}"]
    tp = ", TIME POINTS=TP" if nonlinear else ""
    L += [f"*NODE PRINT, NSET={load_set}, TOTALS=ONLY{tp}", "RF"]
    if o.indenter == "flat":
        L += [f"*NODE PRINT, NSET=EDGE{tp}", "U"]
    if o.keep:
        L += [f"*NODE FILE{tp}", "U"]
    L.append("*END STEP")
    return "\n".join(L) + "\n", load_set


def contact_block(o, mesh):
    """Frictionless penalty contact between the skin and the sphere."""
    zone = min(1.5 * contact_zone(o), o.radius)
    skin = mesh.faces({1}, lambda x, y: abs(y) < TOL and x <= zone + TOL)
    c = (0.0, o.sphere_radius)
    on_sphere = lambda x, y: abs(math.hypot(x - c[0], y - c[1]) - o.sphere_radius) < 1e-6 * o.sphere_radius + TOL
    tool = mesh.faces({3}, on_sphere)
    if not skin or not tool:
        raise SolveError("could not find the contact faces of the skin or the sphere")
    lc = o.mesh_size
    k = o.contact_stiffness or 20.0 * o.modulus / lc
    L = ["*SURFACE, NAME=SKIN"] + [f"{e}, {s}" for e, s in skin]
    L += ["*SURFACE, NAME=BALL"] + [f"{e}, {s}" for e, s in tool]
    L += ["*CONTACT PAIR, INTERACTION=SLIP, TYPE=SURFACE TO SURFACE", "SKIN, BALL",
          "*SURFACE INTERACTION, NAME=SLIP",
          "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{k:.10e}"]
    return L


# --------------------------------------------------------------------------
# running CalculiX and reading its results

def solver_env():
    env = dict(os.environ)
    for key in ("OMP_NUM_THREADS", "CCX_NPROC_EQUATION_SOLVER", "CCX_NPROC_RESULTS",
                "CCX_NPROC_STIFFNESS", "NUMBER_OF_CPUS"):
        env[key] = "1"
    return env


def run_ccx(workdir, job):
    res = subprocess.run(["ccx", "-i", job], cwd=workdir, env=solver_env(),
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    with open(os.path.join(workdir, job + ".log"), "w") as f:
        f.write(res.stdout)
    errors = [l.strip() for l in res.stdout.splitlines() if "*ERROR" in l]
    return res.returncode, errors


NUM = r"[-+]?\d*\.?\d+(?:[eE][-+]?\d+)?"


def read_totals(dat_path, set_name):
    """[(time, fy)] from '*NODE PRINT ... TOTALS=ONLY' blocks of a .dat file."""
    out = []
    head = re.compile(rf"total force \(fx,fy,fz\) for set {set_name} and time\s+({NUM})")
    with open(dat_path) as f:
        lines = f.read().splitlines()
    for i, line in enumerate(lines):
        m = head.search(line)
        if m:
            vals = next(l for l in lines[i + 1:] if l.strip()).split()
            out.append((float(m.group(1)), float(vals[1])))
    return out


def read_edge_drift(dat_path, node_set="EDGE"):
    """Largest radial displacement printed for the punch-edge node (m)."""
    head = re.compile(rf"displacements \(vx,vy,vz\) for set {node_set} and time")
    best = 0.0
    with open(dat_path) as f:
        lines = f.read().splitlines()
    for i, line in enumerate(lines):
        if head.search(line):
            vals = next(l for l in lines[i + 1:] if l.strip()).split()
            best = max(best, abs(float(vals[1])))
    return best


def curve_from_totals(o, totals, nonlinear):
    """Depth/force rows for the output depths; a linear solve is scaled."""
    rows = [(0.0, 0.0)]
    if not nonlinear:
        t, fy = totals[-1]
        for i in range(1, o.steps + 1):
            s = i / o.steps
            rows.append((s * o.max_depth, -fy * AXI_FORCE_FACTOR * s))
        return rows
    for t, fy in totals:
        if t > 0.0:
            rows.append((t * o.max_depth, -fy * AXI_FORCE_FACTOR))
    return rows


def write_csv(path, rows):
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["depth_m", "force_n"])
        for d, F in rows:
            w.writerow([f"{d:.6e}", f"{F:.6e}"])


# --------------------------------------------------------------------------
# driver

def solve(o, workdir, log=print):
    """Mesh, solve and return (rows, info dict). Raises SolveError."""
    o.mesh_size = o.mesh_size or default_mesh_size(o)
    geo = os.path.join(workdir, "model.geo")
    msh = os.path.join(workdir, "model.msh")
    with open(geo, "w") as f:
        f.write(geo_text(o, o.mesh_size))
    t0 = time.monotonic()
    cpu0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    run_gmsh(geo, msh)
    mesh = Mesh(*read_msh22(msh))
    text, load_set = inp_text(o, mesh)
    with open(os.path.join(workdir, "model.inp"), "w") as f:
        f.write(text)
    rc, errors = run_ccx(workdir, "model")
    cpu1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    info = {
        "wall_s": time.monotonic() - t0,
        "cpu_s": (cpu1.ru_utime + cpu1.ru_stime) - (cpu0.ru_utime + cpu0.ru_stime),
        "elements": len(mesh.elements),
        "nodes": len(mesh.nodes_of({1, 2, 3})),
    }
    dat = os.path.join(workdir, "model.dat")
    totals = read_totals(dat, load_set) if os.path.exists(dat) else []
    nonlinear = o.nlgeom or o.indenter == "sphere"
    rows = curve_from_totals(o, totals, nonlinear) if totals else [(0.0, 0.0)]
    if o.indenter == "flat" and os.path.exists(dat):
        info["edge_drift_m"] = read_edge_drift(dat)
    reached = rows[-1][0]
    info["reached_depth_m"] = reached
    if rc != 0 or errors or reached < o.max_depth * (1.0 - 1e-6):
        why = errors[0] if errors else f"ccx exit code {rc}"
        err = SolveError(f"CalculiX stopped at depth {reached:.4g} m of {o.max_depth:.4g} m "
                         f"({why})")
        err.rows, err.info = rows, info
        raise err
    return rows, info


def describe(o, info):
    text = (f"{o.indenter} on h={o.thickness:g} m, E={o.modulus:g} Pa, nu={o.poisson:g}, "
            f"{o.material}{' nlgeom' if o.nlgeom else ''}: {info['elements']} elements, "
            f"{info['nodes']} nodes, wall {info['wall_s']:.1f} s, cpu {info['cpu_s']:.1f} s")
    if "edge_drift_m" in info:
        text += f", punch-edge radial drift {info['edge_drift_m']:.3g} m"
    return text


def main(argv=None):
    parser = build_parser()
    o = parser.parse_args(argv)
    check_options(parser, o)
    for prog in ("gmsh", "ccx"):
        if shutil.which(prog) is None:
            print(f"indent.py: error: '{prog}' not found on PATH", file=sys.stderr)
            return 2
    if o.keep:
        os.makedirs(o.keep, exist_ok=True)
        workdir, cleanup = o.keep, None
    else:
        cleanup = tempfile.TemporaryDirectory(prefix="palpa_fem_")
        workdir = cleanup.name
    try:
        rows, info = solve(o, workdir)
    except SolveError as exc:
        rows = getattr(exc, "rows", None)
        if o.allow_partial and rows and len(rows) > 1:
            write_csv(o.out, rows)
            print(f"indent.py: warning: {exc}; wrote the converged part to {o.out}",
                  file=sys.stderr)
            print(describe(o, exc.info), file=sys.stderr)
            return 0
        print(f"indent.py: error: {exc}", file=sys.stderr)
        return 1
    finally:
        if cleanup is not None:
            cleanup.cleanup()
    write_csv(o.out, rows)
    if not o.quiet:
        print(describe(o, info), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
