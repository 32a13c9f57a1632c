#!/usr/bin/env python3
"""Builds a corpus of session files for batch tests and benchmarks.

Each output session is a copy of one of the BASE sessions (round robin) with its meta
rewritten: a new session id, a trainee out of --trainees, and a start time one hour after
the previous attempt of that trainee, so learning curves have an order. With
--minutes M every copy's samples are repeated (shifted in time) until they last at least
M minutes, the way a long recording would. --corrupt K adds K damaged files (random
bytes, a truncated session) whose names sort among the good ones. --format 2 --cli PATH
converts the (stretched) bases to session format 2 with `PATH session upgrade` before they
are copied, as finished recordings are; stretching needs format-1 bases (their rows).

Standard library only (sqlite3), so the corpus can be built wherever the tests run.
"""
import argparse
import datetime
import os
import random
import shutil
import sqlite3
import subprocess
import sys


def stretch(path, minutes):
    """Repeats the samples of `path` until they cover `minutes`; events stay as they are
    except the end event, which moves to the new last sample."""
    db = sqlite3.connect(path)
    version = db.execute("select value from meta where key = 'format_version'").fetchone()[0]
    if version != "1":
        sys.exit("make_batch_corpus: --minutes needs format-1 bases (rows to repeat); %s is format %s" % (path, version))
    (n, t_last) = db.execute("select count(*), max(t) from samples").fetchone()
    if n == 0:
        db.close()
        return
    rate = float(db.execute("select value from meta where key='rate_hz'").fetchone()[0])
    period = t_last + 1.0 / rate
    copies = 0
    while period * (copies + 1) < minutes * 60.0:
        copies += 1
        db.execute(
            "insert into samples select tick + ?, t + ?, x, y, z, fx, fy, fz, body, u, v, depth, "
            "buttons, overrun, fault from samples where tick < ?", (n * copies, period * copies, n))
    db.execute("update events set t = (select max(t) from samples) where kind = 'end'")
    db.commit()
    db.close()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("base", nargs="+", help="finished session files to copy")
    ap.add_argument("--out", required=True, help="folder for the corpus (created)")
    ap.add_argument("--count", type=int, default=1000)
    ap.add_argument("--trainees", type=int, default=20)
    ap.add_argument("--minutes", type=float, default=0.0, help="stretch each base to at least this long first")
    ap.add_argument("--corrupt", type=int, default=1)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--format", type=int, choices=(1, 2), default=1,
                    help="session format of the copies: 1 as the bases are, 2 through palpa-cli session upgrade")
    ap.add_argument("--cli", help="palpa-cli, for --format 2")
    args = ap.parse_args()
    if args.format == 2 and not args.cli:
        ap.error("--format 2 needs --cli PATH (palpa-cli converts the bases)")

    os.makedirs(args.out, exist_ok=True)
    rng = random.Random(args.seed)
    bases = []
    for i, b in enumerate(args.base):
        staged = os.path.join(args.out, ".base-%d.palpa" % i)
        shutil.copyfile(b, staged)
        if args.minutes > 0:
            stretch(staged, args.minutes)
        bases.append(staged)
    if args.format == 2:
        res = subprocess.run([args.cli, "session", "upgrade"] + bases, capture_output=True, text=True)
        if res.returncode != 0:
            sys.exit("make_batch_corpus: %s session upgrade failed: %s" % (args.cli, res.stderr.strip()))

    start = datetime.datetime(2026, 1, 5, 8, 0, 0, tzinfo=datetime.timezone.utc)
    attempts = {}
    for i in range(args.count):
        trainee = "trainee-%03d" % (i % args.trainees)
        k = attempts.get(trainee, 0)
        attempts[trainee] = k + 1
        name = os.path.join(args.out, "s%05d.palpa" % i)
        shutil.copyfile(bases[i % len(bases)], name)
        db = sqlite3.connect(name)
        started = (start + datetime.timedelta(hours=k, minutes=i % args.trainees)).strftime("%Y-%m-%dT%H:%M:%SZ")
        for key, value in (("id", "%032x" % rng.getrandbits(128)), ("trainee", trainee), ("started_at", started)):
            db.execute("insert or replace into meta(key, value) values (?, ?)", (key, value))
        db.commit()
        db.close()
    for j in range(args.corrupt):
        bad = os.path.join(args.out, "s%05d-corrupt.palpa" % (j * max(1, args.count // max(1, args.corrupt))))
        if j % 2 == 0:
            with open(bad, "wb") as f:
                f.write(bytes(rng.getrandbits(8) for _ in range(8192)))
        else:
            with open(bases[0], "rb") as f:
                data = f.read()
            with open(bad, "wb") as f:
                f.write(data[: len(data) // 3])
    for b in bases:
        os.remove(b)
    print("make_batch_corpus: %d sessions (+%d corrupt) in %s" % (args.count, args.corrupt, args.out), file=sys.stderr)


if __name__ == "__main__":
    main()
