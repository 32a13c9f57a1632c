#!/usr/bin/python3
"""Builds the seed corpora of the fuzz targets (fuzz/corpus/NAME/) from the repository's
own data, and adds the hostile inputs that once cost seconds and gigabytes (their
regression tests with limits: tests/cli/test_hostile_sessions.py, tests/core/session/session_corrupt_test.cpp).

    /usr/bin/python3 tools/fuzz/make_corpora.py [--repo REPO]

Idempotent: files are rewritten with the same bytes. Files the fuzzers found and were
added by hand (crash-*, timeout-*, or any other name) are left alone.
"""

import argparse
import glob
import importlib.util
import json
import os
import shutil
import sqlite3
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def out_dir(name):
    path = os.path.join(REPO, "fuzz", "corpus", name)
    os.makedirs(path, exist_ok=True)
    return path


def write(name, file, data):
    with open(os.path.join(out_dir(name), file), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def flat_body(width, pulled=None):
    """The hostile flat body of tests/cli/test_hostile_sessions.py (one definition for the
    regression test and the corpus): `width` m across, 20 mm thick in the middle, its first
    boundary skeleton point moved `pulled` m along -x."""
    spec = importlib.util.spec_from_file_location(
        "test_hostile_sessions", os.path.join(REPO, "tests", "cli", "test_hostile_sessions.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.flat_body(width, pulled=pulled)


def case_corpus():
    for path in sorted(glob.glob(os.path.join(REPO, "data", "cases", "*.json"))):
        shutil.copy(path, os.path.join(out_dir("case_loader"), os.path.basename(path)))
    write("case_loader", "hostile-200m-wide.json", json.dumps(flat_body(200.0)))
    write("case_loader", "hostile-50m-spike.json", json.dumps(flat_body(0.1, pulled=50.0)))
    write("case_loader", "hostile-widest-plausible.json", json.dumps(flat_body(2.0)))


def edited_light_session(edit):
    """A copy of the light sample session changed by `edit(db)`, with 512-byte pages (small
    inputs: mutations go further). Returns the file's bytes."""
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "s.palpa")
        src = sqlite3.connect("file:" + os.path.join(REPO, "data", "sessions", "light.palpa") + "?mode=ro", uri=True)
        src.execute("VACUUM INTO ?", (path,))
        src.close()
        db = sqlite3.connect(path)
        edit(db)
        db.commit()
        db.execute("PRAGMA page_size = 512")
        db.execute("VACUUM")
        db.close()
        with open(path, "rb") as f:
            return f.read()


def session_from(case, samples, sql=None):
    """The light sample session's meta with `case`, `samples` (tick, t, u, v, depth) in
    contact, its start and end events; `sql` run on it last. Returns the file's bytes."""
    def edit(db):
        if case is not None:
            db.execute("UPDATE meta SET value = ? WHERE key = 'case'", (json.dumps(case),))
        db.execute("DELETE FROM samples")
        db.executemany("INSERT INTO samples VALUES (?, ?, 0, 0, 0.01, 0, 0, 1, 0, ?, ?, ?, 0, 0, 0)", samples)
        last = samples[-1][1] if samples else 0.0
        db.execute("UPDATE events SET t = ? WHERE kind = 'end'", (last,))
        if sql:
            db.executescript(sql)
    return edited_light_session(edit)


def first_press(db):
    """The light session cut to its first 300 ticks in contact, as recorded."""
    first = db.execute("SELECT min(tick) FROM samples WHERE body IS NOT NULL").fetchone()[0] or 0
    db.execute("DELETE FROM samples WHERE tick < ? OR tick >= ?", (first, first + 300))
    db.execute("UPDATE samples SET tick = tick - ?", (first,))


def session_corpus():
    write("session_scorer", "light-first-press.palpa", edited_light_session(first_press))
    jumps = [(k, k * 0.001, 0.02 if k % 2 == 0 else 0.98, 0.5, 0.005) for k in range(200)]
    write("session_scorer", "hostile-jumps-2m.palpa", session_from(flat_body(2.0), jumps))
    write("session_scorer", "hostile-jumps-200m.palpa", session_from(flat_body(200.0), jumps[:100]))
    stamps = [(k, k * 0.001, 0.5 + 0.001 * (k % 7), 0.5, 0.005) for k in range(500)]
    write("session_scorer", "hostile-stretched-cell.palpa", session_from(flat_body(0.1, pulled=0.45), stamps))
    write("session_scorer", "hostile-u-4e213.palpa",
          session_from(None, [(0, 0.0, 0.5, 0.5, 0.005), (1, 0.001, 4.2e213, 0.5, 0.005)]))
    write("session_scorer", "hostile-time-back.palpa",
          session_from(None, [(0, 0.5, 0.5, 0.5, 0.005), (1, 0.1, 0.5, 0.5, 0.005)]))
    generated = ("CREATE TABLE s2(tick INTEGER PRIMARY KEY, t REAL GENERATED ALWAYS AS "
                 "(length(zeroblob(400000000)) * 0.0) VIRTUAL, x REAL NOT NULL, y REAL NOT NULL, z REAL NOT NULL, "
                 "fx REAL NOT NULL, fy REAL NOT NULL, fz REAL NOT NULL, body INTEGER, u REAL, v REAL, depth REAL, "
                 "buttons INTEGER NOT NULL, overrun INTEGER NOT NULL, fault INTEGER NOT NULL); "
                 "INSERT INTO s2(tick, x, y, z, fx, fy, fz, body, u, v, depth, buttons, overrun, fault) "
                 "SELECT tick, x, y, z, fx, fy, fz, body, u, v, depth, buttons, overrun, fault FROM samples; "
                 "DROP TABLE samples; ALTER TABLE s2 RENAME TO samples;")
    write("session_scorer", "hostile-generated-column.palpa",
          session_from(None, [(k, k * 0.001, 0.5, 0.5, 0.005) for k in range(20)], generated))
    write("session_scorer", "hostile-trigger.palpa",
          session_from(None, [(0, 0.0, 0.5, 0.5, 0.005)],
                       "CREATE TRIGGER wipe AFTER INSERT ON events BEGIN DELETE FROM samples; END;"))


def csv_corpus():
    write("timed_points_csv", "press.csv", "t,x,y,z\n0,0,0,0.03\n0.5,0,0,0.01\n1.0,0.01,0,0.005\n")
    write("timed_points_csv", "crlf-blank-spaces.csv", "t, x ,y,z\r\n\r\n0, 1e-3, 2E-3 ,0\r\n0.25,0,0,0\r\n")
    write("timed_points_csv", "marks-same-time.csv", "t,x,y,z\n1,0,0,0\n1,0.01,0,0\n")
    write("timed_points_csv", "not-finite.csv", "t,x,y,z\n0,nan,0,0\n1,inf,1e309,0\n")
    write("timed_points_csv", "backwards.csv", "t,x,y,z\n1,0,0,0\n0.5,0,0,0\n-1,0,0,0\n")


def spacemouse_corpus():
    def report(*b):
        return bytes([len(b)]) + bytes(b)
    split = bytes([0]) + report(1, 0x10, 0, 0xF0, 0xFF, 0x5E, 0x01) + report(2, 1, 0, 2, 0, 3, 0) + report(3, 5)
    six = bytes([1]) + report(1, *([0x22, 0x01] * 6)) + report(3, 1, 2, 3, 4, 5) + report(1, 0, 0) + report(9, 1)
    write("spacemouse_report", "split-layout.bin", split)
    write("spacemouse_report", "six-axis-layout.bin", six)


def falcon_packet(words, flags):
    nibbles = []
    for w in words:
        bits = w & 0xFFFF
        nibbles += [((bits >> (4 * n)) & 0xF) + 0x41 for n in range(4)]
    return bytes([ord('<')] + nibbles + [flags + 0x41, 0x41, ord('>')])


def falcon_corpus():
    stream = falcon_packet([100, -200, 32767], 0x70) + b"garbage<<" + falcon_packet([-32768, 0, 1], 0x0F)
    write("falcon_packet", "stream-7-byte-reads.bin", bytes([6]) + stream)
    broken = falcon_packet([1, 2, 3], 0)[:10] + falcon_packet([4, 5, 6], 1) + b"<" + b"Z" * 14 + b">"
    write("falcon_packet", "torn-and-bad.bin", bytes([15]) + broken)


def main():
    global REPO
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repo", default=REPO)
    REPO = os.path.abspath(parser.parse_args().repo)
    case_corpus()
    session_corpus()
    csv_corpus()
    spacemouse_corpus()
    falcon_corpus()


if __name__ == "__main__":
    main()
