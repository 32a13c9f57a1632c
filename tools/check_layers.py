#!/usr/bin/python3
"""Checks that every #include follows Palpa's layers (docs/architecture.md, "Layers").

    /usr/bin/python3 tools/check_layers.py [--repo REPO]

Each core module (a folder core/src/M with its headers core/include/palpa/M) may include
only the core modules listed for it in CORE below, and the graph has no cycle. Above core,
each part may include only the parts listed in PARTS (ui never includes app). core, plot
and report include no GUI library; core no OpenCV either; anatomy_io no Qt (VTK's readers
are its business). Prints one line per include
that breaks a rule ("FILE:LINE: ... ") and exits 1; exits 0 when there is none.
"""

import argparse
import os
import re
import sys

# Core modules and the core modules each may include (directly), lowest first.
CORE = {
    "spline": set(),
    "mat": {"spline"},
    "contact": {"mat", "spline"},
    "io": {"mat"},
    "deform": {"contact", "mat", "spline"},
    "scene": {"contact", "io", "mat"},
    "render": {"deform", "mat", "scene", "spline"},
    "engine": {"deform", "scene"},
    "session": {"engine", "io"},
    "score": {"engine", "io", "mat", "scene", "session"},
    "scripted": {"engine", "io", "mat", "scene", "session"},
    "live": {"engine", "io", "render", "scene", "score", "scripted", "session"},
    "author": {"io", "mat", "render", "scene", "scripted"},
    "anatomy": {"io", "mat", "spline"},
}
# Headers any core module may include: palpa/version.hpp (generated) and palpa/vec3.hpp
# (the one 3-vector, docs/architecture.md "One vocabulary").
SHARED = {"version", "vec3"}
CORE_NAMES = set(CORE) | SHARED

# Parts above core: the folders, and which header families (palpa/NAME/...) each may use.
PARTS = {
    "device": {"folders": ["device"], "may": CORE_NAMES | {"device"}},
    "plot": {"folders": ["plot"], "may": {"plot"}},
    "report": {"folders": ["report"], "may": CORE_NAMES | {"plot", "report"}},
    "lrs": {"folders": ["lrs"], "may": {"lrs"}},
    "store": {"folders": ["store"], "may": CORE_NAMES | {"report", "store"}},
    "anatomy_io": {"folders": ["anatomy_io"], "may": CORE_NAMES | {"anatomy_io"}},
    "ui": {"folders": ["ui"], "may": CORE_NAMES | {"anatomy_io", "device", "plot", "report", "ui"}},
    "app": {"folders": ["app"], "may": CORE_NAMES | {"anatomy_io", "device", "plot", "report", "lrs", "store", "ui",
                                                     "options"}},
}

GUI = re.compile(r"#\s*include\s*<(Q[A-Za-z]|QVTK|vtk)")
QT = re.compile(r"#\s*include\s*<(Q[A-Za-z]|QVTK)")  # anatomy_io may use VTK's file readers, not Qt
OPENCV = re.compile(r"#\s*include\s*<opencv2/")
PALPA = re.compile(r'#\s*include\s*"palpa/([a-z0-9_]+)(/|\.hpp")')
LOCAL = re.compile(r'#\s*include\s*"((?:\.\./)+[^"]+)"')
SOURCES = (".cpp", ".hpp", ".h", ".cc", ".in")


def files_under(root):
    for folder, _, names in os.walk(root):
        for name in sorted(names):
            if name.endswith(SOURCES):
                yield os.path.join(folder, name)


def includes(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        for number, line in enumerate(f, 1):
            if "#" in line and "include" in line:
                yield number, line.strip()


def core_module_of(repo, path):
    rel = os.path.relpath(path, os.path.join(repo, "core"))
    parts = rel.split(os.sep)
    if parts[0] == "src" and len(parts) > 2:
        return parts[1]
    if parts[0] == "include" and len(parts) > 3 and parts[1] == "palpa":
        return parts[2]
    return None


def check_core(repo, problems):
    for path in files_under(os.path.join(repo, "core")):
        module = core_module_of(repo, path)
        rel = os.path.relpath(path, repo)
        for number, line in includes(path):
            where = "%s:%d: " % (rel, number)
            if GUI.search(line):
                problems.append(where + "core includes a GUI library (%s)" % line)
            if OPENCV.search(line):
                problems.append(where + "core includes OpenCV (%s); images belong in plot/ or report/" % line)
            m = PALPA.search(line)
            if not m or module is None or module not in CORE:
                if m and m.group(1) not in CORE_NAMES:
                    problems.append(where + "core includes palpa/%s, which is not core" % m.group(1))
                continue
            target = m.group(1)
            if target == module or target in SHARED:
                continue
            if target not in CORE:
                problems.append(where + "core/%s includes palpa/%s, which is not core" % (module, target))
            elif target not in CORE[module]:
                allowed = ", ".join(sorted(CORE[module])) or "no other module"
                problems.append(where + "%s includes %s (%s); %s may include: %s"
                                % (module, target, line.split('"')[1], module, allowed))


def check_parts(repo, problems):
    for part, rule in PARTS.items():
        for folder in rule["folders"]:
            for path in files_under(os.path.join(repo, folder)):
                rel = os.path.relpath(path, repo)
                for number, line in includes(path):
                    where = "%s:%d: " % (rel, number)
                    if part in ("plot", "report") and GUI.search(line):
                        problems.append(where + "%s includes a GUI library (%s)" % (part, line))
                    if part == "anatomy_io" and QT.search(line):
                        problems.append(where + "anatomy_io includes Qt (%s); it reads files with VTK only" % line)
                    m = PALPA.search(line)
                    if m and m.group(1) not in rule["may"]:
                        problems.append(where + "%s includes palpa/%s; %s may include: %s"
                                        % (part, m.group(1), part, ", ".join(sorted(rule["may"] - CORE_NAMES))
                                           + " and core"))
                    local = LOCAL.search(line)
                    if part == "ui" and local and "app/" in os.path.normpath(os.path.join(os.path.dirname(rel),
                                                                                            local.group(1))):
                        problems.append(where + "ui includes a file of app/ (%s)" % local.group(1))


def find_cycle():
    state = {}

    def visit(node, stack):
        state[node] = "open"
        for nxt in sorted(CORE[node]):
            if state.get(nxt) == "open":
                return stack + [node, nxt]
            if nxt not in state:
                found = visit(nxt, stack + [node])
                if found:
                    return found
        state[node] = "done"
        return None

    for node in sorted(CORE):
        if node not in state:
            found = visit(node, [])
            if found:
                return found
    return None


def check(repo):
    problems = []
    cycle = find_cycle()
    if cycle:
        problems.append("tools/check_layers.py: the allowed graph has a cycle: " + " -> ".join(cycle))
    check_core(repo, problems)
    check_parts(repo, problems)
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repo", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    repo = os.path.abspath(parser.parse_args().repo)
    problems = check(repo)
    for p in problems:
        print(p)
    if not problems:
        print("layers: every include follows docs/architecture.md")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
