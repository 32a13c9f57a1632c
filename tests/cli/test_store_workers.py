#!/usr/bin/python3
"""palpa-cli batch --store URL --worker: three worker processes score one store's sessions
while one of them is killed with SIGKILL mid-run. Its lease expires and another worker
takes the session over: every session ends scored exactly once, and each stored score is
the one palpa-cli score FILE --json gives for the file.

    /usr/bin/python3 tests/cli/test_store_workers.py --cli palpa-cli --repo REPO
"""
import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tools"))
import pg_test_server  # noqa: E402

CLI = REPO = None
COUNT = 15
LEASE_S = 3


def make_corpus(folder, count):
    bases = [os.path.join(REPO, "data", "sessions", n + ".palpa") for n in ("expert", "sloppy", "light")]
    subprocess.run([sys.executable, os.path.join(REPO, "tests", "tools", "make_batch_corpus.py"), *bases,
                    "--out", folder, "--count", str(count), "--trainees", "4", "--corrupt", "0"], check=True)
    return sorted(os.path.join(folder, n) for n in os.listdir(folder) if n.endswith(".palpa") and n[0] != ".")


def local_score(path):
    res = subprocess.run([CLI, "score", path, "--json"], capture_output=True, text=True, check=True)
    j = json.loads(res.stdout)
    return j.pop("session")["id"], j


class Workers(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.pg = pg_test_server.server_for_tests()
        cls.dir = tempfile.mkdtemp(prefix="palpa-workers-")
        cls.pg.sql("CREATE DATABASE palpa")
        subprocess.run([CLI, "store", "init", cls.pg.url("palpa")], check=True, capture_output=True, env=cls.pg.env())
        cls.pg.add_login("station", "palpa_station")
        cls.pg.add_login("worker", "palpa_worker")
        cls.files = make_corpus(os.path.join(cls.dir, "corpus"), COUNT)
        push = subprocess.run([CLI, "store", "push", *cls.files, "--store", cls.pg.url("palpa", "station"),
                               "--station", "room-1", "--outbox", os.path.join(cls.dir, "outbox")],
                              capture_output=True, text=True, env=cls.pg.env())
        assert push.returncode == 0, push.stderr

    @classmethod
    def tearDownClass(cls):
        cls.pg.close()
        shutil.rmtree(cls.dir, ignore_errors=True)

    def start_worker(self):
        return subprocess.Popen([CLI, "batch", "--store", self.pg.url("palpa", "worker"), "--worker", "--jobs", "1",
                                 "--lease", str(LEASE_S)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                env=self.pg.env())

    def holding(self, pid):
        return self.pg.sql("SELECT count(*) FROM work_queue WHERE NOT done AND lease_owner LIKE '%%:%d:%%'" % pid,
                           "palpa")

    def test_a_killed_worker_leaves_every_session_scored_exactly_once(self):
        victim = self.start_worker()
        first = victim.stdout.readline()
        self.assertTrue(first.startswith("scored: "), first)
        others = [self.start_worker(), self.start_worker()]
        # Killed while it holds the lease of its next session (mid-run, not between two).
        deadline = time.monotonic() + 10
        while self.holding(victim.pid) != "1" and time.monotonic() < deadline:
            time.sleep(0.01)
        victim.send_signal(signal.SIGKILL)
        rest, _ = victim.communicate()
        victim_scored = 1 + sum(line.startswith("scored: ") for line in rest.splitlines())
        self.assertEqual(self.holding(victim.pid), "1", "the killed worker held no lease")
        started = time.monotonic()
        outputs = [w.communicate(timeout=300) for w in others]
        for w, (out, err) in zip(others, outputs):
            self.assertEqual(w.returncode, 0, err)
        self.assertLess(time.monotonic() - started, 120)
        rows = self.pg.sql("SELECT s.session_id || ' ' || count(sc.id) FROM sessions s "
                           "LEFT JOIN scores sc ON sc.session_id = s.id GROUP BY s.session_id", "palpa").splitlines()
        self.assertEqual(len(rows), COUNT)
        self.assertEqual({r.split()[1] for r in rows}, {"1"}, rows)
        self.assertEqual(self.pg.sql("SELECT count(*) FROM work_queue WHERE NOT done OR last_error IS NOT NULL",
                                     "palpa"), "0")
        # The session the victim held was taken over once its lease expired (on a loaded
        # machine a slow survivor's lease may lapse too and be taken over: still scored once).
        self.assertGreaterEqual(int(self.pg.sql("SELECT count(*) FROM work_queue WHERE attempts >= 2", "palpa")), 1)
        self.assertEqual(self.pg.sql("SELECT count(*) FROM scores WHERE worker LIKE '%%:%d:%%'" % victim.pid, "palpa"),
                         str(victim_scored))
        stored = {}
        for line in self.pg.sql("SELECT s.session_id || ' ' || sc.result::text FROM scores sc "
                                "JOIN sessions s ON s.id = sc.session_id", "palpa").splitlines():
            session_id, result = line.split(" ", 1)
            stored[session_id] = json.loads(result)
        workers = set(self.pg.sql("SELECT DISTINCT split_part(worker, ':', 2) FROM scores", "palpa").split())
        self.assertTrue(workers <= {str(victim.pid)} | {str(w.pid) for w in others}, workers)
        for path in self.files:
            session_id, expected = local_score(path)
            self.assertEqual(stored[session_id], expected, path)


def main():
    global CLI, REPO
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--repo", required=True)
    args, rest = ap.parse_known_args()
    CLI, REPO = os.path.abspath(args.cli), os.path.abspath(args.repo)
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)


if __name__ == "__main__":
    main()
