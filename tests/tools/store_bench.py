#!/usr/bin/python3
"""Times the centre store on a throwaway PostgreSQL (pg_test_server.py): pushing a corpus
of stretched sessions, scoring them with workers, and batch --store --out against the
folder batch on the same files.

    /usr/bin/python3 tests/tools/store_bench.py --cli build/release/app/palpa-cli --count 20 --minutes 5
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import pg_test_server  # noqa: E402


def timed(argv, env):
    start = time.monotonic()
    res = subprocess.run(argv, capture_output=True, text=True, env=env)
    if res.returncode != 0:
        sys.exit("%s: exit %d: %s" % (" ".join(argv[:3]), res.returncode, res.stderr))
    return time.monotonic() - start


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cli", required=True)
    ap.add_argument("--count", type=int, default=20)
    ap.add_argument("--minutes", type=float, default=5.0)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--format", type=int, choices=(1, 2), default=2,
                    help="session format of the corpus (2: as stations record them now)")
    args = ap.parse_args()
    repo = os.path.dirname(os.path.dirname(HERE))
    work = tempfile.mkdtemp(prefix="palpa-store-bench-")
    try:
        corpus = os.path.join(work, "corpus")
        bases = [os.path.join(repo, "data", "sessions", n + ".palpa") for n in ("expert", "sloppy", "light")]
        subprocess.run([sys.executable, os.path.join(HERE, "make_batch_corpus.py"), *bases, "--out", corpus,
                        "--count", str(args.count), "--minutes", str(args.minutes), "--corrupt", "0",
                        "--format", str(args.format), "--cli", args.cli],
                       check=True, capture_output=True)
        files = sorted(os.path.join(corpus, n) for n in os.listdir(corpus) if n.endswith(".palpa") and n[0] != ".")
        size = sum(os.path.getsize(f) for f in files)
        with pg_test_server.PgServer() as pg:
            env, url = pg.env(), pg.url("palpa")
            pg.sql("CREATE DATABASE palpa")
            timed([args.cli, "store", "init", url], env)
            push = timed([args.cli, "store", "push", *files, "--store", url, "--station", "bench",
                          "--outbox", os.path.join(work, "outbox")], env)
            workers = timed([args.cli, "batch", "--store", url, "--worker", "--jobs", str(args.jobs)], env)
            export = timed([args.cli, "batch", "--store", url, "--out", os.path.join(work, "out"),
                            "--jobs", str(args.jobs)], env)
            folder = timed([args.cli, "batch", corpus, "--out", os.path.join(work, "folder-out"),
                            "--jobs", str(args.jobs)], env)
        print("%d sessions of %.0f min (format %d), %.1f MB: push %.1f s (%.2f s/session), workers --jobs %d %.1f s, "
              "batch --store --out %.1f s, folder batch %.1f s"
              % (len(files), args.minutes, args.format, size / 1e6, push, push / len(files), args.jobs, workers, export, folder))
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
