#!/usr/bin/python3
"""The centre end to end: three stations push their sessions, one of them while the server
is stopped (they wait in its outbox, then go up once the server is back), workers score
them, every session ends scored exactly once, and batch --store --out writes the same
summary rows as the folder batch on the stations' own files.

    /usr/bin/python3 tests/cli/test_store_e2e.py --cli palpa-cli --repo REPO
"""
import argparse
import csv
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tools"))
import pg_test_server  # noqa: E402

CLI = REPO = None
PER_STATION = 3


def rows_by_session(summary, keep_station=False):
    """summary.csv's rows by session id, without `file` (and `station`: the store's batch
    takes it from the store, the folder batch from the file, which scripted sessions leave empty)."""
    with open(summary, newline="") as f:
        rows = list(csv.DictReader(f))
    drop = {"file"} if keep_station else {"file", "station"}
    return {r["session_id"]: {k: v for k, v in r.items() if k not in drop} for r in rows}


def files_under(folder):
    return [os.path.join(d, n) for d, _, names in os.walk(folder) for n in names]


class Centre(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.pg = pg_test_server.server_for_tests()
        cls.dir = tempfile.mkdtemp(prefix="palpa-centre-")

    @classmethod
    def tearDownClass(cls):
        cls.pg.close()
        shutil.rmtree(cls.dir, ignore_errors=True)

    def cli(self, *args):
        return subprocess.run([CLI, *args], capture_output=True, text=True, env=self.pg.env(), timeout=300)

    def station_files(self):
        bases = [os.path.join(REPO, "data", "sessions", n + ".palpa") for n in ("expert", "sloppy", "light")]
        corpus = os.path.join(self.dir, "corpus")
        subprocess.run([sys.executable, os.path.join(REPO, "tests", "tools", "make_batch_corpus.py"), *bases,
                        "--out", corpus, "--count", str(3 * PER_STATION), "--trainees", "3", "--corrupt", "0"],
                       check=True, capture_output=True)
        files = sorted(os.path.join(corpus, n) for n in os.listdir(corpus) if n.endswith(".palpa") and n[0] != ".")
        return corpus, {s: files[i * PER_STATION:(i + 1) * PER_STATION] for i, s in enumerate("abc")}

    def push(self, station, *args):
        return self.cli("store", "push", *args, "--store", self.pg.url("palpa", "station_" + station),
                        "--station", "room-" + station, "--outbox", os.path.join(self.dir, "outbox-" + station))

    def test_three_stations_one_offline_then_workers_then_reports(self):
        self.pg.sql("CREATE DATABASE palpa")
        self.assertEqual(self.cli("store", "init", self.pg.url("palpa")).returncode, 0)
        for user, group in (("station_a", "palpa_station"), ("station_b", "palpa_station"),
                            ("station_c", "palpa_station"), ("coordinator", "palpa_coordinator")):
            self.pg.add_login(user, group)
        corpus, files = self.station_files()
        for s in "ab":
            res = self.push(s, *files[s])
            self.assertEqual(res.returncode, 0, res.stderr)
            self.assertEqual(res.stdout.count("stored: "), PER_STATION, res.stdout)
        self.pg.stop()
        offline = self.push("c", *files["c"])
        self.assertEqual(offline.returncode, 0, offline.stderr)
        self.assertEqual(offline.stdout.count("queued: "), PER_STATION, offline.stdout)
        self.pg.start()
        back = self.push("c", "--outbox-only")
        self.assertEqual(back.returncode, 0, back.stderr)
        self.assertIn("outbox: %d sent, 0 waiting" % PER_STATION, back.stdout)
        self.assertEqual(os.listdir(os.path.join(self.dir, "outbox-c")), [])
        self.assertEqual(self.pg.sql("SELECT station || ' ' || count(*) FROM sessions GROUP BY station ORDER BY 1",
                                     "palpa").splitlines(), ["room-%s %d" % (s, PER_STATION) for s in "abc"])

        work = self.cli("batch", "--store", self.pg.url("palpa", "coordinator"), "--worker", "--jobs", "2")
        self.assertEqual(work.returncode, 0, work.stderr)
        self.assertEqual(self.pg.sql("SELECT count(*) FROM sessions s WHERE (SELECT count(*) FROM scores sc "
                                     "WHERE sc.session_id = s.id) = 1", "palpa"), str(3 * PER_STATION))
        self.assertEqual(self.pg.sql("SELECT count(*) FROM scores", "palpa"), str(3 * PER_STATION))
        again = self.cli("batch", "--store", self.pg.url("palpa", "coordinator"), "--worker")
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertEqual(self.pg.sql("SELECT count(*) FROM scores", "palpa"), str(3 * PER_STATION))

        out, folder_out = os.path.join(self.dir, "out"), os.path.join(self.dir, "folder-out")
        report = self.cli("batch", "--store", self.pg.url("palpa", "coordinator"), "--out", out)
        self.assertEqual(report.returncode, 0, report.stderr)
        folder = self.cli("batch", corpus, "--out", folder_out)
        self.assertEqual(folder.returncode, 0, folder.stderr)
        self.assertEqual(rows_by_session(os.path.join(out, "summary.csv")),
                         rows_by_session(os.path.join(folder_out, "summary.csv")))
        self.assertTrue(os.path.exists(os.path.join(out, "cohort.html")))
        # The station column is the store's: the station that pushed each session.
        pushed_from = {os.path.basename(p)[:-len(".palpa")]: s for s, ps in files.items() for p in ps}
        by_file = {}
        for path in sum(files.values(), []):
            sid = subprocess.run(["sqlite3", path, "SELECT value FROM meta WHERE key = 'id'"], capture_output=True,
                                 text=True, check=True).stdout.strip()
            by_file[sid] = "room-" + pushed_from[os.path.basename(path)[:-len(".palpa")]]
        self.assertEqual({k: r["station"] for k, r in rows_by_session(os.path.join(out, "summary.csv"), True).items()},
                         by_file)
        self.assertEqual(sorted(os.listdir(os.path.join(out, "trainees"))),
                         sorted(os.listdir(os.path.join(folder_out, "trainees"))))
        # The folder batch's filters select alike (the store is asked for a superset).
        only = ("--trainee", "trainee-001", "--since", "2026-01-05")
        report = self.cli("batch", "--store", self.pg.url("palpa", "coordinator"), "--out", out + "-1", *only)
        self.assertEqual(report.returncode, 0, report.stderr)
        folder = self.cli("batch", corpus, "--out", folder_out + "-1", *only)
        self.assertEqual(folder.returncode, 0, folder.stderr)
        picked = rows_by_session(os.path.join(out + "-1", "summary.csv"))
        self.assertEqual(picked, rows_by_session(os.path.join(folder_out + "-1", "summary.csv")))
        self.assertEqual({r["trainee"] for r in picked.values()}, {"trainee-001"})
        self.assertEqual(len(files_under(os.path.join(out + "-1", "stored"))), len(picked))
        self.assertEqual(sorted(os.listdir(os.path.join(out + "-1", "stored")))[0][:len("room-a-")], "room-a-")


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
