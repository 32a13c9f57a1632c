#!/usr/bin/python3
"""palpa-cli store push and status against a real PostgreSQL server: a session is stored
once (pushing it again says "already stored"), with the SHA-256 of its bytes; an incomplete
session is refused; with the server unreachable the session is copied into the outbox
(the station's file untouched), status lists it, and push --outbox-only uploads it and
empties the outbox; the store is found through PALPA_STORE or the config file.

    /usr/bin/python3 tests/cli/test_store_push.py --cli palpa-cli --repo REPO
"""
import argparse
import hashlib
import json
import os
import resource
import shutil
import signal
import sqlite3
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tools"))
import pg_test_server  # noqa: E402

CLI = REPO = None


def sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


class Push(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.pg = pg_test_server.server_for_tests()
        cls.pg.sql("CREATE DATABASE palpa")
        init = subprocess.run([CLI, "store", "init", cls.pg.url("palpa")], capture_output=True, text=True,
                              env=cls.pg.env())
        assert init.returncode == 0, init.stderr
        cls.pg.add_login("station_a", "palpa_station")
        cls.url = cls.pg.url("palpa", "station_a")

    @classmethod
    def tearDownClass(cls):
        cls.pg.close()

    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="palpa-push-")
        self.outbox = os.path.join(self.dir, "outbox")
        self.home = os.path.join(self.dir, "home")
        os.makedirs(self.home)

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def cli(self, *args, **env):
        # HOME and XDG_* point into the test folder: no user's config or outbox is read.
        env = dict({"HOME": self.home, "XDG_CONFIG_HOME": os.path.join(self.home, ".config"),
                    "XDG_DATA_HOME": os.path.join(self.home, ".local", "share")}, **env)
        return subprocess.run([CLI, *args], capture_output=True, text=True, env=self.pg.env(**env), timeout=120)

    def session_copy(self, name, new_id):
        path = os.path.join(self.dir, name)
        shutil.copyfile(os.path.join(REPO, "data", "sessions", "light.palpa"), path)
        db = sqlite3.connect(path)
        db.execute("UPDATE meta SET value = ? WHERE key = 'id'", (new_id,))
        db.commit()
        db.close()
        return path

    def stored(self, session_id):
        return self.pg.sql("SELECT sha256 || ' ' || size_bytes || ' ' || file_name || ' ' || station FROM sessions "
                           "WHERE session_id = '%s'" % session_id, "palpa")

    def test_push_twice_stores_once_with_the_file_checksum(self):
        path = self.session_copy("twice.palpa", "a0" * 16)
        first = self.cli("store", "push", path, "--store", self.url, "--station", "room-1", "--outbox", self.outbox)
        self.assertEqual(first.returncode, 0, first.stderr)
        self.assertIn("stored: " + path, first.stdout)
        second = self.cli("store", "push", path, "--store", self.url, "--station", "room-1", "--outbox", self.outbox)
        self.assertEqual(second.returncode, 0, second.stderr)
        self.assertIn("already stored: " + path, second.stdout)
        self.assertEqual(self.stored("a0" * 16), "%s %d twice.palpa room-1" % (sha256(path), os.path.getsize(path)))
        self.assertEqual(self.pg.sql("SELECT count(*) FROM sessions WHERE session_id = '%s'" % ("a0" * 16), "palpa"), "1")
        self.assertEqual(self.pg.sql("SELECT count(*) FROM work_queue w JOIN sessions s ON s.id = w.session_id "
                                     "WHERE s.session_id = '%s' AND NOT w.done" % ("a0" * 16), "palpa"), "1")
        self.assertFalse(os.path.exists(self.outbox))

    def test_a_full_disk_queues_nothing_and_leaves_no_partial_file(self):
        # RLIMIT_FSIZE stands for a full disk: writes past 64 kB fail (EFBIG, SIGXFSZ ignored).
        path = self.session_copy("full.palpa", "f5" * 16)
        down = "host=127.0.0.1 port=%d dbname=palpa user=station_a connect_timeout=5" % pg_test_server.free_port()

        def small_files():
            signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
            resource.setrlimit(resource.RLIMIT_FSIZE, (65536, 65536))

        res = subprocess.run([CLI, "store", "push", path, "--store", down, "--station", "room-2", "--outbox", self.outbox],
                             capture_output=True, text=True, env=self.pg.env(HOME=self.home), timeout=120,
                             preexec_fn=small_files)
        self.assertEqual(res.returncode, 1, res.stderr)
        self.assertEqual(len(res.stderr.strip().splitlines()), 1, res.stderr)
        self.assertIn(path + ": not pushed and not queued:", res.stderr)
        self.assertNotIn("queued: ", res.stdout)
        self.assertEqual(os.listdir(self.outbox), [])  # no copy, no record, no temporary file
        self.assertEqual(os.path.getsize(path), os.path.getsize(os.path.join(REPO, "data", "sessions", "light.palpa")))

    def test_an_incomplete_session_is_refused(self):
        path = self.session_copy("cut.palpa", "b1" * 16)
        db = sqlite3.connect(path)
        db.execute("DELETE FROM events WHERE kind = 'end'")
        db.commit()
        db.close()
        res = self.cli("store", "push", path, "--store", self.url, "--station", "room-1", "--outbox", self.outbox)
        self.assertEqual(res.returncode, 2)
        self.assertIn(path + ": session incomplete", res.stderr)
        self.assertEqual(self.stored("b1" * 16), "")
        self.assertFalse(os.path.exists(self.outbox))

    def test_unreachable_server_queues_then_outbox_only_uploads(self):
        path = self.session_copy("later.palpa", "c2" * 16)
        before = sha256(path)
        down = "host=127.0.0.1 port=%d dbname=palpa user=station_a connect_timeout=5" % pg_test_server.free_port()
        res = self.cli("store", "push", path, "--store", down, "--station", "room-2", "--outbox", self.outbox)
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertIn("queued: " + path, res.stdout)
        copy = os.path.join(self.outbox, "c2" * 16 + ".palpa")
        self.assertEqual(sha256(copy), before)
        self.assertEqual(sha256(path), before)  # the station's file is untouched
        with open(os.path.join(self.outbox, "c2" * 16 + ".json")) as f:
            meta = json.load(f)
        self.assertEqual((meta["trainee"], meta["size"], meta["source"]), ("sample-light", os.path.getsize(path), path))
        self.assertEqual(meta["attempts"], 1)  # one push, one attempt
        again = self.cli("store", "push", path, "--store", down, "--station", "room-2", "--outbox", self.outbox)
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertIn("already queued: " + path, again.stdout)
        with open(os.path.join(self.outbox, "c2" * 16 + ".json")) as f:
            self.assertEqual(json.load(f)["attempts"], 2)
        status = self.cli("store", "status", "--store", down, "--station", "room-2", "--outbox", self.outbox)
        self.assertEqual(status.returncode, 0, status.stderr)
        self.assertIn("1 waiting", status.stdout)
        self.assertIn("trainee sample-light", status.stdout)
        self.assertIn("last error: store: cannot connect to 127.0.0.1:", status.stdout)
        flush = self.cli("store", "push", "--outbox-only", "--store", self.url, "--station", "room-2",
                         "--outbox", self.outbox)
        self.assertEqual(flush.returncode, 0, flush.stderr)
        self.assertIn("outbox: 1 sent, 0 waiting", flush.stdout)
        self.assertEqual(os.listdir(self.outbox), [])
        self.assertEqual(self.stored("c2" * 16), "%s %d later.palpa room-2" % (before, os.path.getsize(path)))
        after = self.cli("store", "status", "--store", self.url, "--station", "room-2", "--outbox", self.outbox)
        self.assertIn("0 waiting", after.stdout)
        self.assertRegex(after.stdout, r"store 127\.0\.0\.1:\d+/palpa as station_a: \d+ sessions stored by this login")

    def test_a_connection_string_libpq_cannot_parse_is_refused_not_queued(self):
        path = self.session_copy("typo.palpa", "e4" * 16)
        res = self.cli("store", "push", path, "--store", "host=127.0.0.1 dbname", "--station", "room-1",
                       "--outbox", self.outbox)
        self.assertEqual(res.returncode, 1, res.stdout)
        lines = res.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, res.stderr)
        self.assertIn("store: bad connection string: ", lines[0])
        self.assertFalse(os.path.exists(os.path.join(self.outbox, "e4" * 16 + ".palpa")))

    def test_the_store_comes_from_the_environment_or_the_config_file(self):
        path = self.session_copy("env.palpa", "d3" * 16)
        res = self.cli("store", "push", path, "--outbox", self.outbox, PALPA_STORE=self.url, PALPA_STATION="room-env")
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertTrue(self.stored("d3" * 16).endswith(" room-env"))
        config = os.path.join(self.home, ".config", "palpa")
        os.makedirs(config)
        with open(os.path.join(config, "store.json"), "w") as f:
            json.dump({"store": self.url, "station": "room-file", "outbox": self.outbox}, f)
        path = self.session_copy("file.palpa", "e4" * 16)
        res = self.cli("store", "push", path)
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertTrue(self.stored("e4" * 16).endswith(" room-file"))
        with open(os.path.join(config, "store.json"), "w") as f:
            json.dump({"store": self.url, "stations": "typo"}, f)
        res = self.cli("store", "push", path)
        self.assertEqual(res.returncode, 2)
        self.assertEqual(len(res.stderr.strip().splitlines()), 1, res.stderr)
        self.assertIn("store.json: stations: unknown setting", res.stderr)


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
