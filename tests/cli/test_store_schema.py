#!/usr/bin/python3
"""palpa-cli store init against a real PostgreSQL server (tests/tools/pg_test_server.py):
the schema is created once and init is idempotent, a newer schema is refused, the roles
keep a station to adding sessions and seeing its own, a failed connection is one line that
names host, port, database and user and never the password.

    /usr/bin/python3 tests/cli/test_store_schema.py --cli palpa-cli --repo REPO
"""
import argparse
import os
import re
import subprocess
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tools"))
import pg_test_server  # noqa: E402

CLI = REPO = None


def run(pg, *args, **extra_env):
    return subprocess.run([CLI, *args], capture_output=True, text=True, env=pg.env(**extra_env), timeout=120)


class Schema(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.pg = pg_test_server.server_for_tests()
        cls.pg.sql("CREATE DATABASE palpa")
        res = run(cls.pg, "store", "init", cls.pg.url("palpa"))
        assert res.returncode == 0, res.stderr
        cls.first_init = res.stdout
        for user, group in (("station_a", "palpa_station"), ("station_b", "palpa_station"),
                            ("coord", "palpa_coordinator"), ("worker", "palpa_worker")):
            cls.pg.add_login(user, group)
        cls.outbox = os.path.join(cls.pg.root, "outbox")

    @classmethod
    def tearDownClass(cls):
        cls.pg.close()

    def push(self, user, station, session):
        return run(self.pg, "store", "push", session, "--store", self.pg.url("palpa", user), "--station", station,
                   "--outbox", self.outbox)

    def test_init_creates_version_3_and_is_idempotent(self):
        self.assertIn("schema version 3 (was 0)", self.first_init)
        again = run(self.pg, "store", "init", self.pg.url("palpa"))
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertIn("already up to date", again.stdout)
        self.assertEqual(self.pg.sql("SELECT version FROM palpa_schema ORDER BY 1", "palpa").split(), ["1", "2", "3"])
        tables = set(self.pg.sql("SELECT tablename FROM pg_tables WHERE schemaname = 'public'", "palpa").split())
        self.assertTrue({"stations", "trainees", "cases", "sessions", "scores", "work_queue", "enrolments",
                         "claim_turns"} <= tables, tables)
        roles = self.pg.sql("SELECT rolname || ':' || rolcanlogin FROM pg_roles WHERE rolname LIKE 'palpa\\_%' "
                            "AND rolname <> 'palpa_admin' ORDER BY 1")
        self.assertEqual(roles.split(), ["palpa_coordinator:false", "palpa_owner:false", "palpa_station:false",
                                         "palpa_worker:false"])

    def test_a_newer_schema_is_refused(self):
        self.pg.sql("CREATE DATABASE newer")
        self.assertEqual(run(self.pg, "store", "init", self.pg.url("newer")).returncode, 0)
        self.pg.sql("INSERT INTO palpa_schema(version) VALUES (99)", "newer")
        res = run(self.pg, "store", "init", self.pg.url("newer"))
        self.assertEqual(res.returncode, 1)
        self.assertEqual(len(res.stderr.strip().splitlines()), 1, res.stderr)
        self.assertIn("schema version 99, newer than this Palpa knows (3)", res.stderr)
        self.assertEqual(self.pg.sql("SELECT max(version) FROM palpa_schema", "newer"), "99")

    def test_a_station_adds_sessions_and_sees_only_its_own(self):
        a = self.push("station_a", "room-a", os.path.join(REPO, "data", "sessions", "expert.palpa"))
        b = self.push("station_b", "room-b", os.path.join(REPO, "data", "sessions", "sloppy.palpa"))
        self.assertEqual((a.returncode, b.returncode), (0, 0), a.stderr + b.stderr)
        a_id = re.search(r"session (\w+)", a.stdout).group(1)
        # The tables themselves are closed to a station: SELECT fails.
        denied = self.pg.psql("SELECT session_id FROM sessions", "palpa", "station_b", check=False)
        self.assertNotEqual(denied.returncode, 0)
        self.assertIn("permission denied", denied.stderr)
        # Its view shows its own uploads only.
        self.assertEqual(self.pg.sql("SELECT count(*) FROM station_sessions WHERE session_id = '%s'" % a_id,
                                     "palpa", "station_b"), "0")
        self.assertEqual(self.pg.sql("SELECT station FROM station_sessions", "palpa", "station_b"), "room-b")
        self.assertEqual(self.pg.sql("SELECT count(*) FROM station_sessions WHERE session_id = '%s'" % a_id,
                                     "palpa", "station_a"), "1")
        for sql in ("INSERT INTO trainees(name) VALUES ('x')", "DELETE FROM sessions",
                    "INSERT INTO scores(session_id, scorer_version, thresholds_sha256, score, passed, result, worker) "
                    "VALUES (1, 'v', 'h', 1, true, '{}', 'me')"):
            self.assertNotEqual(self.pg.psql(sql, "palpa", "station_a", check=False).returncode, 0, sql)
        # The coordinator reads everything; a worker may not push.
        self.assertEqual(self.pg.sql("SELECT count(*) FROM sessions", "palpa", "coord"), "2")
        self.assertNotEqual(self.pg.psql("SELECT palpa_push_session(NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, "
                                         "NULL, NULL, NULL, NULL)", "palpa", "worker", check=False).returncode, 0)
        # A station name belongs to the login that first used it.
        stolen = self.push("station_b", "room-a", os.path.join(REPO, "data", "sessions", "light.palpa"))
        self.assertEqual(stolen.returncode, 2)
        self.assertIn('station "room-a" is registered to another login', stolen.stderr)
        self.assertNotIn("station_a", stolen.stderr)  # a refusal names no other login

    def test_a_failed_connection_is_one_line_without_the_password(self):
        closed = pg_test_server.free_port()
        url = "host=127.0.0.1 port=%d dbname=palpa user=someone password=hunter2-secret connect_timeout=5" % closed
        res = run(self.pg, "store", "init", url)
        self.assertEqual(res.returncode, 1)
        self.assertEqual(len(res.stderr.strip().splitlines()), 1, res.stderr)
        self.assertIn("store: cannot connect to 127.0.0.1:%d/palpa as someone: " % closed, res.stderr)
        self.assertNotIn("hunter2", res.stderr + res.stdout)
        wrong = run(self.pg, "store", "init", self.pg.url("palpa", "station_a") + " password=wrong-pass-123",
                    PGPASSFILE=os.devnull)
        self.assertEqual(wrong.returncode, 1)
        self.assertIn("store: cannot connect to 127.0.0.1:%d/palpa as station_a: " % self.pg.port, wrong.stderr)
        self.assertIn("password authentication failed", wrong.stderr)
        self.assertNotIn("wrong-pass-123", wrong.stderr)


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
