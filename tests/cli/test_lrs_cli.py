#!/usr/bin/env python3
"""palpa-cli's xAPI statements against a real learning record store.

Run: python3 tests/cli/test_lrs_cli.py --cli build/release/app/palpa-cli --repo . \
         --node-dir build/release/tests/xapi-node

The statements of the sample sessions are checked with Learning Locker's validator
(@learninglocker/xapi-validation) and sent to Learning Locker's xAPI statement service
(@learninglocker/xapi-statements) running in memory on loopback: both installed from the
npm registry with `npm ci` from tests/xapi/package-lock.json into --node-dir. Without
Node.js the test is skipped (exit 77) on a developer's machine and fails under CI=true.
"""
import argparse
import base64
import hashlib
import json
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time
import unittest
import urllib.request

CLI = None
REPO = None
NODE_DIR = None
TIMEOUT = 120
SESSIONS = ("expert", "sloppy", "light")
HOME_PAGE = "https://sim.example-hospital.org"


def node_modules():
    return os.path.join(NODE_DIR, "node_modules")


def install_node_packages():
    """npm ci into NODE_DIR unless the lock file installed there is the same."""
    source = os.path.join(REPO, "tests", "xapi")
    with open(os.path.join(source, "package-lock.json"), "rb") as f:
        digest = hashlib.sha256(f.read()).hexdigest()
    stamp = os.path.join(NODE_DIR, "installed-lock.sha256")
    if os.path.exists(stamp) and open(stamp).read() == digest and os.path.isdir(node_modules()):
        return
    os.makedirs(NODE_DIR, exist_ok=True)
    for name in ("package.json", "package-lock.json"):
        shutil.copy(os.path.join(source, name), os.path.join(NODE_DIR, name))
    subprocess.run(["npm", "ci", "--no-audit", "--no-fund", "--loglevel=error"], cwd=NODE_DIR, check=True,
                   timeout=600, stdout=subprocess.DEVNULL)
    with open(stamp, "w") as f:
        f.write(digest)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class LocalLrs:
    """Learning Locker's xAPI statement service, in memory, on 127.0.0.1 (a real LRS:
    it validates every statement it is sent and answers as the xAPI spec says)."""

    def __init__(self, port):
        self.port = port
        self.endpoint = f"http://127.0.0.1:{port}/xAPI"
        self.process = None

    def start(self, log_dir):
        env = dict(os.environ, AUTH_REPO="test", EVENTS_REPO="test", MODELS_REPO="memory", STORAGE_REPO="memory",
                   EXPRESS_PORT=str(self.port), WINSTON_CONSOLE_LEVEL="error")
        server = os.path.join(node_modules(), "@learninglocker", "xapi-statements", "dist", "server.js")
        self.log = open(os.path.join(log_dir, f"lrs-{self.port}-{time.time_ns()}.log"), "w")
        self.process = subprocess.Popen(["node", server], env=env, cwd=log_dir, stdout=self.log, stderr=self.log)
        deadline = time.time() + 60
        while time.time() < deadline:
            try:
                with urllib.request.urlopen(self.endpoint + "/about", timeout=2) as r:
                    if r.status == 200:
                        return
            except OSError:
                time.sleep(0.2)
        raise RuntimeError("the local LRS did not start")

    def stop(self):
        if self.process:
            self.process.terminate()
            self.process.wait(timeout=30)
            self.process = None
            self.log.close()

    def get(self, query):
        request = urllib.request.Request(self.endpoint + "/statements?" + query, headers={
            "X-Experience-API-Version": "1.0.3",
            "Authorization": "Basic " + base64.b64encode(b"key:secret").decode()})
        with urllib.request.urlopen(request, timeout=10) as r:
            return json.loads(r.read())


def run(args, env, timeout=TIMEOUT):
    return subprocess.run([CLI] + args, capture_output=True, text=True, timeout=timeout, env=env)


def validate(files):
    env = dict(os.environ, NODE_PATH=node_modules())
    return subprocess.run(["node", os.path.join(REPO, "tests", "xapi", "validate.js")] + files, capture_output=True,
                          text=True, timeout=TIMEOUT, env=env)


class Lrs(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="palpa_lrs_")
        home = os.path.join(cls.tmp.name, "home")
        os.makedirs(home)
        with open(os.path.join(home, ".netrc"), "w") as f:
            f.write("machine 127.0.0.1 login key password secret\n")
        os.chmod(os.path.join(home, ".netrc"), 0o600)
        cls.env = {k: v for k, v in os.environ.items() if not k.startswith(("PALPA_", "XDG_"))}
        cls.env.update(HOME=home, PALPA_XAPI_HOME_PAGE=HOME_PAGE)
        cls.outbox = os.path.join(home, ".local", "share", "palpa", "xapi-outbox")
        cls.lrs = LocalLrs(free_port())
        cls.lrs.start(cls.tmp.name)
        cls.reports = os.path.join(cls.tmp.name, "reports")
        for name in SESSIONS:
            res = run(["score", os.path.join(REPO, "data", "sessions", name + ".palpa"), "--report", cls.reports],
                      cls.env)
            assert res.returncode == 0, res.stderr

    @classmethod
    def tearDownClass(cls):
        cls.lrs.stop()
        cls.tmp.cleanup()

    def statement_files(self):
        return [os.path.join(self.reports, n + ".xapi.json") for n in SESSIONS]

    def status(self):
        res = run(["lrs", "status"], self.env)
        self.assertEqual(res.returncode, 0, res.stderr)
        return res.stdout

    def test_1_statements_pass_learning_lockers_validator(self):
        res = validate(self.statement_files())
        self.assertEqual(res.returncode, 0, res.stdout + res.stderr)
        self.assertEqual(res.stdout.count(": ok"), 3, res.stdout)

    def test_1_the_validator_can_fail(self):
        broken = json.load(open(self.statement_files()[0]))
        del broken["actor"]["account"]["homePage"]
        broken["result"]["score"]["scaled"] = 3
        path = os.path.join(self.tmp.name, "broken.xapi.json")
        json.dump(broken, open(path, "w"))
        res = validate([path])
        self.assertEqual(res.returncode, 1, res.stdout)
        self.assertIn("homePage", res.stdout)
        self.assertIn("scaled", res.stdout)

    def test_1_the_actor_is_an_account_on_the_configured_home_page(self):
        for f in self.statement_files():
            actor = json.load(open(f))["actor"]
            self.assertEqual(actor["objectType"], "Agent")
            self.assertEqual(actor["account"]["homePage"], HOME_PAGE)
            self.assertTrue(actor["account"]["name"].startswith("sample-"))

    def test_2_sent_statements_are_in_the_lrs_once_even_when_sent_twice(self):
        for _ in range(2):
            res = run(["lrs", "send", *self.statement_files(), "--lrs", self.lrs.endpoint], self.env)
            self.assertEqual(res.returncode, 0, res.stderr)
            self.assertIn("3 sent", res.stderr)
        self.assertIn("0 waiting, 0 rejected", self.status())
        for f in self.statement_files():
            sent = json.load(open(f))
            stored = self.lrs.get("statementId=" + sent["id"])
            self.assertEqual(stored["actor"], sent["actor"])
            self.assertEqual(stored["result"]["score"], sent["result"]["score"])
        everything = self.lrs.get("limit=100")["statements"]
        ids = [s["id"] for s in everything]
        self.assertEqual(sorted(ids), sorted(set(ids)))

    def test_3_a_statement_waits_while_the_lrs_is_down_and_goes_when_it_is_back(self):
        self.lrs.stop()
        try:
            res = run(["lrs", "send", self.statement_files()[1], "--lrs", self.lrs.endpoint, "--attempts", "2"],
                      self.env)
            self.assertEqual(res.returncode, 3, res.stderr)
            self.assertIn("1 waiting", res.stderr)
            status = self.status()
            self.assertIn("waiting", status)
            self.assertIn("trainee=sample-sloppy", status)
            self.assertIn("1 waiting, 0 rejected", status)
        finally:
            self.lrs.start(self.tmp.name)  # a fresh, empty LRS
        res = run(["lrs", "flush", "--lrs", self.lrs.endpoint], self.env)
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertIn("0 waiting, 0 rejected", self.status())
        sent = json.load(open(self.statement_files()[1]))
        self.assertEqual(self.lrs.get("statementId=" + sent["id"])["id"], sent["id"])

    def test_4_a_statement_the_lrs_refuses_is_kept_aside_with_the_reason(self):
        broken = json.load(open(self.statement_files()[2]))
        broken["id"] = "11111111-2222-4333-8444-555555555555"
        broken["result"]["score"]["scaled"] = 3
        path = os.path.join(self.tmp.name, "refused.xapi.json")
        json.dump(broken, open(path, "w"))
        res = run(["lrs", "send", path, "--lrs", self.lrs.endpoint], self.env)
        self.assertEqual(res.returncode, 2, res.stderr)
        self.assertEqual(len(res.stderr.strip().splitlines()), 1, res.stderr)
        self.assertIn("rejected", res.stderr)
        self.assertIn("HTTP 400", res.stderr)
        self.assertTrue(os.path.exists(os.path.join(self.outbox, "rejected", broken["id"] + ".json")))
        self.assertIn("rejected " + broken["id"], self.status())

    def test_5_bad_input_is_one_line_naming_the_file(self):
        path = os.path.join(self.tmp.name, "not-json.xapi.json")
        open(path, "w").write("{")
        res = run(["lrs", "send", path, "--lrs", self.lrs.endpoint], self.env)
        self.assertEqual(res.returncode, 2)
        self.assertEqual(res.stderr.strip(), f"palpa-cli: error: {path}: not a JSON xAPI statement")
        res = run(["lrs", "flush"], self.env)
        self.assertEqual(res.returncode, 2)
        self.assertIn("no learning record store configured", res.stderr)

    def test_5_credentials_in_the_endpoint_never_reach_the_output(self):
        endpoint = self.lrs.endpoint.replace("http://", "http://key:topsecret@")
        res = run(["lrs", "send", self.statement_files()[0], "--lrs", endpoint], self.env)
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertNotIn("topsecret", res.stdout + res.stderr)

    def test_6_score_with_lrs_sends_the_sessions_statement(self):
        session = os.path.join(REPO, "data", "sessions", "light.palpa")
        res = run(["score", session, "--lrs", self.lrs.endpoint], self.env)
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertIn("lrs: 1 sent", res.stderr)
        sent = json.load(open(self.statement_files()[2]))  # the same statement id: uuid5 of the session id
        stored = self.lrs.get("statementId=" + sent["id"])
        self.assertEqual(stored["actor"]["account"], {"homePage": HOME_PAGE, "name": sent["actor"]["account"]["name"]})
        self.assertEqual(stored["verb"]["id"], sent["verb"]["id"])


def main():
    global CLI, REPO, NODE_DIR
    parser = argparse.ArgumentParser()
    parser.add_argument("--cli", required=True)
    parser.add_argument("--repo", required=True)
    parser.add_argument("--node-dir", required=True)
    args, rest = parser.parse_known_args()
    CLI, REPO, NODE_DIR = os.path.abspath(args.cli), os.path.abspath(args.repo), os.path.abspath(args.node_dir)
    if not (shutil.which("node") and shutil.which("npm")):
        if os.environ.get("CI"):
            print("cli.lrs: Node.js and npm are needed (the validator and the local LRS come from npm)")
            return 1
        print("cli.lrs: skipped: Node.js or npm not installed")
        return 77
    install_node_packages()
    result = unittest.main(argv=[sys.argv[0]] + rest, exit=False).result
    return 0 if result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
