#!/usr/bin/python3
"""Basic command-line behaviour of palpa-cli (help, version, usage and input errors of `fit`).

Run:
    /usr/bin/python3 tests/cli/test_cli_basics.py --cli PATH/palpa-cli [unittest arguments]

Standard library only.  Every call has a 20 s timeout.  Error cases must
exit with the stated code, never by a signal, and write exactly ONE non-empty
line to stderr, of the form "palpa-cli: error: ..." (spec, "palpa-cli":
"Errors: one line on stderr 'palpa-cli: error: ...' naming the file (and
line/field), exit code 2 for bad input or usage"), with no traceback or
C++ runtime message.  Bad UV.csv rows must name the UV file and the line
number (1-based, the header being line 1).
"""

import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import unittest

CLI = None
TIMEOUT = 20


def run(args):
    return subprocess.run([CLI] + list(args), capture_output=True, text=True, timeout=TIMEOUT,
                          stdin=subprocess.DEVNULL)


def small_case():
    rows, cols = 4, 5
    med, rad, stf = [], [], []
    for i in range(rows):
        for j in range(cols):
            med.append([0.02 * i, 0.015 * j, 0.001 * i * j])
            rad.append(0.0 if i in (0, rows - 1) or j in (0, cols - 1) else 0.005)
            stf.append(500.0 + 10.0 * i)
    return {"format": "palpa-case", "version": 1, "title": "small",
            "bodies": [{"id": "b0", "rows": rows, "cols": cols, "medial": med,
                        "radius": rad, "stiffness": stf},
                       {"id": "b1", "rows": 3, "cols": 3,
                        "medial": [[0.01 * i, 0.01 * j, 0.0] for i in range(3) for j in range(3)],
                        "radius": [0.0, 0.0, 0.0, 0.0, 0.002, 0.0, 0.0, 0.0, 0.0],
                        "stiffness": [100.0] * 9, "damping": [1.0] * 9, "mass": [0.01] * 9}]}


class CliBasics(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls._tmp = tempfile.TemporaryDirectory(prefix="palpa_cli_basics_")
        d = cls._tmp.name
        cls.dir = d
        cls.case = os.path.join(d, "small_case.json")
        with open(cls.case, "w", encoding="utf-8") as fh:
            json.dump(small_case(), fh)
        cls.good_uv = cls.write(d, "good_uv.csv", "u,v\n0,0\n0.1,0.3333333333333333\n1,1\n0.5,1\n")

    @classmethod
    def tearDownClass(cls):
        cls._tmp.cleanup()

    @staticmethod
    def write(d, name, text):
        p = os.path.join(d, name)
        with open(p, "w", encoding="utf-8") as fh:
            fh.write(text)
        return p

    # -- helpers ------------------------------------------------------------

    def assertNoCrash(self, res, what):
        self.assertGreaterEqual(res.returncode, 0, "%s: killed by signal %d\nstderr: %s"
                                % (what, -res.returncode, res.stderr))
        for bad in ("Traceback", "terminate called", "Segmentation", "AddressSanitizer",
                    "runtime error", "Assertion", "what():"):
            self.assertNotIn(bad, res.stderr, "%s: stderr shows a crash/diagnostic:\n%s" % (what, res.stderr))

    def assertOneLineError(self, res, what, code=2, contains=()):
        self.assertNoCrash(res, what)
        lines = [ln for ln in res.stderr.splitlines() if ln.strip()]
        self.assertEqual(res.returncode, code, "%s: exit code %d, want %d\nstderr: %s"
                         % (what, res.returncode, code, res.stderr))
        self.assertEqual(len(lines), 1, "%s: want exactly one line on stderr, got %d:\n%s"
                         % (what, len(lines), res.stderr))
        line = lines[0]
        self.assertTrue(line.startswith("palpa-cli: error:"),
                        "%s: line should start with 'palpa-cli: error:': %r" % (what, line))
        for c in contains:
            self.assertIn(c, line, "%s: error line should contain %r: %r" % (what, c, line))
        return line

    def assertLineNumber(self, line, path, number, what):
        rest = line.replace(path, "<UV>").replace(os.path.basename(path), "<UV>")
        self.assertRegex(rest, r"(?<![\d.])%d(?![\d.])" % number,
                         "%s: error line should give line number %d: %r" % (what, number, line))

    # -- help and version ---------------------------------------------------

    def test_help(self):
        res = run(["--help"])
        self.assertNoCrash(res, "--help")
        self.assertEqual(res.returncode, 0, res.stderr)
        text = res.stdout + res.stderr
        self.assertIn("validate", text)
        self.assertIn("fit", text)

    def test_version(self):
        res = run(["--version"])
        self.assertNoCrash(res, "--version")
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertRegex(res.stdout.strip(), r"^palpa-cli \d+\.\d+\.\d+\S*$")

    def test_fit_help(self):
        res = run(["fit", "--help"])
        self.assertNoCrash(res, "fit --help")
        self.assertEqual(res.returncode, 0, res.stderr)
        text = res.stdout + res.stderr
        for opt in ("--body", "--surface", "--eval"):
            self.assertIn(opt, text, "fit --help should document %s" % opt)

    def test_validate_help(self):
        res = run(["validate", "--help"])
        self.assertNoCrash(res, "validate --help")
        self.assertEqual(res.returncode, 0, res.stderr)

    # -- usage errors -------------------------------------------------------

    def test_unknown_option(self):
        res = run(["--frobnicate"])
        self.assertOneLineError(res, "unknown option")

    def test_unknown_option_is_named(self):
        """Stricter than the brief: the one line names the offending option."""
        res = run(["--frobnicate"])
        self.assertOneLineError(res, "unknown option", contains=("--frobnicate",))

    def test_unknown_fit_option(self):
        res = run(["fit", self.case, "--frobnicate"])
        self.assertOneLineError(res, "unknown fit option", contains=("--frobnicate",))

    def test_unknown_subcommand(self):
        res = run(["frobnicate"])
        self.assertOneLineError(res, "unknown subcommand")

    def test_unknown_subcommand_is_named(self):
        """Stricter than the brief: the one line names the unknown subcommand."""
        res = run(["frobnicate"])
        self.assertOneLineError(res, "unknown subcommand", contains=("frobnicate",))

    def test_no_arguments_does_not_crash(self):
        res = run([])
        self.assertNoCrash(res, "no arguments")
        self.assertIn(res.returncode, (0, 2), res.stderr)

    def test_surface_nonsense(self):
        res = run(["fit", self.case, "--surface", "nonsense", "--eval", self.good_uv])
        self.assertOneLineError(res, "--surface nonsense", contains=("nonsense",))

    # -- input errors -------------------------------------------------------

    def test_fit_missing_case_file(self):
        missing = os.path.join(self.dir, "no_such_case.json")
        res = run(["fit", missing])
        self.assertOneLineError(res, "fit missing file", contains=("no_such_case.json",))

    def test_fit_not_json(self):
        p = self.write(self.dir, "not_json_case.json", "{ this is not json\n")
        res = run(["fit", p])
        self.assertNoCrash(res, "fit not JSON")
        self.assertEqual(res.returncode, 2, res.stderr)
        self.assertIn("not_json_case.json", res.stderr)

    def test_fit_invalid_case(self):
        case = small_case()
        case["bodies"][0]["radius"][0] = 0.001          # boundary radius must be 0
        p = os.path.join(self.dir, "invalid_case.json")
        with open(p, "w", encoding="utf-8") as fh:
            json.dump(case, fh)
        res = run(["fit", p, "--eval", self.good_uv])
        self.assertNoCrash(res, "fit invalid case")
        self.assertEqual(res.returncode, 2, res.stderr)
        self.assertIn("invalid_case.json", res.stderr)

    def test_fit_body_nosuch(self):
        res = run(["fit", self.case, "--body", "nosuch", "--eval", self.good_uv])
        self.assertOneLineError(res, "--body nosuch", contains=("nosuch",))

    def test_uv_missing_file(self):
        missing = os.path.join(self.dir, "no_such_uv.csv")
        res = run(["fit", self.case, "--eval", missing])
        self.assertOneLineError(res, "missing UV file", contains=("no_such_uv.csv",))

    def test_uv_bad_header(self):
        p = self.write(self.dir, "bad_header_uv.csv", "x,y\n0.5,0.5\n")
        res = run(["fit", self.case, "--eval", p])
        self.assertOneLineError(res, "UV bad header", contains=("bad_header_uv.csv",))

    def test_uv_not_a_number(self):
        p = self.write(self.dir, "nan_text_uv.csv", "u,v\n0.5,0.5\n0.25,abc\n")
        res = run(["fit", self.case, "--eval", p])
        line = self.assertOneLineError(res, "UV non-number", contains=("nan_text_uv.csv",))
        self.assertLineNumber(line, p, 3, "UV non-number")

    def test_uv_trailing_garbage(self):
        p = self.write(self.dir, "garbage_uv.csv", "u,v\n0.5,0.5x\n")
        res = run(["fit", self.case, "--eval", p])
        line = self.assertOneLineError(res, "UV trailing garbage", contains=("garbage_uv.csv",))
        self.assertLineNumber(line, p, 2, "UV trailing garbage")

    def test_uv_out_of_range(self):
        for name, text, lineno in [("above_uv.csv", "u,v\n1.5,0.5\n", 2),
                                   ("below_uv.csv", "u,v\n0.5,0.5\n0.2,0.1\n0.3,-0.25\n", 4),
                                   ("nan_uv.csv", "u,v\nnan,0.5\n", 2),
                                   ("inf_uv.csv", "u,v\n0.5,inf\n", 2)]:
            with self.subTest(uv=name):
                p = self.write(self.dir, name, text)
                res = run(["fit", self.case, "--eval", p])
                line = self.assertOneLineError(res, "UV out of range (%s)" % name, contains=(name,))
                self.assertLineNumber(line, p, lineno, "UV out of range (%s)" % name)

    def test_uv_wrong_column_count(self):
        for name, text in [("one_col_uv.csv", "u,v\n0.5\n"), ("three_col_uv.csv", "u,v\n0.5,0.5,0.5\n")]:
            with self.subTest(uv=name):
                p = self.write(self.dir, name, text)
                res = run(["fit", self.case, "--eval", p])
                line = self.assertOneLineError(res, "UV column count (%s)" % name, contains=(name,))
                self.assertLineNumber(line, p, 2, "UV column count (%s)" % name)

    # -- good calls -----------------------------------------------------------

    def test_fit_summary(self):
        res = run(["fit", self.case])
        self.assertNoCrash(res, "fit summary")
        self.assertEqual(res.returncode, 0, res.stderr)
        out = res.stdout
        for label in ("grid", "degrees", "knots u", "knots v", "residual", "memory", "time"):
            self.assertRegex(out, r"(?m)^%s\b" % label, "summary lacks its %r line:\n%s" % (label, out))
        # The residual at the data sites is round-off: every figure on those lines is tiny
        # next to the case's scale (positions ~1e-2 m, stiffness ~1e2 N/m).
        res_lines = out[out.index("residual"):out.index("memory")]
        figures = [float(x) for x in re.findall(r"(\d+(?:\.\d+)?e[-+]\d+|\b0\b)", res_lines)]
        self.assertTrue(figures, res_lines)
        self.assertLess(max(figures), 1e-10, res_lines)

    def test_fit_eval_csv_shape(self):
        for surface, header in [("skeleton", "u,v,x,y,z,radius,stiffness,damping,mass"),
                                ("top", "u,v,x,y,z"), ("bottom", "u,v,x,y,z")]:
            for body in ("b0", "b1"):
                with self.subTest(surface=surface, body=body):
                    res = run(["fit", self.case, "--body", body, "--surface", surface, "--eval", self.good_uv])
                    self.assertNoCrash(res, "fit --eval")
                    self.assertEqual(res.returncode, 0, res.stderr)
                    lines = [ln for ln in res.stdout.splitlines() if ln.strip()]
                    self.assertEqual(lines[0], header)
                    self.assertEqual(len(lines), 5)
                    want_uv = [(0.0, 0.0), (0.1, 0.3333333333333333), (1.0, 1.0), (0.5, 1.0)]
                    ncol = len(header.split(","))
                    for ln, (u, v) in zip(lines[1:], want_uv):
                        vals = [float(x) for x in ln.split(",")]
                        self.assertEqual(len(vals), ncol, ln)
                        # 17 significant digits round-trip every double exactly
                        self.assertEqual((vals[0], vals[1]), (u, v), ln)

    def test_fit_eval_header_only(self):
        p = self.write(self.dir, "header_only_uv.csv", "u,v\n")
        res = run(["fit", self.case, "--eval", p])
        self.assertNoCrash(res, "header-only UV")
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertEqual([ln for ln in res.stdout.splitlines() if ln.strip()],
                         ["u,v,x,y,z,radius,stiffness,damping,mass"])


class NumericOptions(unittest.TestCase):
    """Every numeric option refuses NaN, infinities, non-numbers and out-of-range values with
    one line naming the option and its range; the boundary values themselves are accepted."""

    assertNoCrash = CliBasics.assertNoCrash
    assertOneLineError = CliBasics.assertOneLineError
    write = staticmethod(CliBasics.write)

    @classmethod
    def setUpClass(cls):
        cls._tmp = tempfile.TemporaryDirectory(prefix="palpa_cli_numbers_")
        cls.dir = cls._tmp.name
        cls.case = os.path.join(cls.dir, "small_case.json")
        with open(cls.case, "w", encoding="utf-8") as fh:
            json.dump(small_case(), fh)

    @classmethod
    def tearDownClass(cls):
        cls._tmp.cleanup()

    # (arguments before the option, option, its range's text in --help, values outside it)
    CASES = (
        (["probe", "CASE", "--points", "POINTS"], "--max-force", "above 0, at most 1000 N", ["0", "1001"]),
        (["probe", "CASE", "--points", "POINTS"], "--shear-delta", "1e-06 to 0.5", ["0", "0.6"]),
        (["probe", "CASE", "--points", "POINTS"], "--bisect-levels", "1 to 40", ["0", "41", "2.5"]),
        (["simulate", "CASE", "--trajectory", "POINTS", "--out", "OUT"], "--rate", "10 to 100000 Hz", ["5"]),
        (["simulate", "CASE", "--device", "virtual", "--out", "OUT"], "--duration", "above 0, at most 86400 s",
         ["0", "1e6"]),
        (["exercise", "CASE", "--trainee", "t", "--out", "OUT"], "--seed", "2^64 - 1",
         ["-1", "18446744073709551616", "1.5", "1e3"]),
        (["batch", "POINTS", "--out", "OUT"], "--jobs", "1 to 1024", ["0", "1025"]),
        (["bench", "table1"], "--seconds", "0.1 to 600 s", ["0.01", "601"]),
    )

    def fill(self, args):
        points = self.write(self.dir, "points.csv", "x,y,z\n0.03,0.03,0.004\n")
        out = os.path.join(self.dir, "never-written.out")
        return [{"CASE": self.case, "POINTS": points, "OUT": out}.get(a, a) for a in args]

    def test_nan_infinity_and_out_of_range_are_refused_naming_the_option(self):
        for before, option, _, outside in self.CASES:
            for value in ["nan", "NaN", "inf", "-inf", "1e400", "", "3x"] + outside:
                with self.subTest(option=option, value=value):
                    res = run(self.fill(before) + [option, value])
                    line = self.assertOneLineError(res, "%s %r" % (option, value), contains=(option,))
                    self.assertTrue("finite" in line or "range" in line or "whole number" in line
                                    or "not a seed" in line, line)
                    self.assertNotRegex(line, r"\d{20,}e|e\+308", "a human-sized bound: " + line)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "never-written.out")))

    def test_the_range_is_in_the_help_text(self):
        for before, option, shown, _ in self.CASES:
            with self.subTest(option=option):
                res = run([before[0]] + ([before[1]] if before[0] == "bench" else []) + ["--help"])
                self.assertEqual(res.returncode, 0, res.stderr)
                help_line = [ln for ln in res.stdout.splitlines() if option in ln]
                self.assertTrue(help_line and shown in " ".join(res.stdout.split()), (option, help_line))

    def test_the_bounds_themselves_are_accepted(self):
        args = self.fill(["probe", "CASE", "--points", "POINTS"])
        for option, value in (("--max-force", "1000"), ("--shear-delta", "0.5"), ("--bisect-levels", "40")):
            with self.subTest(option=option):
                res = run(args + [option, value])
                self.assertEqual(res.returncode, 0, res.stderr)


def main():
    global CLI
    ap = argparse.ArgumentParser(description="palpa-cli basic behaviour")
    ap.add_argument("--cli", required=True, help="path to the palpa-cli binary")
    args, rest = ap.parse_known_args()
    CLI = os.path.abspath(args.cli)
    if not (os.path.isfile(CLI) and os.access(CLI, os.X_OK)):
        print("test_cli_basics: error: not an executable file: %s" % CLI, file=sys.stderr)
        return 2
    prog = unittest.main(argv=[sys.argv[0]] + rest, exit=False)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
