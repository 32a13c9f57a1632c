#!/usr/bin/python3
"""tools/check_layers.py: the repository follows its layers, and an include that breaks
one (a lower core module reaching up, a GUI or OpenCV header in core, ui reaching into
app/, a cycle in the allowed graph) is reported with its file and line.

    /usr/bin/python3 tests/tools/test_check_layers.py --repo REPO
"""

import argparse
import importlib.util
import os
import sys
import tempfile
import unittest

REPO = None


def load_checker():
    spec = importlib.util.spec_from_file_location("check_layers", os.path.join(REPO, "tools", "check_layers.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def plant(root, rel, lines):
    path = os.path.join(root, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


class Layers(unittest.TestCase):
    def test_the_repository_follows_its_layers(self):
        problems = load_checker().check(REPO)
        self.assertEqual(problems, [], "\n".join(problems))

    def test_every_broken_rule_is_named_with_file_and_line(self):
        checker = load_checker()
        with tempfile.TemporaryDirectory() as root:
            plant(root, "core/src/io/case.cpp", ['#include "palpa/io/case_file.hpp"', '#include "palpa/score/score.hpp"'])
            plant(root, "core/include/palpa/mat/body.hpp", ["#pragma once", "#include <QWidget>"])
            plant(root, "core/src/spline/fit.cpp", ["#include <opencv2/core.hpp>"])
            plant(root, "ui/src/window.cpp", ['#include "palpa/ui/window.hpp"', '#include "palpa/options/number_checks.hpp"',
                                              '#include "../../app/cli/commands.hpp"'])
            plant(root, "report/src/page.cpp", ['#include "palpa/score/score.hpp"', "#include <vtkActor.h>"])
            plant(root, "device/src/mouse.cpp", ['#include "palpa/ui/vtk_view.hpp"'])
            plant(root, "anatomy_io/src/read.cpp", ["#include <vtkSTLReader.h>", "#include <QString>",
                                                    '#include "palpa/anatomy/label_volume.hpp"',
                                                    '#include "palpa/report/page.hpp"'])
            plant(root, "ui/src/import.cpp", ['#include "palpa/anatomy_io/anatomy_io.hpp"'])
            problems = checker.check(root)
        found = sorted(p.split(": ", 1)[0] for p in problems)
        self.assertEqual(found, ["anatomy_io/src/read.cpp:2", "anatomy_io/src/read.cpp:4",
                                 "core/include/palpa/mat/body.hpp:2", "core/src/io/case.cpp:2", "core/src/spline/fit.cpp:1",
                                 "device/src/mouse.cpp:1", "report/src/page.cpp:2", "ui/src/window.cpp:2",
                                 "ui/src/window.cpp:3"], "\n".join(problems))
        io_line = next(p for p in problems if p.startswith("core/src/io/case.cpp:2"))
        self.assertIn("io includes score", io_line)
        self.assertIn("io may include: mat", io_line)

    def test_a_cycle_in_the_allowed_graph_is_refused(self):
        checker = load_checker()
        checker.CORE["spline"] = {"author"}
        with tempfile.TemporaryDirectory() as root:
            problems = checker.check(root)
        self.assertEqual(len(problems), 1, problems)
        self.assertIn("cycle", problems[0])
        self.assertIn("spline -> author", problems[0])


def main():
    global REPO
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repo", required=True)
    args, rest = parser.parse_known_args()
    REPO = os.path.abspath(args.repo)
    result = unittest.main(argv=[sys.argv[0]] + rest, exit=False).result
    return 0 if result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
