#!/usr/bin/python3
"""Independent pure-Python reference for `palpa-cli fit` (Palpa case format v1).

This is a deliberately slow, textbook implementation of the fit agreed in the
Palpa working spec (paper section 2.1 + The NURBS Book, algorithm A9.4), used
only to cross-check the C++ implementation.  It shares no code or structure
with the C++ one on purpose:

* B-spline basis functions come from the Cox-de Boor recursion evaluated for
  ALL basis functions of the knot vector (not the A2.2 triangular scheme that
  only computes the p+1 non-zero ones);
* the right end of the domain is closed explicitly: at u == U[-1] the degree-0
  function of the last non-empty knot span is 1, so the last basis function is
  1 there and derivatives are the left-hand limits;
* first derivatives come from the B-spline derivative formula
  N'_{i,p} = p/(u_{i+p}-u_i) N_{i,p-1} - p/(u_{i+p+1}-u_{i+1}) N_{i+1,p-1}
  (with 0/0 := 0), not from finite differences;
* the collocation systems are dense matrices solved by Gaussian elimination
  with partial pivoting (the matrix is stored and pivoted densely; updates with
  an exactly-zero multiplier are skipped, which changes no result);
* the surface is evaluated as the plain double sum sum_i sum_j N_i(u) N_j(v) P_ij
  (terms whose basis product is exactly zero are skipped, which changes no
  result for finite control points).

The fit (spec, "Fit"):
* skeleton SK = 7 channels x, y, z, radius, stiffness, damping, mass with
  defaults filled in first (mass 1e-3 kg, damping 2*0.7*sqrt(k*m));
* degree p = min(3, rows-1) along u (index i, rows), q = min(3, cols-1) along v;
* chord-length parameters from xyz only, computed per column (row), averaged
  over the columns (rows) whose total chord length is non-zero; first
  parameter 0 and last 1 exactly (centripetal is available as an option);
* knots by averaging (NURBS Book eq. 9.8);
* control points from the u-direction then the v-direction collocation solve;
* normals N(i,j) = normalize(Su x Sv) of SK's xyz at (ubar_i, vbar_j);
* top R = P + r N, bottom S = P - r N with P, r the DATA values (where r == 0
  the point is P exactly, whatever the normal; a vanishing Su x Sv gives the
  zero normal and is reported in Fit.degenerate_normals when r > 0 there);
* top and bottom are 3-channel surfaces interpolated on the same parameters
  and knots.

Module use:
    import a94_reference as ref
    body = ref.load_body("case.json", "b0")        # or None for the first body
    f = ref.fit(body)
    ref.evaluate_skeleton(f, u, v)   # [x, y, z, radius, stiffness, damping, mass]
    ref.evaluate_top(f, u, v)        # [x, y, z]
    ref.evaluate_bottom(f, u, v)     # [x, y, z]

Command line (mirrors `palpa-cli fit`):
    a94_reference.py [fit] CASE [--body ID] [--surface skeleton|top|bottom]
                     [--centripetal] --eval UV.csv
prints the CSV `u,v,x,y,z[,radius,stiffness,damping,mass]` with 17
significant digits.  Errors: one line "a94_reference: error: ..." and exit 2.
Standard library only.
"""

import argparse
import json
import math
import sys

DEFAULT_MASS = 1e-3          # kg per point when "mass" is absent
DAMPING_RATIO = 0.7          # default damping b = 2 * 0.7 * sqrt(k * m)

SKELETON_CHANNELS = ("x", "y", "z", "radius", "stiffness", "damping", "mass")
CONTOUR_CHANNELS = ("x", "y", "z")
SURFACES = ("skeleton", "top", "bottom")


class ReferenceError_(Exception):
    """Bad input for the reference (message is one line)."""


# ---------------------------------------------------------------------------
# Case loading
# ---------------------------------------------------------------------------

def load_case(path):
    with open(path, "r", encoding="utf-8") as fh:
        return json.load(fh)


def body_from_json(b):
    """Plain dict body with defaults for damping/mass filled in."""
    rows = int(b["rows"])
    cols = int(b["cols"])
    n = rows * cols
    medial = [[float(c) for c in pt] for pt in b["medial"]]
    radius = [float(x) for x in b["radius"]]
    stiffness = [float(x) for x in b["stiffness"]]
    if len(medial) != n or len(radius) != n or len(stiffness) != n:
        raise ReferenceError_("body %r: array sizes do not match rows*cols" % b.get("id"))
    if "mass" in b and b["mass"] is not None:
        mass = [float(x) for x in b["mass"]]
    else:
        mass = [DEFAULT_MASS] * n
    if "damping" in b and b["damping"] is not None:
        damping = [float(x) for x in b["damping"]]
    else:
        damping = [2.0 * DAMPING_RATIO * math.sqrt(stiffness[k] * mass[k]) for k in range(n)]
    if len(mass) != n or len(damping) != n:
        raise ReferenceError_("body %r: damping/mass sizes do not match rows*cols" % b.get("id"))
    return {
        "id": b.get("id"),
        "rows": rows,
        "cols": cols,
        "medial": medial,
        "radius": radius,
        "stiffness": stiffness,
        "damping": damping,
        "mass": mass,
        "has_damping": "damping" in b,
        "has_mass": "mass" in b,
    }


def load_body(path, body_id=None):
    """Load body `body_id` (default: the first) from a case file."""
    case = load_case(path)
    bodies = case.get("bodies") or []
    if not bodies:
        raise ReferenceError_("%s: no bodies" % path)
    if body_id is None:
        return body_from_json(bodies[0])
    for b in bodies:
        if b.get("id") == body_id:
            return body_from_json(b)
    raise ReferenceError_("%s: no body with id %r" % (path, body_id))


def skeleton_data(body):
    """Data grid Q[i][j] = [x,y,z,radius,stiffness,damping,mass] (defaults filled)."""
    rows, cols = body["rows"], body["cols"]
    Q = []
    for i in range(rows):
        row = []
        for j in range(cols):
            k = i * cols + j
            x, y, z = body["medial"][k]
            row.append([x, y, z, body["radius"][k], body["stiffness"][k],
                        body["damping"][k], body["mass"][k]])
        Q.append(row)
    return Q


# ---------------------------------------------------------------------------
# Parameters and knots
# ---------------------------------------------------------------------------

def _dist3(a, b):
    return math.sqrt((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2 + (a[2] - b[2]) ** 2)


def chord_parameters(lines, centripetal=False):
    """Averaged chord-length parameters for a family of polylines.

    `lines` is a list of polylines, each a list of n xyz points (the same n).
    Returns n parameters, first 0.0, last 1.0 exactly; polylines of total
    length 0 are skipped.
    """
    n = len(lines[0])
    acc = [0.0] * n
    used = 0
    for pts in lines:
        chords = []
        for k in range(1, n):
            d = _dist3(pts[k], pts[k - 1])
            chords.append(math.sqrt(d) if centripetal else d)
        total = sum(chords)
        if total == 0.0:
            continue
        used += 1
        cum = 0.0
        for k in range(1, n):
            cum += chords[k - 1]
            acc[k] += cum / total
    if used == 0:
        raise ReferenceError_("all polylines have zero length: cannot parameterize")
    params = [a / used for a in acc]
    params[0] = 0.0
    params[-1] = 1.0
    return params


def averaged_knots(params, p):
    """NURBS Book eq. 9.8: clamped knot vector of length len(params) + p + 1."""
    n = len(params)
    U = [0.0] * (p + 1)
    for j in range(1, n - p):
        U.append(sum(params[j:j + p]) / p)
    U += [1.0] * (p + 1)
    assert len(U) == n + p + 1
    return U


# ---------------------------------------------------------------------------
# B-spline basis: Cox-de Boor recursion over all basis functions
# ---------------------------------------------------------------------------

def _last_nonempty_span(U):
    for i in range(len(U) - 2, -1, -1):
        if U[i] < U[i + 1]:
            return i
    raise ReferenceError_("knot vector has no non-empty span")


def basis_table(U, p, u):
    """Cox-de Boor table: T[d][i] = N_{i,d}(u) for d = 0..p.

    Row d has len(U) - 1 - d entries.  Half-open spans [U_i, U_{i+1}) except
    the last non-empty span, which is closed on the right so that u == U[-1]
    is inside the domain.
    """
    if not (U[0] <= u <= U[-1]):
        raise ReferenceError_("parameter %r outside [%r, %r]" % (u, U[0], U[-1]))
    m = len(U) - 1
    last = _last_nonempty_span(U)
    T0 = [0.0] * m
    for i in range(m):
        if U[i] <= u < U[i + 1]:
            T0[i] = 1.0
    if u == U[-1]:
        T0[last] = 1.0
    T = [T0]
    for d in range(1, p + 1):
        prev = T[-1]
        cur = []
        for i in range(m - d):
            val = 0.0
            den1 = U[i + d] - U[i]
            if den1 != 0.0 and prev[i] != 0.0:
                val += (u - U[i]) / den1 * prev[i]
            den2 = U[i + d + 1] - U[i + 1]
            if den2 != 0.0 and prev[i + 1] != 0.0:
                val += (U[i + d + 1] - u) / den2 * prev[i + 1]
            cur.append(val)
        T.append(cur)
    return T


def basis(U, p, u):
    """All N_{i,p}(u), i = 0..len(U)-p-2."""
    return basis_table(U, p, u)[p]


def basis_and_derivative(U, p, u):
    """(N, dN): all N_{i,p}(u) and N'_{i,p}(u) by the derivative formula."""
    T = basis_table(U, p, u)
    N = T[p]
    if p == 0:
        return N, [0.0] * len(N)
    low = T[p - 1]
    dN = []
    for i in range(len(N)):
        val = 0.0
        den1 = U[i + p] - U[i]
        if den1 != 0.0:
            val += p / den1 * low[i]
        den2 = U[i + p + 1] - U[i + 1]
        if den2 != 0.0:
            val -= p / den2 * low[i + 1]
        dN.append(val)
    return N, dN


# ---------------------------------------------------------------------------
# Dense linear algebra: Gaussian elimination with partial pivoting
# ---------------------------------------------------------------------------

def solve_dense(A, B):
    """Solve A X = B; A is n x n (list of rows), B is n x m (list of rows).

    Gaussian elimination with partial pivoting on the dense matrix.  Returns X
    as n rows of m values.  Raises on an exactly singular pivot.
    """
    n = len(A)
    A = [list(r) for r in A]
    B = [list(r) for r in B]
    m = len(B[0]) if n else 0
    for k in range(n):
        piv = max(range(k, n), key=lambda r: abs(A[r][k]))
        if A[piv][k] == 0.0:
            raise ReferenceError_("singular collocation matrix (column %d)" % k)
        if piv != k:
            A[k], A[piv] = A[piv], A[k]
            B[k], B[piv] = B[piv], B[k]
        akk = A[k][k]
        rowk = A[k]
        bk = B[k]
        for r in range(k + 1, n):
            f = A[r][k] / akk
            if f == 0.0:
                continue
            rowr = A[r]
            rowr[k] = 0.0
            for c in range(k + 1, n):
                if rowk[c] != 0.0:
                    rowr[c] -= f * rowk[c]
            br = B[r]
            for c in range(m):
                br[c] -= f * bk[c]
    X = [None] * n
    for k in range(n - 1, -1, -1):
        acc = list(B[k])
        for c in range(k + 1, n):
            a = A[k][c]
            if a == 0.0:
                continue
            xc = X[c]
            for t in range(m):
                acc[t] -= a * xc[t]
        akk = A[k][k]
        X[k] = [val / akk for val in acc]
    return X


def collocation_matrix(U, p, params):
    return [basis(U, p, t) for t in params]


def interpolate_grid(Q, ubar, vbar, U, p, V, q):
    """A9.4: control points P[i][j][c] of the surface through Q[k][l][c]."""
    rows, cols, C = len(Q), len(Q[0]), len(Q[0][0])
    Au = collocation_matrix(U, p, ubar)
    Av = collocation_matrix(V, q, vbar)
    # u direction: one RHS per (column l, channel c)
    Bu = [[Q[k][l][c] for l in range(cols) for c in range(C)] for k in range(rows)]
    R = solve_dense(Au, Bu)             # R[i][l*C + c]
    # v direction: one RHS per (row i, channel c)
    Bv = [[R[i][l * C + c] for i in range(rows) for c in range(C)] for l in range(cols)]
    Pv = solve_dense(Av, Bv)            # Pv[j][i*C + c]
    return [[[Pv[j][i * C + c] for c in range(C)] for j in range(cols)] for i in range(rows)]


# ---------------------------------------------------------------------------
# Surfaces
# ---------------------------------------------------------------------------

class Surface:
    """Tensor-product B-spline surface with C channels."""

    def __init__(self, U, p, V, q, P):
        self.U, self.p, self.V, self.q, self.P = U, p, V, q, P
        self.C = len(P[0][0])

    def _sum(self, Nu, Nv, channels):
        out = [0.0] * len(channels)
        P = self.P
        for i, a in enumerate(Nu):
            if a == 0.0:
                continue
            Pi = P[i]
            for j, b in enumerate(Nv):
                w = a * b
                if w == 0.0:
                    continue
                Pij = Pi[j]
                for t, c in enumerate(channels):
                    out[t] += w * Pij[c]
        return out

    def eval(self, u, v, channels=None):
        channels = range(self.C) if channels is None else channels
        return self._sum(basis(self.U, self.p, u), basis(self.V, self.q, v), list(channels))

    def eval_with_derivatives(self, u, v, channels=None):
        """(S, Su, Sv) for the given channels (default all)."""
        channels = list(range(self.C) if channels is None else channels)
        Nu, dNu = basis_and_derivative(self.U, self.p, u)
        Nv, dNv = basis_and_derivative(self.V, self.q, v)
        return (self._sum(Nu, Nv, channels),
                self._sum(dNu, Nv, channels),
                self._sum(Nu, dNv, channels))


class Fit:
    pass


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def fit(body, centripetal=False):
    """Fit skeleton, top and bottom surfaces of a body (dict from body_from_json)."""
    rows, cols = body["rows"], body["cols"]
    if rows < 2 or cols < 2:
        raise ReferenceError_("rows and cols must be >= 2")
    Q = skeleton_data(body)
    p = min(3, rows - 1)
    q = min(3, cols - 1)
    columns = [[Q[i][j][:3] for i in range(rows)] for j in range(cols)]
    rowlines = [[Q[i][j][:3] for j in range(cols)] for i in range(rows)]
    ubar = chord_parameters(columns, centripetal)
    vbar = chord_parameters(rowlines, centripetal)
    U = averaged_knots(ubar, p)
    V = averaged_knots(vbar, q)
    sk = Surface(U, p, V, q, interpolate_grid(Q, ubar, vbar, U, p, V, q))

    normals = [[None] * cols for _ in range(rows)]
    top_pts = [[None] * cols for _ in range(rows)]
    bot_pts = [[None] * cols for _ in range(rows)]
    degenerate = []
    for i in range(rows):
        for j in range(cols):
            _, Su, Sv = sk.eval_with_derivatives(ubar[i], vbar[j], (0, 1, 2))
            c = _cross(Su, Sv)
            ln = math.sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2])
            Pd = Q[i][j][:3]
            r = Q[i][j][3]
            if ln > 0.0 and math.isfinite(ln):
                nrm = [c[0] / ln, c[1] / ln, c[2] / ln]
            else:
                nrm = [0.0, 0.0, 0.0]
                if r != 0.0:
                    degenerate.append((i, j))
            normals[i][j] = nrm
            if r == 0.0:
                top_pts[i][j] = list(Pd)
                bot_pts[i][j] = list(Pd)
            else:
                top_pts[i][j] = [Pd[t] + r * nrm[t] for t in range(3)]
                bot_pts[i][j] = [Pd[t] - r * nrm[t] for t in range(3)]

    f = Fit()
    f.body = body
    f.rows, f.cols, f.p, f.q = rows, cols, p, q
    f.ubar, f.vbar, f.U, f.V = ubar, vbar, U, V
    f.data = Q
    f.skeleton = sk
    f.normals = normals
    f.top_data = top_pts
    f.bottom_data = bot_pts
    f.top = Surface(U, p, V, q, interpolate_grid(top_pts, ubar, vbar, U, p, V, q))
    f.bottom = Surface(U, p, V, q, interpolate_grid(bot_pts, ubar, vbar, U, p, V, q))
    f.degenerate_normals = degenerate
    return f


def evaluate_skeleton(f, u, v):
    return f.skeleton.eval(u, v)


def evaluate_top(f, u, v):
    return f.top.eval(u, v)


def evaluate_bottom(f, u, v):
    return f.bottom.eval(u, v)


def evaluate(f, surface, u, v):
    if surface == "skeleton":
        return evaluate_skeleton(f, u, v)
    if surface == "top":
        return evaluate_top(f, u, v)
    if surface == "bottom":
        return evaluate_bottom(f, u, v)
    raise ReferenceError_("unknown surface %r" % surface)


def header(surface):
    chans = SKELETON_CHANNELS if surface == "skeleton" else CONTOUR_CHANNELS
    return "u,v," + ",".join(chans)


def data_grid(f, surface):
    """Values the surface interpolates at the data sites, Q[i][j][c]."""
    return {"skeleton": f.data, "top": f.top_data, "bottom": f.bottom_data}[surface]


# ---------------------------------------------------------------------------
# UV.csv and CLI
# ---------------------------------------------------------------------------

def read_uv(path):
    with open(path, "r", encoding="utf-8") as fh:
        lines = fh.read().splitlines()
    if not lines or lines[0].strip().replace(" ", "") != "u,v":
        raise ReferenceError_("%s: line 1: header must be 'u,v'" % path)
    out = []
    for ln, line in enumerate(lines[1:], start=2):
        if not line.strip():
            continue
        parts = line.split(",")
        if len(parts) != 2:
            raise ReferenceError_("%s: line %d: expected 2 values" % (path, ln))
        try:
            u, v = float(parts[0]), float(parts[1])
        except ValueError:
            raise ReferenceError_("%s: line %d: not a number" % (path, ln))
        if not (0.0 <= u <= 1.0 and 0.0 <= v <= 1.0):
            raise ReferenceError_("%s: line %d: value outside [0,1]" % (path, ln))
        out.append((u, v))
    return out


def fmt(x):
    return "%.17g" % x


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv and argv[0] == "fit":
        argv = argv[1:]
    ap = argparse.ArgumentParser(prog="a94_reference",
                                 description="Reference fit (mirrors palpa-cli fit)")
    ap.add_argument("case")
    ap.add_argument("--body", default=None)
    ap.add_argument("--surface", choices=SURFACES, default="skeleton")
    ap.add_argument("--eval", dest="uv", required=True)
    ap.add_argument("--centripetal", action="store_true")
    args = ap.parse_args(argv)
    try:
        body = load_body(args.case, args.body)
        f = fit(body, centripetal=args.centripetal)
        uv = read_uv(args.uv)
    except (ReferenceError_, OSError, ValueError, KeyError, TypeError) as e:
        print("a94_reference: error: %s" % e, file=sys.stderr)
        return 2
    if f.degenerate_normals and args.surface != "skeleton":
        print("a94_reference: warning: degenerate normal with radius > 0 at %s"
              % f.degenerate_normals[:5], file=sys.stderr)
    out = [header(args.surface)]
    for u, v in uv:
        vals = evaluate(f, args.surface, u, v)
        out.append(",".join([fmt(u), fmt(v)] + [fmt(x) for x in vals]))
    sys.stdout.write("\n".join(out) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
