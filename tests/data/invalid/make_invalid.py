#!/usr/bin/env python3
"""Writes the invalid case files used by the validation tests, and expected.json.

Each file is a small valid 3x3 case with exactly one change that breaks one rule of
case format v1 (docs/case-format.md). Deterministic: rerunning it reproduces the
committed files byte for byte. Usage: python3 tests/data/invalid/make_invalid.py

expected.json maps each file name to:
  "pointer": the JSON pointer the one-line error must name ("line" for errors found
             while reading the text, reported as "line L, column C"; "" for the root).
             A list means any one of the alternatives. A pointer also matches
             a deeper one (the error for a missing field may name the parent or
             the field itself).
  "keyword": a lowercase word the error line must contain (a list: any of them).
  "schema":  true when data/schema/palpa-case.schema.json rejects the file too.
  "lines":   how many problems the file has (only where it is more than one, because
             one change breaks a rule several times); a validator may report all of
             them or stop at the first, so 1 to "lines" error lines are accepted.
  "what":    the broken rule, for humans.
"""

import copy
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))
ROWS = COLS = 3
N = ROWS * COLS
MID = 4  # the only interior site of a 3x3 grid


def base():
    medial = []
    for i in range(ROWS):
        for j in range(COLS):
            x, y = 0.02 * (i - 1), 0.02 * (j - 1)
            medial.append([x, y, 0.005 if (i, j) == (1, 1) else 0.0])
    radius = [0.0] * N
    radius[MID] = 0.01
    return {
        "format": "palpa-case",
        "version": 1,
        "title": "invalid-case base (3x3)",
        "bodies": [{
            "id": "b0",
            "rows": ROWS,
            "cols": COLS,
            "medial": medial,
            "radius": radius,
            "stiffness": [200.0] * N,
        }],
    }


def dump(v, ind=0):
    """Readable JSON: arrays of scalars on one line."""
    pad, pad2 = " " * ind, " " * (ind + 2)
    if isinstance(v, dict):
        if not v:
            return "{}"
        items = [f"{pad2}{json.dumps(k)}: {dump(x, ind + 2)}" for k, x in v.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(v, list):
        if all(not isinstance(x, (dict, list)) for x in v):
            return "[" + ", ".join(json.dumps(x) for x in v) + "]"
        return "[\n" + ",\n".join(pad2 + dump(x, ind + 2) for x in v) + "\n" + pad + "]"
    return json.dumps(v)


CASES = {}  # name -> (text, expected entry)


def add(name, pointer, keyword, schema, what, edit=None, text=None, lines=1):
    if text is None:
        c = base()
        edit(c)
        text = dump(c) + "\n"
    entry = {"pointer": pointer, "keyword": keyword, "schema": schema}
    if lines != 1:
        entry["lines"] = lines
    entry["what"] = what
    CASES[name] = (text, entry)


def body(c):
    return c["bodies"][0]


def setitem(path, value):
    """edit function: sets c[path...] = value."""
    def edit(c):
        obj = c
        for k in path[:-1]:
            obj = obj[k]
        obj[path[-1]] = value
    return edit


def delitem(path):
    def edit(c):
        obj = c
        for k in path[:-1]:
            obj = obj[k]
        del obj[path[-1]]
    return edit


def with_arrays(**arrays):
    """edit function adding per-point arrays, then one bad entry: with_arrays(mass=(1e-3, 0.0))."""
    def edit(c):
        for key, (good, bad) in arrays.items():
            body(c)[key] = [good] * N
            body(c)[key][MID] = bad
    return edit


B = ["bodies", 0]

# --- errors found while reading the text ------------------------------------
base_text = dump(base()) + "\n"
add("not-json.json", "line", "json", False, "not JSON at all", text="this is not a case file\n")
add("empty-file.json", "line", "json", False, "empty file (0 bytes)", text="")
add("truncated.json", "line", "json", False, "text cut off in the middle",
    text=base_text[: len(base_text) // 2])
add("nan-literal.json", "line", "json", False, "bare NaN is not JSON",
    text=base_text.replace("[0.0, 0.0, 0.0, 0.0, 0.01,", "[0.0, 0.0, 0.0, 0.0, NaN,"))
# 1e400 overflows a double: a parser either rejects it or reads inf, which is not finite.
add("huge-number.json", ["line", "/bodies/0/radius/4"], ["json", "radius"], True,
    "number overflowing a double (1e400)",
    text=base_text.replace("[0.0, 0.0, 0.0, 0.0, 0.01,", "[0.0, 0.0, 0.0, 0.0, 1e400,"))
assert "NaN" in CASES["nan-literal.json"][0] and "1e400" in CASES["huge-number.json"][0]
# Nesting is checked on the raw text before parsing, so it is reported by position.
add("deep-nesting.json", "line", "nest", False, "10000 nested arrays in an extra field (limit 64)",
    text=base_text.replace('"title":', '"comment": ' + "[" * 10000 + "]" * 10000 + ',\n  "title":', 1))

# --- root -------------------------------------------------------------------
add("root-not-object.json", "", "object", True, "root is an array", text="[]\n")
add("missing-format.json", "", "format", True, "no \"format\"", delitem(["format"]))
add("wrong-format.json", "/format", "format", True, "\"format\" is not \"palpa-case\"",
    setitem(["format"], "palpa-cas"))
add("version-2.json", "/version", "version", True, "\"version\" is 2", setitem(["version"], 2))
add("version-string.json", "/version", "version", True, "\"version\" is the string \"1\"",
    setitem(["version"], "1"))
add("missing-title.json", "", "title", True, "no \"title\"", delitem(["title"]))
add("title-not-string.json", "/title", "title", True, "\"title\" is a number", setitem(["title"], 42))
add("title-too-long.json", "/title", "title", True, "\"title\" has 1025 characters",
    setitem(["title"], "t" * 1025))
add("missing-bodies.json", "", "bodies", True, "no \"bodies\"", delitem(["bodies"]))
add("bodies-not-array.json", "/bodies", "bodies", True, "\"bodies\" is an object",
    setitem(["bodies"], {}))
add("empty-bodies.json", "/bodies", "bodies", True, "\"bodies\" is empty", setitem(["bodies"], []))
add("tumors-not-array.json", "/tumors", "tumors", True, "\"tumors\" is an object",
    setitem(["tumors"], {"body": "b0", "center": [0, 0, 0.005], "radius": 0.002, "stiffness": 1000}))
add("tumor-not-object.json", "/tumors/0", "tumors", True, "a \"tumors\" entry is a number",
    setitem(["tumors"], [42]))


def too_many_bodies():
    small = {"id": "", "rows": 2, "cols": 2,
             "medial": [[0, 0, 0], [0, 0.01, 0], [0.01, 0, 0], [0.01, 0.01, 0]],
             "radius": [0, 0, 0, 0], "stiffness": [100, 100, 100, 100]}
    bodies = []
    for k in range(257):
        b = dict(small, id=f"b{k}")
        bodies.append(json.dumps(b, separators=(",", ":")))
    return ('{\n  "format": "palpa-case",\n  "version": 1,\n  "title": "257 bodies",\n'
            '  "bodies": [\n    ' + ",\n    ".join(bodies) + "\n  ]\n}\n")


add("too-many-bodies.json", "/bodies", "bodies", True, "257 bodies (limit 256)", text=too_many_bodies())

# --- body header ------------------------------------------------------------
add("body-not-object.json", "/bodies/0", "object", True, "a body is a number",
    setitem(["bodies", 0], 1))
add("missing-id.json", "/bodies/0", "id", True, "body without \"id\"", delitem(B + ["id"]))
add("empty-id.json", "/bodies/0/id", "id", True, "empty \"id\"", setitem(B + ["id"], ""))
add("id-too-long.json", "/bodies/0/id", "id", True, "\"id\" of 65 characters",
    setitem(B + ["id"], "b" * 65))
add("id-not-string.json", "/bodies/0/id", "id", True, "\"id\" is a number", setitem(B + ["id"], 7))


def duplicate(c):
    second = copy.deepcopy(body(c))
    for p in second["medial"]:
        p[0] += 0.1
    c["bodies"].append(second)


add("duplicate-ids.json", "/bodies/1/id", "duplicate", False, "two bodies with id \"b0\"", duplicate)
add("missing-rows.json", "/bodies/0", "rows", True, "body without \"rows\"", delitem(B + ["rows"]))
add("rows-not-integer.json", "/bodies/0/rows", "rows", True, "\"rows\" is 2.5",
    setitem(B + ["rows"], 2.5))


def grid_1xn(c):
    b = body(c)
    b.update(rows=1, cols=9, medial=[[0.0, 0.01 * j, 0.0] for j in range(9)],
             radius=[0.0] * 9, stiffness=[200.0] * 9)


add("grid-1xN.json", "/bodies/0/rows", "rows", True, "1 x 9 grid (rows must be >= 2)", grid_1xn)
add("cols-too-large.json", "/bodies/0/cols", "cols", True, "\"cols\" is 257 (limit 256)",
    setitem(B + ["cols"], 257))
# Must be rejected from the header alone, before anything of rows*cols size is allocated.
add("absurd-size.json", "/bodies/0", ["rows", "cols"], True, "100000 x 100000 grid with 3x3 arrays",
    lambda c: body(c).update(rows=100000, cols=100000), lines=2)

# --- per-point arrays -------------------------------------------------------
add("count-mismatch.json", "/bodies/0/radius", "radius", False, "\"radius\" has 8 entries, not 9",
    lambda c: body(c)["radius"].pop())
add("medial-count-mismatch.json", "/bodies/0/medial", "medial", False, "\"medial\" has 10 points, not 9",
    lambda c: body(c)["medial"].append([0.05, 0.05, 0.0]))
add("damping-count-mismatch.json", "/bodies/0/damping", "damping", False,
    "\"damping\" has 8 entries, not 9", lambda c: body(c).update(damping=[0.5] * 8))
add("medial-not-array.json", "/bodies/0/medial", "medial", True, "\"medial\" is a string",
    setitem(B + ["medial"], "none"))
add("medial-not-triplets.json", "/bodies/0/medial/4", "medial", True, "a medial point with 2 coordinates",
    setitem(B + ["medial", MID], [0.0, 0.0]))
add("medial-out-of-range.json", "/bodies/0/medial/4", "medial", True, "a coordinate of 1000 m (limit 100)",
    setitem(B + ["medial", MID, 2], 1000.0))
add("missing-radius.json", "/bodies/0", "radius", True, "body without \"radius\"", delitem(B + ["radius"]))
add("negative-radius.json", "/bodies/0/radius/4", "radius", True, "radius -0.01 m",
    setitem(B + ["radius", MID], -0.01))
add("radius-too-large.json", "/bodies/0/radius/4", "radius", True, "radius 11 m (limit 10)",
    setitem(B + ["radius", MID], 11.0))
add("nan-like-string.json", "/bodies/0/radius/4", "radius", True, "radius is the string \"NaN\"",
    setitem(B + ["radius", MID], "NaN"))
add("boundary-radius.json", "/bodies/0/radius/1", "boundary", False,
    "non-zero radius at boundary site (0, 1) (closure condition)", setitem(B + ["radius", 1], 0.01))
add("missing-stiffness.json", "/bodies/0", "stiffness", True, "body without \"stiffness\"",
    delitem(B + ["stiffness"]))
add("negative-stiffness.json", "/bodies/0/stiffness/4", "stiffness", True, "stiffness -1 N/m",
    setitem(B + ["stiffness", MID], -1.0))
add("stiffness-too-large.json", "/bodies/0/stiffness/4", "stiffness", True, "stiffness 2e9 N/m (limit 1e9)",
    setitem(B + ["stiffness", MID], 2e9))


def by_modulus(c):
    b = body(c)
    del b["stiffness"]
    b["modulus"] = [5000.0] * N


def by_modulus_then(path, value):
    def edit(c):
        by_modulus(c)
        setitem(path, value)(c)
    return edit


add("stiffness-and-modulus.json", "/bodies/0/modulus", "not both", True, "both stiffness (N/m) and modulus (Pa)",
    setitem(B + ["modulus"], [5000.0] * N))
add("negative-modulus.json", "/bodies/0/modulus/4", "modulus", True, "modulus -1 Pa",
    by_modulus_then(B + ["modulus", MID], -1.0))
add("poisson-too-large.json", "/bodies/0/poisson", "poisson", True, "Poisson's ratio 0.5 (limit 0.499)",
    by_modulus_then(B + ["poisson"], 0.5))
add("stiffening-without-modulus.json", "/bodies/0/stiffening", "modulus", True,
    "strain stiffening on a body given in N/m", setitem(B + ["stiffening"], 3.6))
add("stiffening-too-large.json", "/bodies/0/stiffening", "stiffening", True, "stiffening 25 (limit 20)",
    by_modulus_then(B + ["stiffening"], 25.0))
add("negative-stiffening.json", "/bodies/0/stiffening", "stiffening", True, "stiffening -1",
    by_modulus_then(B + ["stiffening"], -1.0))
add("tumour-stiffening-without-modulus.json", "/tumors/0/stiffening", "modulus", True,
    "strain stiffening on a tumour given in N/m",
    setitem(["tumors"], [{"body": "b0", "center": [0, 0, 0.005], "radius": 0.002, "stiffness": 1000,
                          "stiffening": 11.1}]))
add("tumour-stiffness-and-modulus.json", "/tumors/0/modulus", "not both", True,
    "a tumour with both stiffness (N/m) and modulus (Pa)",
    setitem(["tumors"], [{"body": "b0", "center": [0, 0, 0.005], "radius": 0.002, "stiffness": 1000,
                          "modulus": 20000}]))
add("unknown-force-model.json", "/bodies/0/force_model", "force_model", True, "force_model \"hertz\"",
    setitem(B + ["force_model"], "hertz"))
add("negative-damping.json", "/bodies/0/damping/4", "damping", True, "damping -0.5 N s/m",
    with_arrays(damping=(0.5, -0.5)))
add("damping-too-large.json", "/bodies/0/damping/4", "damping", True, "damping 2e7 N s/m (limit 1e7)",
    with_arrays(damping=(0.5, 2e7)))
add("zero-mass.json", "/bodies/0/mass/4", "mass", True, "mass 0 kg (must be > 0)",
    with_arrays(mass=(1e-3, 0.0)))
add("negative-mass.json", "/bodies/0/mass/4", "mass", True, "mass -1e-3 kg",
    with_arrays(mass=(1e-3, -1e-3)))
add("mass-too-large.json", "/bodies/0/mass/4", "mass", True, "mass 2000 kg (limit 1000)",
    with_arrays(mass=(1e-3, 2000.0)))

# --- skeleton geometry ------------------------------------------------------
# Site (1,1) moved onto (1,0): neighbours coincide, but row 1 is not a pole.
add("coincident-neighbours.json", "/bodies/0/medial", "coincid", False,
    "neighbouring sites (1,0) and (1,1) coincide outside a pole", setitem(B + ["medial", MID], [0.0, -0.02, 0.0]))


def two_poles(c):
    # Rows 0 and 1 both collapse onto the same point: each is a legal pole on its
    # own, but the column neighbours (0,j)-(1,j) then coincide.
    m = body(c)["medial"]
    for k in range(2 * COLS):
        m[k] = [-0.02, 0.0, 0.0]


add("pole-rows-coincide.json", "/bodies/0/medial", "coincid", False,
    "rows 0 and 1 both collapse onto the same point", two_poles, lines=2 * COLS - 1)


def main():
    expected = {}
    for name, (text, entry) in sorted(CASES.items()):
        with open(os.path.join(HERE, name), "w", encoding="utf-8", newline="\n") as f:
            f.write(text)
        expected[name] = entry
    with open(os.path.join(HERE, "expected.json"), "w", encoding="utf-8", newline="\n") as f:
        json.dump(expected, f, indent=2)
        f.write("\n")
    print(f"wrote {len(expected)} invalid cases and expected.json")


if __name__ == "__main__":
    main()
