#!/usr/bin/env python3
"""End-to-end tests of `palpa-cli validate` on the bundled and the invalid cases.

Usage: python3 tests/cli/test_validate_cli.py --cli PATH/TO/palpa-cli --repo REPO_ROOT [unittest options]
Every run has a timeout, so a hang fails the test instead of blocking it.
"""

import argparse
import glob
import json
import os
import re
import subprocess
import sys
import tempfile
import unittest

CLI = None   # set in main()
REPO = None
TIMEOUT_S = 20
EXIT_BAD_INPUT = 2


def run(args, cwd=None):
    """Runs palpa-cli; a timeout fails the calling test."""
    try:
        return subprocess.run([CLI] + args, cwd=cwd, capture_output=True, text=True,
                              errors="replace", timeout=TIMEOUT_S)
    except subprocess.TimeoutExpired:
        raise AssertionError(f"palpa-cli {' '.join(args)} did not finish within {TIMEOUT_S} s")


def lines(text):
    return [line for line in text.splitlines() if line.strip()]


def alternatives(value):
    return value if isinstance(value, list) else [value]


def names_pointer(line, pointer):
    """True if the error line names the pointer. "line" means a text position
    ("line L, column C"); "" is the root. A pointer also matches a deeper one."""
    if pointer == "line":
        return re.search(r"\bline \d+", line) is not None
    if pointer in ("", "/"):
        return True
    return re.search(re.escape(pointer) + r"(?=[:/\s]|$)", line) is not None


def describe(proc):
    return f"exit {proc.returncode}\nstdout: {proc.stdout!r}\nstderr: {proc.stderr!r}"


class ValidateCliTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.cases_dir = os.path.join(REPO, "data", "cases")
        cls.invalid_dir = os.path.join(REPO, "tests", "data", "invalid")
        cls.cases = sorted(os.path.basename(p) for p in glob.glob(os.path.join(cls.cases_dir, "*.json")))
        with open(os.path.join(cls.invalid_dir, "expected.json"), encoding="utf-8") as f:
            cls.expected = json.load(f)

    def assert_clean_exit(self, proc, code):
        # A negative code means the process died from a signal (a crash).
        self.assertGreaterEqual(proc.returncode, 0, "killed by a signal\n" + describe(proc))
        self.assertEqual(proc.returncode, code, describe(proc))

    def test_bundled_cases_are_valid(self):
        self.assertTrue(self.cases, "no bundled cases found")
        for name in self.cases:
            with self.subTest(case=name):
                proc = run(["validate", name], cwd=self.cases_dir)
                self.assert_clean_exit(proc, 0)
                self.assertEqual(lines(proc.stdout), [f"{name}: ok"], describe(proc))
                self.assertEqual(proc.stderr.strip(), "", describe(proc))

    def test_all_bundled_cases_at_once(self):
        proc = run(["validate"] + self.cases, cwd=self.cases_dir)
        self.assert_clean_exit(proc, 0)
        self.assertEqual(lines(proc.stdout), [f"{name}: ok" for name in self.cases], describe(proc))

    def test_invalid_files_give_one_line_error(self):
        self.assertTrue(self.expected, "expected.json is empty")
        for name, exp in sorted(self.expected.items()):
            with self.subTest(file=name):
                proc = run(["validate", name], cwd=self.invalid_dir)
                self.assert_clean_exit(proc, EXIT_BAD_INPUT)
                err = lines(proc.stderr)
                # One line per problem: exactly one, unless the single change breaks a
                # rule several times (then the validator may report each or stop early).
                most = exp.get("lines", 1)
                self.assertTrue(1 <= len(err) <= most,
                                f"expected {'exactly one line' if most == 1 else f'1 to {most} lines'}"
                                " on stderr\n" + describe(proc))
                for line in err:
                    self.assertIn(name, line, "error does not name the file")
                line = err[0]
                pointers = alternatives(exp["pointer"])
                self.assertTrue(any(names_pointer(line, p) for p in pointers),
                                f"error does not name {pointers}: {line!r}")
                keywords = alternatives(exp["keyword"])
                self.assertTrue(any(k in line.lower() for k in keywords),
                                f"error does not mention {keywords}: {line!r}")
                self.assertNotIn(": ok", proc.stdout, describe(proc))

    def test_all_invalid_files_at_once(self):
        names = sorted(self.expected)
        proc = run(["validate"] + names, cwd=self.invalid_dir)
        self.assert_clean_exit(proc, EXIT_BAD_INPUT)
        err = lines(proc.stderr)
        self.assertGreaterEqual(len(err), len(names), describe(proc))
        self.assertLessEqual(len(err), sum(self.expected[n].get("lines", 1) for n in names), describe(proc))
        for name in names:
            self.assertTrue(any(name in line for line in err), f"no error names {name}\n" + describe(proc))

    def test_valid_and_invalid_together(self):
        valid = os.path.join(self.cases_dir, "flat-5x5.json")
        invalid = os.path.join(self.invalid_dir, "boundary-radius.json")
        proc = run(["validate", valid, invalid])
        self.assert_clean_exit(proc, EXIT_BAD_INPUT)
        self.assertEqual(lines(proc.stdout), [f"{valid}: ok"], describe(proc))
        err = lines(proc.stderr)
        self.assertEqual(len(err), 1, describe(proc))
        self.assertIn(invalid, err[0])

    def test_missing_file(self):
        with tempfile.TemporaryDirectory() as tmp:
            missing = os.path.join(tmp, "no-such-case.json")
            proc = run(["validate", missing])
        self.assert_clean_exit(proc, EXIT_BAD_INPUT)
        err = lines(proc.stderr)
        self.assertEqual(len(err), 1, describe(proc))
        self.assertIn(missing, err[0])

    def test_oversized_file(self):
        # Over the 64 MiB limit: a valid case padded with trailing whitespace.
        with tempfile.TemporaryDirectory() as tmp:
            big = os.path.join(tmp, "oversized.json")
            with open(os.path.join(self.cases_dir, "flat-5x5.json"), "rb") as src, open(big, "wb") as dst:
                dst.write(src.read())
                dst.write(b" " * ((64 << 20) + 1))
            proc = run(["validate", big])
        self.assert_clean_exit(proc, EXIT_BAD_INPUT)
        err = lines(proc.stderr)
        self.assertEqual(len(err), 1, describe(proc))
        self.assertIn(big, err[0])
        self.assertTrue(any(k in err[0].lower() for k in ("large", "size", "mib", "byte")), err[0])

    def test_validate_without_files_is_a_usage_error(self):
        proc = run(["validate"])
        self.assert_clean_exit(proc, EXIT_BAD_INPUT)
        self.assertTrue(proc.stderr.strip(), describe(proc))

    def test_version(self):
        proc = run(["--version"])
        self.assert_clean_exit(proc, 0)
        self.assertRegex(proc.stdout.strip(), r"^palpa-cli \d+\.\d+\.\d+$")


def main():
    global CLI, REPO
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cli", required=True, help="path to the palpa-cli binary")
    ap.add_argument("--repo", required=True, help="repository root")
    args, rest = ap.parse_known_args()
    CLI, REPO = os.path.abspath(args.cli), os.path.abspath(args.repo)
    unittest.main(argv=[sys.argv[0]] + rest)


if __name__ == "__main__":
    main()
