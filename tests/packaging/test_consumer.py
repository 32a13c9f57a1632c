#!/usr/bin/env python3
"""The core for other projects: `cmake --install` into a scratch prefix, then
examples/consumer is configured and built against that prefix alone
(find_package(Palpa) -> Palpa::core) and run.

Run: python3 tests/packaging/test_consumer.py --build-dir build/release --source-dir . --version 0.1.0

The truth for the consumer's output comes from the case files themselves: the number of
bodies and grid sizes, and for a body whose grid is mirror-symmetric about its middle point
(checked here), the top contour at that point lies straight above the skeleton point by one
radius (the normal is vertical there by symmetry).
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import unittest

ARGS = None
SKIP = 77
TOL = 1e-9  # m; the fit interpolates the data sites to round-off, printed to 1e-9 m


def run(cmd, timeout=600, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, **kw)


def expected_centre_top(body):
    rows, cols = body["rows"], body["cols"]
    self_check = rows % 2 == 1 and cols % 2 == 1
    pts, rad = body["medial"], body["radius"]
    ci, cj = rows // 2, cols // 2
    c = pts[ci * cols + cj]
    for i in range(rows):
        for j in range(cols):
            p = pts[i * cols + j]
            mi = pts[(2 * ci - i) * cols + j]  # mirrored in u
            mj = pts[i * cols + (2 * cj - j)]  # mirrored in v
            self_check = self_check and abs(p[2] - mi[2]) < 1e-12 and abs(p[2] - mj[2]) < 1e-12
            self_check = self_check and abs(rad[i * cols + j] - rad[(2 * ci - i) * cols + j]) < 1e-12
            self_check = self_check and abs(rad[i * cols + j] - rad[i * cols + (2 * cj - j)]) < 1e-12
            # x and y mirror about the centre point (a regular grid around it)
            self_check = self_check and abs((p[0] - c[0]) + (mi[0] - c[0])) < 1e-12
            self_check = self_check and abs((p[1] - c[1]) + (mj[1] - c[1])) < 1e-12
    r = rad[ci * cols + cj]
    return self_check, (c[0], c[1], c[2] + r)


class Consumer(unittest.TestCase):
    tmp = None

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="palpa_consumer_")
        cls.prefix = os.path.join(cls.tmp.name, "prefix")
        res = run([ARGS.cmake, "--install", ARGS.build_dir, "--prefix", cls.prefix])
        if res.returncode != 0:
            raise AssertionError("cmake --install failed:\n" + res.stdout + res.stderr)
        build = os.path.join(cls.tmp.name, "build")
        configure = [ARGS.cmake, "-S", os.path.join(ARGS.source_dir, "examples", "consumer"), "-B", build,
                     "-G", ARGS.generator, "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_PREFIX_PATH=" + cls.prefix,
                     "-DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF", "-DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF"]
        if ARGS.cxx:
            configure.append("-DCMAKE_CXX_COMPILER=" + ARGS.cxx)
        res = run(configure)
        if res.returncode != 0:
            raise AssertionError("configuring examples/consumer failed:\n" + res.stdout + res.stderr)
        cls.configure_log = res.stdout
        res = run([ARGS.cmake, "--build", build])
        if res.returncode != 0:
            raise AssertionError("building examples/consumer failed:\n" + res.stdout + res.stderr)
        cls.program = os.path.join(build, "palpa-consumer")
        cls.cache = open(os.path.join(build, "CMakeCache.txt")).read()

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_package_found_in_the_prefix_only(self):
        m = re.search(r"^Palpa_DIR:PATH=(.*)$", self.cache, re.M)
        self.assertIsNotNone(m)
        self.assertTrue(os.path.realpath(m.group(1)).startswith(os.path.realpath(self.prefix) + os.sep), m.group(1))
        # The package lives where docs/install.md says: PREFIX/lib/cmake/Palpa.
        self.assertTrue(os.path.isfile(os.path.join(self.prefix, "lib", "cmake", "Palpa", "PalpaConfig.cmake")))

    def check_case(self, path, args):
        with open(path) as fh:
            case = json.load(fh)
        res = run([self.program] + args)
        self.assertEqual(res.returncode, 0, res.stderr)
        lines = res.stdout.splitlines()
        self.assertEqual(lines[0], "palpa " + ARGS.version)
        self.assertEqual(lines[1], "case %s: %d bodies" % (path, len(case["bodies"])))
        self.assertEqual(len(lines), 2 + len(case["bodies"]))
        checked = 0
        for body, line in zip(case["bodies"], lines[2:]):
            m = re.fullmatch(r"body (\S+): (\d+) x (\d+) points; top at the centre \((\S+), (\S+), (\S+)\) m", line)
            self.assertIsNotNone(m, line)
            self.assertEqual((m.group(1), int(m.group(2)), int(m.group(3))), (body["id"], body["rows"], body["cols"]))
            symmetric, top = expected_centre_top(body)
            if symmetric:
                for got, want in zip((float(m.group(k)) for k in (4, 5, 6)), top):
                    self.assertAlmostEqual(got, want, delta=TOL, msg=line)
                checked += 1
        return checked

    def test_installed_default_case(self):
        # No argument: the default case through Palpa_DATA_DIR of the installed package.
        path = os.path.join(self.prefix, "share", "palpa", "cases", "default.json")
        self.assertEqual(self.check_case(path, []), 1)

    def test_two_bodies(self):
        path = os.path.join(ARGS.source_dir, "data", "cases", "two-bodies.json")
        self.assertGreaterEqual(self.check_case(path, [path]), 1)

    def test_bad_case_is_one_line(self):
        bad = os.path.join(self.tmp.name, "bad.json")
        with open(bad, "w") as fh:
            fh.write('{"format": "palpa-case", "version": 1, "bodies": [')
        res = run([self.program, bad])
        self.assertEqual(res.returncode, 2)
        self.assertEqual(len(res.stderr.strip().splitlines()), 1, res.stderr)
        self.assertTrue(res.stderr.startswith(bad + ": "), res.stderr)


def main():
    global ARGS
    p = argparse.ArgumentParser()
    p.add_argument("--build-dir", required=True)
    p.add_argument("--source-dir", required=True)
    p.add_argument("--version", required=True)
    p.add_argument("--cmake", default="cmake")
    p.add_argument("--generator", default="Ninja")
    p.add_argument("--cxx", default="")
    p.add_argument("--sanitized", action="store_true")
    ARGS, rest = p.parse_known_args()
    ARGS.build_dir = os.path.abspath(ARGS.build_dir)
    ARGS.source_dir = os.path.abspath(ARGS.source_dir)
    if ARGS.sanitized:
        print("SKIP: the installed-package test runs in the release build (an ASan core needs the sanitizer "
              "runtime in every consumer); run ctest --preset release -R packaging")
        return SKIP
    prog = unittest.main(argv=[sys.argv[0]] + rest, exit=False, verbosity=2)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
