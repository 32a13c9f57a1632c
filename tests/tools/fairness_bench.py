#!/usr/bin/python3
"""How long one station's session waits behind another station's flood, on a throwaway
PostgreSQL (pg_test_server.py): station A pushes FLOOD sessions, then station B pushes one,
then the workers score everything. Prints where B's session came in the scoring order and
how long it waited from its push to its score, beside A's last session.

    /usr/bin/python3 tests/tools/fairness_bench.py --cli build/release/app/palpa-cli --flood 200 --jobs 2
"""
import argparse
import hashlib
import os
import shutil
import sqlite3
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import pg_test_server  # noqa: E402


def copy_with_id(source, path, n):
    shutil.copyfile(source, path)
    db = sqlite3.connect(path)
    db.execute("UPDATE meta SET value = ? WHERE key = 'id'", (hashlib.sha256(b"%d" % n).hexdigest()[:32],))
    db.commit()
    db.close()
    return path


def run(argv, env):
    res = subprocess.run(argv, capture_output=True, text=True, env=env)
    if res.returncode != 0:
        sys.exit("%s: exit %d: %s" % (" ".join(argv[:3]), res.returncode, res.stderr))
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cli", required=True)
    ap.add_argument("--flood", type=int, default=200)
    ap.add_argument("--jobs", type=int, default=2)
    args = ap.parse_args()
    repo = os.path.dirname(os.path.dirname(HERE))
    work = tempfile.mkdtemp(prefix="palpa-fairness-")
    try:
        with pg_test_server.PgServer() as pg:
            env = pg.env()
            pg.sql("CREATE DATABASE palpa")
            run([args.cli, "store", "init", pg.url("palpa")], env)
            for user, group in (("station_a", "palpa_station"), ("station_b", "palpa_station"),
                                ("worker", "palpa_worker")):
                pg.add_login(user, group)
            run([args.cli, "session", "upgrade", os.path.join(repo, "data", "sessions", "sloppy.palpa"), "--out", work],
                env)
            small = os.path.join(work, "sloppy.palpa")
            flood = [copy_with_id(small, os.path.join(work, "a%d.palpa" % k), k) for k in range(args.flood)]
            run([args.cli, "store", "push", *flood, "--store", pg.url("palpa", "station_a"), "--station", "room-a",
                 "--outbox", os.path.join(work, "outbox-a")], env)
            late = copy_with_id(small, os.path.join(work, "b.palpa"), 10 ** 6)
            run([args.cli, "store", "push", late, "--store", pg.url("palpa", "station_b"), "--station", "room-b",
                 "--outbox", os.path.join(work, "outbox-b")], env)
            start = time.monotonic()
            run([args.cli, "batch", "--store", pg.url("palpa", "worker"), "--worker", "--jobs", str(args.jobs)], env)
            total = time.monotonic() - start
            rows = pg.sql("SELECT s.uploaded_by || ' ' || extract(epoch FROM sc.scored_at - s.uploaded_at) "
                          "FROM scores sc JOIN sessions s ON s.id = sc.session_id ORDER BY sc.id", "palpa").splitlines()
            b = [k for k, r in enumerate(rows) if r.startswith("station_b ")]
            waits = {r.split()[0]: float(r.split()[1]) for r in rows}
            print("%d sessions from room-a, then 1 from room-b, %d worker threads: all scored in %.1f s "
                  "(%.3f s a session)" % (args.flood, args.jobs, total, total / len(rows)))
            print("room-b's session: scored %d of %d (first in first out: %d of %d), %.1f s after its push; "
                  "room-a's last: %.1f s after its push" % (b[0] + 1, len(rows), len(rows), len(rows),
                                                          waits["station_b"], float(rows[-1].split()[1])))
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
