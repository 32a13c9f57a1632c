#!/usr/bin/env python3
"""The Debian package, end to end: cpack builds it from the already built tree into a
temporary folder, dpkg-deb unpacks it into a scratch root, and the installed programs run
from there with the installed data (never the source tree).

Run: python3 tests/packaging/test_deb.py --build-dir build/release --source-dir . --version 0.1.0

The truths: the file list the install layout promises (docs/install.md), the version of
project() in the package name, its control fields and --version, the Depends that
dpkg-shlibdeps derives from the binaries, an exercise run by the installed palpa-cli on
the installed default case found relative to the binary, and a postinst that never fails.
With PALPA_TEST_APT_INSTALL=1 as root it also installs the package with apt-get.
"""
import argparse
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET

ARGS = None
SKIP = 77  # ctest SKIP_RETURN_CODE


def run(cmd, timeout=300, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, **kw)


def clean_env():
    """The environment of a user who has only the package: no PALPA_DATA_DIR, no display."""
    env = dict(os.environ)
    for name in ("PALPA_DATA_DIR", "DISPLAY", "WAYLAND_DISPLAY"):
        env.pop(name, None)
    return env


class Deb(unittest.TestCase):
    tmp = None

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="palpa_deb_")
        cls.out = os.path.join(cls.tmp.name, "cpack")
        res = run([ARGS.cpack, "-G", "DEB", "-B", cls.out, "--config",
                   os.path.join(ARGS.build_dir, "CPackConfig.cmake")], timeout=600, cwd=cls.tmp.name)
        if res.returncode != 0:
            raise AssertionError("cpack failed:\n" + res.stdout + res.stderr)
        debs = glob.glob(os.path.join(cls.out, "*.deb"))
        if len(debs) != 1:
            raise AssertionError("expected one .deb in %s, found %s" % (cls.out, debs))
        cls.deb = debs[0]
        cls.arch = run(["dpkg", "--print-architecture"]).stdout.strip()
        cls.root = os.path.join(cls.tmp.name, "root")
        subprocess.run(["dpkg-deb", "-x", cls.deb, cls.root], check=True)
        cls.control = os.path.join(cls.tmp.name, "control")
        subprocess.run(["dpkg-deb", "-e", cls.deb, cls.control], check=True)
        cls.work = os.path.join(cls.tmp.name, "work")  # cwd of every run: outside the source tree
        os.mkdir(cls.work)
        print("package %s: %d bytes" % (os.path.basename(cls.deb), os.path.getsize(cls.deb)), file=sys.stderr)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def field(self, name):
        return run(["dpkg-deb", "-f", self.deb, name]).stdout.strip()

    def installed(self, *parts):
        return os.path.join(self.root, "usr", *parts)

    def test_file_name_and_control_fields(self):
        self.assertEqual(os.path.basename(self.deb), "palpa_%s_%s.deb" % (ARGS.version, self.arch))
        self.assertEqual(self.field("Package"), "palpa")
        self.assertEqual(self.field("Version"), ARGS.version)
        self.assertEqual(self.field("Architecture"), self.arch)
        self.assertEqual(self.field("Section"), "science")
        self.assertRegex(self.field("Maintainer"), r".+ <.+@.+>")
        self.assertTrue(self.field("Description").startswith("palpation trainer"))

    def test_depends_come_from_the_binaries(self):
        # dpkg-shlibdeps: one entry per shared library package the binaries load.
        names = {d.strip().split(" ")[0] for d in self.field("Depends").split(",")}
        expected = ["libc6", "libstdc++6", "libopencv-imgcodecs", "libsqlite3-0", "libhidapi-hidraw0", "libusb-1.0-0",
                    "libfmt", "libpq5"]
        if not ARGS.no_gui:
            expected += ["libqt5widgets5", "libvtk9"]
        for prefix in expected:
            self.assertTrue(any(n.startswith(prefix) for n in names), "%s not in Depends: %s" % (prefix, names))

    def test_file_list(self):
        expected = [
            "bin/palpa-cli",
            "share/palpa/schema/palpa-case.schema.json",
            "share/palpa/reference/slab40_E5k_flat_neohooke.csv", "share/palpa/reference/README.md",
            "share/applications/palpa.desktop",
            "share/icons/hicolor/scalable/apps/palpa.svg",
            "lib/udev/rules.d/70-palpa.rules",
            "share/doc/palpa/README.md",
            "share/doc/palpa/copyright", "share/doc/palpa/LICENSE",
            "share/doc/palpa/docs/images/trainee.png",
            "include/palpa/version.hpp", "include/palpa/io/case_file.hpp", "include/palpa/io/data_paths.hpp",
            "lib/libpalpa_core.a",
            "lib/cmake/Palpa/PalpaConfig.cmake", "lib/cmake/Palpa/PalpaConfigVersion.cmake",
            "lib/cmake/Palpa/PalpaTargets.cmake",
        ]
        if not ARGS.no_gui:
            expected.append("bin/palpa")
        cases = sorted(os.path.basename(p) for p in glob.glob(os.path.join(ARGS.source_dir, "data", "cases", "*.json")))
        self.assertIn("default.json", cases)
        expected += ["share/palpa/cases/" + c for c in cases]
        expected += ["share/doc/palpa/docs/" + os.path.basename(p)
                     for p in glob.glob(os.path.join(ARGS.source_dir, "docs", "*.md"))]
        for rel in expected:
            self.assertTrue(os.path.isfile(self.installed(rel)), "missing in the package: /usr/" + rel)
        for rel in ("bin/palpa-cli",) + (() if ARGS.no_gui else ("bin/palpa",)):
            self.assertTrue(os.access(self.installed(rel), os.X_OK), rel + " is not executable")
        # Everything lives under /usr, and only cases (not the script that makes them) are data.
        self.assertEqual(sorted(os.listdir(self.root)), ["usr"])
        self.assertEqual(sorted(os.listdir(self.installed("share", "palpa", "cases"))), cases)
        # The rules are the reviewed file, unchanged.
        with open(self.installed("lib", "udev", "rules.d", "70-palpa.rules")) as a, \
                open(os.path.join(ARGS.source_dir, "packaging", "udev", "70-palpa.rules")) as b:
            self.assertEqual(a.read(), b.read())

    def test_version_of_both_programs(self):
        for program in ("palpa-cli",) + (() if ARGS.no_gui else ("palpa",)):
            res = run([self.installed("bin", program), "--version"], env=clean_env(), cwd=self.work)
            self.assertEqual(res.returncode, 0, res.stderr)
            self.assertEqual(res.stdout.strip(), "%s %s" % (program, ARGS.version))

    def test_gui_help_runs_without_a_display(self):
        if ARGS.no_gui:
            self.skipTest("built without the GUI (PALPA_BUILD_GUI=OFF)")
        res = run([self.installed("bin", "palpa"), "--help"], env=clean_env(), cwd=self.work)
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertIn("--mode", res.stdout)
        self.assertIn("bundled", res.stdout)

    def test_exercise_with_the_installed_default_case(self):
        session = os.path.join(self.work, "ci.palpa")
        res = run([self.installed("bin", "palpa-cli"), "exercise", "default", "--trainee", "ci", "--seed", "7",
                   "--out", session, "--json"], env=clean_env(), cwd=self.work)
        self.assertEqual(res.returncode, 0, res.stderr)
        # Found relative to the binary: <root>/usr/bin/../share/palpa.
        self.assertIn("palpated " + self.installed("share", "palpa", "cases", "default.json"), res.stderr)
        self.assertNotIn(os.path.realpath(ARGS.source_dir), res.stderr)
        report = json.loads(res.stdout)
        self.assertEqual(report["session"]["trainee"], "ci")
        self.assertEqual(report["session"]["software_version"], ARGS.version)
        self.assertEqual(report["session"]["case_source"], self.installed("share", "palpa", "cases", "default.json"))
        # The expert scripted trainee finds the default case's one tumour (docs/scoring.md).
        self.assertEqual(report["sensitivity"], 1.0)
        self.assertTrue(report["passed"])
        self.assertTrue(os.path.getsize(session) > 0)
        # The installed palpa-cli scores its own session again to the same result.
        again = run([self.installed("bin", "palpa-cli"), "score", session, "--json"], env=clean_env(), cwd=self.work)
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertEqual(json.loads(again.stdout), report)

    def test_installed_program_never_reads_the_source_tree(self):
        # Without its share/palpa, the installed palpa-cli says where it looked; the source
        # tree's data/ (which exists) is not among the places.
        share = self.installed("share", "palpa")
        os.rename(share, share + ".away")
        try:
            res = run([self.installed("bin", "palpa-cli"), "exercise", "default", "--trainee", "ci",
                       "--out", os.path.join(self.work, "never.palpa")], env=clean_env(), cwd=self.work)
        finally:
            os.rename(share + ".away", share)
        self.assertEqual(res.returncode, 2, res.stderr)
        self.assertEqual(len(res.stderr.strip().splitlines()), 1, res.stderr)
        self.assertIn(share, res.stderr)
        self.assertNotIn(os.path.realpath(os.path.join(ARGS.source_dir, "data")), res.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.work, "never.palpa")))

    def test_data_dir_from_the_environment(self):
        env = clean_env()
        env["PALPA_DATA_DIR"] = os.path.join(self.work, "nowhere")
        res = run([self.installed("bin", "palpa-cli"), "exercise", "default", "--trainee", "ci",
                   "--out", os.path.join(self.work, "never.palpa")], env=env, cwd=self.work)
        self.assertEqual(res.returncode, 2, res.stderr)
        self.assertIn("PALPA_DATA_DIR=" + env["PALPA_DATA_DIR"], res.stderr)

    def test_desktop_entry_and_icon(self):
        entry = {}
        with open(self.installed("share", "applications", "palpa.desktop")) as fh:
            for line in fh:
                if "=" in line:
                    key, value = line.rstrip("\n").split("=", 1)
                    entry[key] = value
        self.assertEqual(entry["Type"], "Application")
        self.assertEqual(entry["Exec"], "palpa")  # the installed binary's name, on PATH
        self.assertEqual(entry["Icon"], "palpa")  # the installed icon's name
        self.assertEqual(entry["Categories"], "Education;MedicalSoftware;")
        root = ET.parse(self.installed("share", "icons", "hicolor", "scalable", "apps", "palpa.svg")).getroot()
        self.assertEqual(root.tag, "{http://www.w3.org/2000/svg}svg")
        validator = shutil.which("desktop-file-validate")
        if not validator:
            self.skipTest("desktop-file-validate is not installed (desktop-file-utils); the entry's fields were "
                          "checked by hand")
        res = run([validator, self.installed("share", "applications", "palpa.desktop")])
        self.assertEqual(res.returncode, 0, res.stdout + res.stderr)
        # One main category (Education), so the menu lists Palpa once: no error, warning or hint.
        problems = [line for line in res.stdout.splitlines()
                    if ": error: " in line or ": warning: " in line or ": hint: " in line]
        self.assertEqual(problems, [], res.stdout)

    def test_postinst_and_postrm_never_fail(self):
        for script in ("postinst", "postrm"):
            path = os.path.join(self.control, script)
            self.assertEqual(os.stat(path).st_mode & 0o777, 0o755, script)
        # A udevadm that fails (no running udev: a container, a chroot) and none at all.
        stubs = os.path.join(self.tmp.name, "stubs")
        os.makedirs(stubs, exist_ok=True)
        calls = os.path.join(self.tmp.name, "udevadm.calls")
        with open(os.path.join(stubs, "udevadm"), "w") as fh:
            fh.write('#!/bin/sh\necho "$@" >> "%s"\nexit 1\n' % calls)
        os.chmod(os.path.join(stubs, "udevadm"), 0o755)
        for path_env in (stubs, os.path.join(self.tmp.name, "empty")):
            env = {"PATH": path_env}
            res = run(["/bin/sh", os.path.join(self.control, "postinst"), "configure"], env=env)
            self.assertEqual(res.returncode, 0, res.stderr)
            res = run(["/bin/sh", os.path.join(self.control, "postrm"), "remove"], env=env)
            self.assertEqual(res.returncode, 0, res.stderr)
        with open(calls) as fh:
            lines = fh.read().splitlines()
        self.assertIn("control --reload-rules", lines)
        self.assertTrue(any(line.startswith("trigger") for line in lines), lines)

    def test_apt_install_on_this_system(self):
        if os.environ.get("PALPA_TEST_APT_INSTALL") != "1" or os.geteuid() != 0:
            self.skipTest("set PALPA_TEST_APT_INSTALL=1 and run as root to install the package with apt-get")
        env = clean_env()
        env["DEBIAN_FRONTEND"] = "noninteractive"
        res = run(["apt-get", "install", "-y", "-o", "DPkg::Lock::Timeout=600", "./" + os.path.basename(self.deb)],
                  timeout=1800, env=env, cwd=self.out)
        self.assertEqual(res.returncode, 0, res.stdout + res.stderr)
        res = run(["/usr/bin/palpa-cli", "exercise", "default", "--trainee", "apt", "--seed", "1",
                   "--out", os.path.join(self.work, "apt.palpa")], env=clean_env(), cwd=self.work)
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertIn("palpated /usr/share/palpa/cases/default.json", res.stderr)


def main():
    global ARGS
    p = argparse.ArgumentParser()
    p.add_argument("--build-dir", required=True)
    p.add_argument("--source-dir", required=True)
    p.add_argument("--version", required=True)
    p.add_argument("--cpack", default="cpack")
    p.add_argument("--sanitized", action="store_true")
    p.add_argument("--no-gui", action="store_true", help="the tree was configured with PALPA_BUILD_GUI=OFF")
    ARGS, rest = p.parse_known_args()
    ARGS.build_dir = os.path.abspath(ARGS.build_dir)
    ARGS.source_dir = os.path.abspath(ARGS.source_dir)
    if ARGS.sanitized:
        print("SKIP: packaging tests run in the release build (a package of ASan binaries is not one anybody "
              "installs); run ctest --preset release -R packaging")
        return SKIP
    for tool in ("dpkg-deb", "dpkg-shlibdeps"):
        if not shutil.which(tool):
            print("SKIP: %s is not installed (dpkg-dev)" % tool)
            return SKIP
    prog = unittest.main(argv=[sys.argv[0]] + rest, exit=False, verbosity=2)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
