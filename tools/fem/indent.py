#!/usr/bin/python3
"""Finite-element reference for indentation of a bonded elastic layer (Palpa).

Model
-----
An elastic layer of thickness h and radius R (default 60 mm, standing in for
a 120 x 120 mm slab) lies on a rigid base. The bottom face is bonded (both
displacement components fixed), the outer rim is traction free and the axis
carries the symmetry condition u_r = 0. The problem is solved as
axisymmetric with second-order elements (CalculiX CAX8 by default) on a mesh
made by gmsh; both programs are run as command-line tools in a temporary
directory.

Indenters (all rigid and frictionless):
  flat    flat-ended cylinder of radius a (default 7.5 mm), displacement
          controlled: the skin nodes with r <= a (undeformed) get
          u_z = -depth, u_r is left free. This is exactly Sneddon's / Hayes'
          boundary-value problem. The contact set is fixed and the punch's
          side wall is not modelled, so at large depth the free skin next
          to the sharp edge rolls into the punch and the solve stops
          (neo-Hookean: about 10 % of h on a 40 mm layer, 15 % on 20 mm).
          --pin-edge also holds the edge node at r = a, which goes further
          (about 18 % and 22 %) and stiffens the curve by up to ~3 %.
  pad     the same cylinder with its edge rounded (--edge-radius, default
          1 mm), pressed on with penalty contact, so the skin can wrap the
          rounded edge. Slow with NLGEOM (in a trial it reached 6 mm on a
          40 mm neo-Hookean layer in 75 s).
  sphere  a finger: a sphere of radius Rs (default 8 mm) on a cylinder of the
          same radius, penalty contact; presses up to 1.5 Rs deep.
The contact tools are elastic bodies 1000x stiffer than the layer whose top
edge is displaced; contact is surface to surface, without friction.

Optional: one stiffer spherical inclusion centred on the axis
(--inclusion-radius, --inclusion-depth of its centre below the skin,
--inclusion-ratio of the moduli, same Poisson's ratio). A ratio of 1 gives
the twin model: the same mesh with no stiffness contrast.

Optional, instead of --modulus: a layered column (--layers "T1:E1,T2:E2,...",
thicknesses in m from the skin down, moduli in Pa, all bonded to each other and
the last to the rigid base; same Poisson's ratio). Each interface is a mesh
line, meshed no coarser than a third of the thinner of its two layers, so every
element lies in one material. Linear material only; no inclusion. --thickness
may be left out (it is the sum of the layers) or must equal that sum.

Materials: linear elastic (E, nu), or compressible neo-Hookean via CalculiX
*HYPERELASTIC, NEO HOOKE: U = C10 (I1bar - 3) + (J - 1)^2 / D1, whose
initial shear modulus is 2 C10 and bulk modulus 2 / D1, hence
C10 = E / (4 (1 + nu)) and D1 = 6 (1 - 2 nu) / E (needs --nlgeom).

Units: SI throughout (m, Pa, N); the model itself is written in metres.
CalculiX reports forces of axisymmetric elements for a 2 degree segment of
the ring; they are multiplied by 180 to give the whole indenter force.

Output: CSV with columns depth_m,force_n (force on the indenter, positive
in compression), one row per load step, starting at 0,0. Exit status 1 if
gmsh or CalculiX fails (the message says at which depth the solve stopped).
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

AXI_FORCE_FACTOR = 180.0      # CAX forces are for 2 of the 360 degrees
TOOL_STIFFNESS_RATIO = 1000.0  # contact tools: E_tool = 1000 E
TOOL_POISSON = 0.3
GROWTH = 0.25                  # element size increase per unit distance
TOL = 1e-9                     # geometric tolerance (m)
ELEMENT_TYPES = {"quad": ("CAX8", "CAX6"), "quad-reduced": ("CAX8R", "CAX6"),
                 "tri": ("CAX8", "CAX6")}
PHYS_LAYER, PHYS_INCLUSION, PHYS_TOOL = 1, 2, 3
PHYS_SUBLAYER = 10             # + i: the i-th layer below the top one (--layers)


class SolveError(RuntimeError):
    """gmsh or CalculiX failed; rows/info hold what converged, if anything."""

    def __init__(self, message, rows=None, info=None):
        super().__init__(message)
        self.rows, self.info = rows, info


# --------------------------------------------------------------------------
# options

def parsed(text, kind, what):
    try:
        return kind(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not {what}: {text}")


def positive(text):
    value = parsed(text, float, "a number")
    if not (value > 0.0 and math.isfinite(value)):
        raise argparse.ArgumentTypeError(f"must be a positive number, got {text}")
    return value


def poisson(text):
    value = parsed(text, float, "a number")
    if not 0.0 <= value < 0.5:
        raise argparse.ArgumentTypeError(f"must be in [0, 0.5), got {text}")
    return value


def count(text):
    value = parsed(text, int, "an integer")
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be an integer >= 1, got {text}")
    return value


def layer_list(text):
    """--layers "T1:E1,T2:E2,...": [(thickness m, modulus Pa)] from the skin down."""
    layers = []
    for item in text.split(","):
        parts = item.split(":")
        if len(parts) != 2:
            raise argparse.ArgumentTypeError(f"want thickness:modulus, got {item!r}")
        layers.append((positive(parts[0]), positive(parts[1])))
    return layers


def build_parser():
    p = argparse.ArgumentParser(
        prog="indent.py",
        description="Axisymmetric CalculiX model of a rigid frictionless indenter on an "
                    "elastic layer bonded to a rigid base (SI units: m, Pa, N).")
    p.add_argument("--thickness", type=positive, help="layer thickness h (m); required "
                   "unless --layers gives it")
    p.add_argument("--modulus", type=positive, help="Young's modulus E (Pa); required "
                   "unless --layers")
    p.add_argument("--layers", type=layer_list, default=None, metavar="T1:E1,T2:E2,...",
                   help="a layered column instead of --modulus: thicknesses (m) and moduli "
                        "(Pa) from the skin down, bonded; linear material only")
    p.add_argument("--poisson", type=poisson, default=0.49, help="Poisson's ratio (default 0.49)")
    p.add_argument("--radius", type=positive, default=0.060, help="layer radius R (m, default 0.060)")
    p.add_argument("--indenter", choices=("flat", "pad", "sphere"), default="flat")
    p.add_argument("--punch-radius", type=positive, default=0.0075,
                   help="flat punch / pad radius a (m, default 0.0075)")
    p.add_argument("--pin-edge", action="store_true",
                   help="flat punch: also hold the punch-edge node at r = a (keeps the skin "
                        "from folding round the sharp edge at large depth)")
    p.add_argument("--edge-radius", type=positive, default=0.001,
                   help="rounding of the pad edge (m, default 0.001)")
    p.add_argument("--sphere-radius", type=positive, default=0.008,
                   help="sphere radius (m, default 0.008)")
    p.add_argument("--material", choices=("linear", "neohookean"), default="linear")
    p.add_argument("--nlgeom", action="store_true", help="geometrically nonlinear analysis")
    p.add_argument("--max-depth", type=positive, default=0.001, help="final depth (m, default 0.001)")
    p.add_argument("--steps", type=count, default=10,
                   help="number of equal depth steps written (default 10)")
    p.add_argument("--mesh-size", type=positive, default=None,
                   help="element size at the indenter (m); default a/24 (flat), "
                        "edge radius/4 (pad), contact radius/12 (sphere)")
    p.add_argument("--element", choices=tuple(ELEMENT_TYPES), default="quad",
                   help="CAX8 quadrilaterals (quad, default), CAX8R (quad-reduced) "
                        "or CAX6 triangles (tri)")
    p.add_argument("--inclusion-radius", type=positive, default=None, help="inclusion radius (m)")
    p.add_argument("--inclusion-depth", type=positive, default=None,
                   help="depth of the inclusion centre below the skin (m)")
    p.add_argument("--inclusion-ratio", type=positive, default=None,
                   help="inclusion modulus / layer modulus (1 = same mesh, no contrast)")
    p.add_argument("--contact-stiffness", type=positive, default=None,
                   help="penalty stiffness of pad/sphere contact (Pa/m; default 20 E / mesh size)")
    p.add_argument("--out", required=True, help="CSV file to write (depth_m,force_n)")
    p.add_argument("--keep", metavar="DIR", default=None,
                   help="keep the mesh and CalculiX files (with a .frd) in DIR")
    p.add_argument("--allow-partial", action="store_true",
                   help="if CalculiX stops early, write the converged part and exit 0")
    p.add_argument("--quiet", action="store_true", help="print nothing on success")
    return p


def check_layers(p, o):
    """Fill --thickness and the top layer's --modulus from --layers (that modulus sets the
    contact penalty and the tools' stiffness), or ask for the two plain options."""
    if o.layers is None:
        missing = [name for name, v in (("--thickness", o.thickness), ("--modulus", o.modulus))
                   if v is None]
        if missing:
            p.error(f"the following arguments are required: {', '.join(missing)}")
        return
    total = sum(t for t, _ in o.layers)
    if o.thickness is not None and abs(o.thickness - total) > 1e-9:
        p.error(f"--thickness {o.thickness:g} differs from the sum of --layers, {total:g}")
    if o.modulus is not None:
        p.error("give either --modulus or --layers")
    if o.material != "linear":
        p.error("--layers supports --material linear only")
    if o.inclusion_radius is not None:
        p.error("--layers does not take an inclusion")
    o.thickness, o.modulus = total, o.layers[0][1]


def check_options(p, o):
    """Reject inconsistent options with a one-line argparse error (exit 2)."""
    check_layers(p, o)
    if o.max_depth >= o.thickness:
        p.error("--max-depth must be smaller than --thickness")
    if o.indenter in ("flat", "pad") and o.punch_radius >= 0.5 * o.radius:
        p.error("--punch-radius must be below half of --radius")
    if o.indenter == "pad" and o.edge_radius >= 0.5 * o.punch_radius:
        p.error("--edge-radius must be below half of --punch-radius")
    if o.indenter == "sphere" and o.max_depth >= 1.5 * o.sphere_radius:
        p.error("--max-depth must be below 1.5 x --sphere-radius")
    if o.indenter == "sphere" and o.sphere_radius >= 0.5 * o.radius:
        p.error("--sphere-radius must be below half of --radius")
    if o.pin_edge and o.indenter != "flat":
        p.error("--pin-edge applies to --indenter flat only")
    if o.material == "neohookean" and not o.nlgeom:
        p.error("--material neohookean needs --nlgeom")
    given = [o.inclusion_radius, o.inclusion_depth, o.inclusion_ratio]
    if any(v is not None for v in given) and not all(v is not None for v in given):
        p.error("give all three of --inclusion-radius, --inclusion-depth, --inclusion-ratio")
    if o.inclusion_radius is not None:
        if o.inclusion_depth - o.inclusion_radius <= 0.05 * o.thickness:
            p.error("the inclusion must lie below the skin (depth - radius > 5% of thickness)")
        if o.inclusion_depth + o.inclusion_radius >= 0.95 * o.thickness:
            p.error("the inclusion must stay clear of the base (depth + radius < 95% of thickness)")
        if o.inclusion_radius >= 0.5 * o.radius:
            p.error("--inclusion-radius must be below half of --radius")


def uses_contact(o):
    return o.indenter in ("pad", "sphere")


def is_nonlinear(o):
    return o.nlgeom or uses_contact(o)


# --------------------------------------------------------------------------
# geometry and mesh (gmsh .geo, built-in kernel; x = r, y = z, skin at y = 0)

def sphere_contact_radius(o):
    """Hertz-like contact radius at the final depth, with a 1.5 margin (m); past the
    hemisphere the skin wraps on round the finger's side, so up to 1.3 sphere radii."""
    return min(1.5 * math.sqrt(2.0 * o.sphere_radius * o.max_depth), 1.3 * o.sphere_radius)


def skin_zone(o):
    """Radius of the skin strip that gets the fine mesh (m)."""
    if o.indenter == "flat":
        return o.punch_radius
    if o.indenter == "pad":
        return o.punch_radius + 2.0 * o.edge_radius
    return sphere_contact_radius(o)


def default_mesh_size(o):
    if o.indenter == "flat":
        return o.punch_radius / 24.0
    if o.indenter == "pad":
        return o.edge_radius / 4.0
    return sphere_contact_radius(o) / 12.0


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


def layer_geometry(g, o, lc):
    """Layer outline split at the fine skin strip and around the inclusion.

    Returns (layer surface, inclusion surface or None, skin-strip curve,
    point at the outer end of the strip, inclusion arcs, (base curve, its axis and rim
    points)). With --layers this is the top layer."""
    h, R = (o.layers[0][0] if is_layered(o) else o.thickness), o.radius  # the top layer's
    base_axis, base_rim = g.point(0.0, -h, lc), g.point(R, -h, lc)
    top_rim, top_zone, top_axis = g.point(R, 0.0, lc), g.point(skin_zone(o), 0.0, lc), g.point(0.0, 0.0, lc)
    strip = g.line(top_zone, top_axis)
    outer = [g.line(base_axis, base_rim), g.line(base_rim, top_rim), g.line(top_rim, top_zone), strip]
    base = (outer[0], base_axis, base_rim)
    if o.inclusion_radius is None:
        outer.append(g.line(top_axis, base_axis))
        return g.surface(outer), None, strip, top_zone, [], base
    ri, di = o.inclusion_radius, o.inclusion_depth
    q_top, q_mid = g.point(0.0, -di + ri, lc), g.point(0.0, -di, lc)
    q_rim, q_bot = g.point(ri, -di, lc), g.point(0.0, -di - ri, lc)
    a1, a2 = g.arc(q_top, q_mid, q_rim), g.arc(q_rim, q_mid, q_bot)
    outer += [g.line(top_axis, q_top), a1, a2, g.line(q_bot, base_axis)]
    inclusion = g.surface([-a2, -a1, g.line(q_top, q_mid), g.line(q_mid, q_bot)])
    return g.surface(outer), inclusion, strip, top_zone, [a1, a2], base


def is_layered(o):
    return o.layers is not None and len(o.layers) > 1


def lower_layers(g, o, lc, top_base):
    """The layers under the top one, each a rectangle sharing its upper edge with the
    layer above (top_base: the top layer's base curve, its axis and rim points).
    Returns [(physical tag, surface)] and [(interface curve, size along it)]."""
    R, depth = o.radius, o.layers[0][0]
    above, axis_pt, rim_pt = top_base
    surfaces, interfaces = [], []
    for i, (t, _) in enumerate(o.layers[1:], start=1):
        size = min(lc, max(o.mesh_size, min(t, o.layers[i - 1][0]) / 3.0))
        interfaces.append((above, size))
        depth += t
        b_axis, b_rim = g.point(0.0, -depth, lc), g.point(R, -depth, lc)
        base = g.line(b_axis, b_rim)
        loop = [base, g.line(b_rim, rim_pt), -above, g.line(axis_pt, b_axis)]
        surfaces.append((PHYS_SUBLAYER + i, g.surface(loop)))
        axis_pt, rim_pt, above = b_axis, b_rim, base
    return surfaces, interfaces


def body_tags(o):
    """Physical tags of the tissue (every layer and the inclusion), not the tool."""
    tags = {PHYS_LAYER, PHYS_INCLUSION}
    if o.layers is not None:
        tags |= {PHYS_SUBLAYER + i for i in range(1, len(o.layers))}
    return tags


def tool_height(o):
    """Height of the driven top edge of the contact tool above the skin (m)."""
    if o.indenter == "sphere":
        return o.sphere_radius + o.max_depth
    return o.max_depth + 2.0 * o.edge_radius


def sphere_geometry(g, o, lc):
    """A finger: the quarter disc of a sphere touching the skin at the origin, on a
    cylinder of the same radius (its side is met once a press passes the hemisphere)."""
    Rs, H = o.sphere_radius, tool_height(o)
    bottom, centre, rim = g.point(0.0, 0.0, lc), g.point(0.0, Rs, lc), g.point(Rs, Rs, lc)
    top_rim, top_axis = g.point(Rs, H, lc), g.point(0.0, H, lc)
    arc, side = g.arc(rim, centre, bottom), g.line(top_rim, rim)
    surf = g.surface([arc, g.line(bottom, top_axis), g.line(top_axis, top_rim), side])
    return surf, [arc, side]


def pad_geometry(g, o, lc):
    """Cylinder section r <= a, 0 <= z <= H with a rounded lower edge."""
    a, rf, H = o.punch_radius, o.edge_radius, tool_height(o)
    p0, p1 = g.point(0.0, 0.0, lc), g.point(a - rf, 0.0, lc)
    pc, p2 = g.point(a - rf, rf, lc), g.point(a, rf, lc)
    p3, p4 = g.point(a, H, lc), g.point(0.0, H, lc)
    face, fillet, side = g.line(p0, p1), g.arc(p1, pc, p2), g.line(p2, p3)
    surf = g.surface([face, fillet, side, g.line(p3, p4), g.line(p4, p0)])
    return surf, [face, fillet, side]


def threshold(field, source, size_min, size_max, dist_min):
    """gmsh Threshold field: size_min near the source, graded to size_max."""
    dist_max = dist_min + (size_max - size_min) / GROWTH
    return (f"Field[{field}] = Threshold; Field[{field}].InField = {source};"
            f" Field[{field}].SizeMin = {size_min!r}; Field[{field}].SizeMax = {size_max!r};"
            f" Field[{field}].DistMin = {dist_min!r}; Field[{field}].DistMax = {dist_max!r};")


def distance(field, curves=(), points=()):
    text = f"Field[{field}] = Distance;"
    if curves:
        text += f" Field[{field}].CurvesList = {{{', '.join(map(str, curves))}}};"
        text += f" Field[{field}].NumPointsPerCurve = 400;"
    if points:
        text += f" Field[{field}].PointsList = {{{', '.join(map(str, points))}}};"
    return text


def geo_text(o, lc):
    """The whole .geo script: geometry, size fields and mesh options."""
    g = Geo()
    lc_far = max(min(o.thickness, o.radius) / 4.0, lc)
    layer, inclusion, strip, strip_end, inclusion_arcs, base = layer_geometry(g, o, lc_far)
    phys = [(PHYS_LAYER, layer)]
    interfaces = []
    if is_layered(o):
        lower, interfaces = lower_layers(g, o, lc_far, base)
        phys += lower
    fine_curves = [strip]
    if inclusion is not None:
        phys.append((PHYS_INCLUSION, inclusion))
    if o.indenter == "sphere":
        tool, tool_curves = sphere_geometry(g, o, lc_far)
    elif o.indenter == "pad":
        tool, tool_curves = pad_geometry(g, o, lc_far)
    if uses_contact(o):
        phys.append((PHYS_TOOL, tool))
        fine_curves += tool_curves[:2]
    g.add(distance(1, curves=fine_curves))
    g.add(threshold(2, 1, lc, lc_far, 2.0 * lc))
    fields = [2]
    if o.indenter == "flat":   # the pressure is singular at the punch edge
        g.add(distance(3, points=[strip_end]))  # the strip ends at r = a
        g.add(threshold(4, 3, lc / 3.0, lc_far, 0.5 * lc))
        fields.append(4)
    if inclusion is not None:
        size = min(lc_far, max(lc, o.inclusion_radius / 8.0))
        g.add(distance(5, curves=inclusion_arcs))
        g.add(threshold(6, 5, size, lc_far, 0.0))
        fields.append(6)
    for n, (curve, size) in enumerate(interfaces):   # fields 10, 11; 12, 13; ...
        g.add(distance(10 + 2 * n, curves=[curve]))
        g.add(threshold(11 + 2 * n, 10 + 2 * n, size, lc_far, 0.0))
        fields.append(11 + 2 * n)
    g.add(f"Field[9] = Min; Field[9].FieldsList = {{{', '.join(map(str, fields))}}};")
    g.add("Background Field = 9;")
    for tag, surf in phys:
        g.add(f"Physical Surface({tag}) = {{{surf}}};")
        if o.element != "tri":
            g.add(f"Recombine Surface {{{surf}}};")
    g.add("Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0;"
          " Mesh.MeshSizeFromCurvature = 0;")
    # Mesh.Algorithm 8 crashes in gmsh 4.8; 6 (Frontal-Delaunay) + Blossom works.
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
GMSH_LOWER_DIM = {1, 8, 15}   # lines and points of physical curves, if any


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
                    elements.append((parts[0], GMSH_TYPES[etype], parts[3], parts[3 + ntags:]))
                elif etype not in GMSH_LOWER_DIM:
                    raise SolveError(f"gmsh wrote an unexpected element type {etype}")
    if not elements:
        raise SolveError("gmsh produced no second-order surface elements")
    return nodes, elements


def counter_clockwise(kind, conn, nodes):
    """The connectivity ordered counter-clockwise in the (r, z) plane."""
    ncorner = 3 if kind == "tri6" else 4
    xy = np.array([nodes[n] for n in conn[:ncorner]])
    x, y = xy[:, 0], xy[:, 1]
    if np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) > 0:
        return list(conn)
    c = conn
    if kind == "tri6":
        return [c[0], c[2], c[1], c[5], c[4], c[3]]
    return [c[0], c[3], c[2], c[1], c[7], c[6], c[5], c[4]]


def element_edges(kind, conn):
    """(face label, corner a, corner b, mid node) for each element edge."""
    if kind == "tri6":
        pairs = [(0, 1, 3), (1, 2, 4), (2, 0, 5)]
    else:
        pairs = [(0, 1, 4), (1, 2, 5), (2, 3, 6), (3, 0, 7)]
    return [(f"S{i + 1}", conn[a], conn[b], conn[m]) for i, (a, b, m) in enumerate(pairs)]


class Mesh:
    """Nodes and counter-clockwise elements tagged layer / inclusion / tool."""

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

    def boundary_faces(self, phys_tags, keep):
        """Free edges of the given parts for which keep(xs, ys) of their 3 nodes holds."""
        edges, seen = [], {}
        for eid, kind, phys, conn in self.elements:
            if phys not in phys_tags:
                continue
            for label, a, b, m in element_edges(kind, conn):
                key = frozenset((a, b))
                seen[key] = seen.get(key, 0) + 1
                edges.append((key, eid, label, (a, b, m)))
        out = []
        for key, eid, label, ns in edges:
            xs, ys = zip(*(self.nodes[n] for n in ns))
            if seen[key] == 1 and keep(np.array(xs), np.array(ys)):
                out.append((eid, label))
        return out


# --------------------------------------------------------------------------
# CalculiX input deck

def id_lines(ids, per_line=12):
    ids = list(ids)
    return [", ".join(map(str, ids[i:i + per_line])) for i in range(0, len(ids), per_line)]


def material_block(name, o, modulus, hyperelastic):
    lines = [f"*MATERIAL, NAME={name}"]
    nu = o.poisson
    if hyperelastic:
        c10 = modulus / (4.0 * (1.0 + nu))
        d1 = 6.0 * (1.0 - 2.0 * nu) / modulus
        return lines + ["*HYPERELASTIC, NEO HOOKE", f"{c10:.10e}, {d1:.10e}"]
    return lines + ["*ELASTIC", f"{modulus:.10e}, {nu:.10e}"]


def layer_elsets(o):
    """[(physical tag, element set, material, modulus)] of the layers under the top one."""
    layers = o.layers if is_layered(o) else []
    return [(PHYS_SUBLAYER + i, f"LAYER{i + 1}", f"TISSUE{i + 1}", E)
            for i, (_, E) in enumerate(layers) if i > 0]


def element_block(mesh, element, o):
    quad_type, tri_type = ELEMENT_TYPES[element]
    parts = [(PHYS_LAYER, "LAYER"), (PHYS_INCLUSION, "INCL"), (PHYS_TOOL, "TOOL")]
    parts += [(phys, name) for phys, name, _, _ in layer_elsets(o)]
    out = []
    for kind, ctype in (("quad8", quad_type), ("tri6", tri_type)):
        for phys, name in parts:
            rows = [(eid, conn) for eid, k, p, conn in mesh.elements if k == kind and p == phys]
            if rows:
                out.append(f"*ELEMENT, TYPE={ctype}, ELSET={name}")
                out += [f"{eid}, " + ", ".join(map(str, conn)) for eid, conn in rows]
    return out


def node_sets(o, mesh):
    """Named node sets and the name of the set that is driven."""
    h = o.thickness
    body = mesh.nodes_of(body_tags(o))
    sets = {"BASE": mesh.select(body, lambda x, y: abs(y + h) < TOL),
            "AXIS": mesh.select(body, lambda x, y: abs(x) < TOL and y > -h + TOL)}
    a = o.punch_radius
    if o.indenter == "flat":
        sets["PUNCH"] = mesh.select(body, lambda x, y: abs(y) < TOL and x <= a + TOL)
        sets["EDGE"] = mesh.select(body, lambda x, y: abs(y) < TOL and abs(x - a) < TOL)
        return sets, "PUNCH"
    tool, H = mesh.nodes_of({PHYS_TOOL}), tool_height(o)
    sets["DRIVE"] = mesh.select(tool, lambda x, y: abs(y - H) < TOL)
    sets["TOOLAXIS"] = mesh.select(tool, lambda x, y: abs(x) < TOL and y < H - TOL)
    return sets, "DRIVE"


def contact_block(o, mesh):
    """Frictionless penalty contact: skin (slave) against the tool (master)."""
    if o.indenter == "pad":
        reach = o.punch_radius + max(4.0 * o.edge_radius, o.max_depth)
    else:
        reach = 1.5 * sphere_contact_radius(o)
    reach = min(reach, o.radius)
    skin = mesh.boundary_faces(
        {PHYS_LAYER}, lambda x, y: np.all(np.abs(y) < TOL) and np.all(x <= reach + TOL))
    H = tool_height(o)   # all free edges of the tool except its axis and its top
    tool = mesh.boundary_faces(
        {PHYS_TOOL}, lambda x, y: not np.all(x < TOL) and not np.all(np.abs(y - H) < TOL))
    if not skin or not tool:
        raise SolveError("could not find the contact faces of the skin or the tool")
    k = o.contact_stiffness or 20.0 * o.modulus / o.mesh_size
    return (["*SURFACE, NAME=SKIN"] + [f"{e}, {s}" for e, s in skin]
            + ["*SURFACE, NAME=TOOLFACE"] + [f"{e}, {s}" for e, s in tool]
            + ["*CONTACT PAIR, INTERACTION=SLIP, TYPE=SURFACE TO SURFACE", "SKIN, TOOLFACE",
               "*SURFACE INTERACTION, NAME=SLIP",
               "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{k:.10e}"])


def step_block(o, load_set):
    dt = 1.0 / o.steps
    L = ["*TIME POINTS, NAME=TP, GENERATE", f"0., 1., {dt:.10e}"]
    L.append("*STEP, NLGEOM, INC=10000" if o.nlgeom else "*STEP, INC=10000")
    if is_nonlinear(o):
        first = dt / 10.0 if uses_contact(o) else dt   # contact needs a gentle start
        L += ["*STATIC", f"{first:.10e}, 1., {dt * 1e-3:.10e}, {dt:.10e}"]
        tp = ", TIME POINTS=TP"
    else:
        L += ["*STATIC"]   # one linear solve, scaled to the output depths
        tp = ""
    L += ["*BOUNDARY", f"{load_set}, 2, 2, {-o.max_depth:.10e}"]
    L += [f"*NODE PRINT, NSET={load_set}, TOTALS=ONLY{tp}", "RF"]
    if o.indenter == "flat":
        L += [f"*NODE PRINT, NSET=EDGE{tp}", "U"]
    if o.keep:
        L += [f"*NODE FILE{tp}", "U"]
    return L + ["*END STEP"]


def inp_text(o, mesh):
    """CalculiX input deck and the name of the driven node set."""
    hyper = o.material == "neohookean"
    L = ["*HEADING", "Palpa indentation reference (tools/fem/indent.py), SI units"]
    L.append("*NODE, NSET=NALL")
    for n in sorted(mesh.nodes_of(body_tags(o) | {PHYS_TOOL})):
        x, y = mesh.nodes[n]
        L.append(f"{n}, {x:.12e}, {y:.12e}")
    L += element_block(mesh, o.element, o)
    sets, load_set = node_sets(o, mesh)
    for name, ids in sets.items():
        if not ids:
            raise SolveError(f"empty node set {name}: mesh and geometry disagree")
        L.append(f"*NSET, NSET={name}")
        L += id_lines(ids)
    L += material_block("TISSUE", o, o.modulus, hyper)
    L += ["*SOLID SECTION, ELSET=LAYER, MATERIAL=TISSUE"]
    if o.inclusion_radius is not None:
        L += material_block("LUMP", o, o.modulus * o.inclusion_ratio, hyper)
        L += ["*SOLID SECTION, ELSET=INCL, MATERIAL=LUMP"]
    for _, elset, material, modulus in layer_elsets(o):
        L += material_block(material, o, modulus, hyper)
        L += [f"*SOLID SECTION, ELSET={elset}, MATERIAL={material}"]
    L += ["*BOUNDARY", "BASE, 1, 2, 0.", "AXIS, 1, 1, 0."]
    if o.indenter == "flat" and o.pin_edge:
        L += ["EDGE, 1, 1, 0."]
    if uses_contact(o):
        L += ["TOOLAXIS, 1, 1, 0.", "DRIVE, 1, 1, 0."]
        L += ["*MATERIAL, NAME=RIGID", "*ELASTIC",
              f"{o.modulus * TOOL_STIFFNESS_RATIO:.10e}, {TOOL_POISSON}"]
        L += ["*SOLID SECTION, ELSET=TOOL, MATERIAL=RIGID"]
        L += contact_block(o, mesh)
    L += step_block(o, load_set)
    return "\n".join(L) + "\n", load_set


# --------------------------------------------------------------------------
# running CalculiX and reading its results

def solver_env():
    """Single-threaded CalculiX (the machine is shared)."""
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
    errors = [line.strip() for line in res.stdout.splitlines() if "*ERROR" in line]
    return res.returncode, errors


NUM = r"[-+]?\d*\.?\d+(?:[eE][-+]?\d+)?"


def read_print_blocks(dat_path, title, set_name):
    """[(time, first data row)] of the *NODE PRINT blocks with this title."""
    head = re.compile(rf"{re.escape(title)} for set {set_name} and time\s+({NUM})")
    with open(dat_path) as f:
        lines = f.read().splitlines()
    out = []
    for i, line in enumerate(lines):
        m = head.search(line)
        if m:
            row = next(l for l in lines[i + 1:] if l.strip()).split()
            out.append((float(m.group(1)), [float(v) for v in row]))
    return out


def curve_from_totals(o, totals):
    """Depth/force rows at the output depths; a linear solve is scaled."""
    rows = [(0.0, 0.0)]
    if not is_nonlinear(o):
        fy = totals[-1][1][1]
        return rows + [(i / o.steps * o.max_depth, -fy * AXI_FORCE_FACTOR * i / o.steps)
                       for i in range(1, o.steps + 1)]
    return rows + [(t * o.max_depth, -vals[1] * AXI_FORCE_FACTOR) for t, vals in totals if t > 0.0]


def write_csv(path, rows):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["depth_m", "force_n"])
        for d, F in rows:
            w.writerow([f"{d:.6e}", f"{F:.6e}"])


# --------------------------------------------------------------------------
# driver

def solve(o, workdir):
    """Mesh and solve one model; returns (rows, info). Raises SolveError."""
    o.mesh_size = o.mesh_size or default_mesh_size(o)
    geo, msh = os.path.join(workdir, "model.geo"), os.path.join(workdir, "model.msh")
    with open(geo, "w") as f:
        f.write(geo_text(o, o.mesh_size))
    t0, cpu0 = time.monotonic(), resource.getrusage(resource.RUSAGE_CHILDREN)
    run_gmsh(geo, msh)
    mesh = Mesh(*read_msh22(msh))
    text, load_set = inp_text(o, mesh)
    with open(os.path.join(workdir, "model.inp"), "w") as f:
        f.write(text)
    rc, errors = run_ccx(workdir, "model")
    cpu1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    info = {"wall_s": time.monotonic() - t0,
            "cpu_s": cpu1.ru_utime + cpu1.ru_stime - cpu0.ru_utime - cpu0.ru_stime,
            "elements": len(mesh.elements),
            "nodes": len(mesh.nodes_of(body_tags(o) | {PHYS_TOOL}))}
    dat = os.path.join(workdir, "model.dat")
    totals = read_print_blocks(dat, "total force (fx,fy,fz)", load_set) if os.path.exists(dat) else []
    rows = curve_from_totals(o, totals) if totals else [(0.0, 0.0)]
    if o.indenter == "flat" and totals:
        edge = read_print_blocks(dat, "displacements (vx,vy,vz)", "EDGE")
        info["edge_ur_m"] = max(abs(vals[1]) for _, vals in edge)
    info["reached_depth_m"] = rows[-1][0]
    if rc != 0 or errors or rows[-1][0] < o.max_depth * (1.0 - 1e-6):
        why = errors[0] if errors else f"ccx exit code {rc}"
        raise SolveError(f"CalculiX stopped at depth {rows[-1][0]:.4g} m of "
                         f"{o.max_depth:.4g} m ({why})", rows, info)
    return rows, info


def describe(o, info):
    what = (f"layers {','.join(f'{t:g}:{E:g}' for t, E in o.layers)}" if o.layers
            else f"E={o.modulus:g} Pa")
    text = (f"{o.indenter} on h={o.thickness:g} m, {what}, nu={o.poisson:g}, "
            f"{o.material}{' nlgeom' if o.nlgeom else ''}: {info['elements']} elements, "
            f"{info['nodes']} nodes, wall {info['wall_s']:.1f} s, cpu {info['cpu_s']:.1f} s")
    if "edge_ur_m" in info:
        text += f", largest radial displacement of the punch-edge node {info['edge_ur_m']:.3g} m"
    return text


def main(argv=None):
    parser = build_parser()
    o = parser.parse_args(argv)
    check_options(parser, o)
    for prog in ("gmsh", "ccx"):
        if shutil.which(prog) is None:
            print(f"indent.py: error: '{prog}' not found on PATH", file=sys.stderr)
            return 1
    cleanup = None
    if o.keep:
        os.makedirs(o.keep, exist_ok=True)
        workdir = o.keep
    else:
        cleanup = tempfile.TemporaryDirectory(prefix="palpa_fem_")
        workdir = cleanup.name
    try:
        rows, info = solve(o, workdir)
    except SolveError as exc:
        if o.allow_partial and exc.rows and len(exc.rows) > 1:
            write_csv(o.out, exc.rows)
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
