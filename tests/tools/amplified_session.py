#!/usr/bin/python3
"""A valid format-2 session whose samples are TICKS identical ticks (the finger resting in
the air at 1 kHz), in blocks of 65 536 ticks that compress to a few dozen bytes each: about
100 kB for 72 million ticks, the most a session may hold. The work a reader and a scorer do
per input byte is largest on such a file (docs/security.md, "Bounded work per session").

    /usr/bin/python3 tests/tools/amplified_session.py FORMAT2_SESSION OUT --ticks 72000000 [--id HEX32]

FORMAT2_SESSION gives the meta rows and events (e.g. `palpa-cli session upgrade` of a
sample session); its samples are replaced and its end event moved to the last tick.
"""
import argparse
import os
import shutil
import sqlite3
import struct
import zlib

BLOCK = 65536
# (exponent, value in SI) of each column after tick and t: x y z fx fy fz body u v depth buttons overrun fault
RESTING = [(6, 0.0), (6, 0.0), (6, 0.2), (3, 0.0), (3, 0.0), (3, 0.0), (0, -1), (6, 0.0), (6, 0.0), (6, 0.0),
           (0, 0), (0, 0), (0, 0)]


def column(order, exponent, head):
    """One column of a block: `order` delta passes, the first `order` values raw, the rest all 0 (width 0)."""
    return bytes([order, 0, exponent]) + struct.pack("<%dq" % len(head), *head)


def block(first_tick, count, period_us=1000):
    t0 = first_tick * period_us
    raw = column(2, 0, [first_tick, 1 - first_tick]) if count > 1 else column(1, 0, [first_tick])
    raw += column(2, 6, [t0, period_us - t0]) if count > 1 else column(1, 6, [t0])
    for exponent, value in RESTING:
        raw += column(1, exponent, [int(round(value * 10 ** exponent))])
    return zlib.compress(raw, 9)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("source")
    ap.add_argument("out")
    ap.add_argument("--ticks", type=int, required=True)
    ap.add_argument("--id", help="the new session id (32 lowercase hex digits)")
    args = ap.parse_args()
    shutil.copyfile(args.source, args.out)
    db = sqlite3.connect(args.out)
    version = db.execute("SELECT value FROM meta WHERE key = 'format_version'").fetchone()[0]
    if str(version) != "2":
        raise SystemExit("%s: format_version %s; give a format-2 session" % (args.source, version))
    db.execute("DELETE FROM sample_blocks")
    first = 0
    while first < args.ticks:
        count = min(BLOCK, args.ticks - first)
        db.execute("INSERT INTO sample_blocks(first_tick, count, data) VALUES (?, ?, ?)",
                   (first, count, block(first, count)))
        first += count
    last_t = (args.ticks - 1) * 0.001
    db.execute("DELETE FROM events WHERE kind NOT IN ('start', 'end')")
    db.execute("UPDATE events SET t = ? WHERE kind = 'end'", (last_t,))
    if args.id:
        db.execute("UPDATE meta SET value = ? WHERE key = 'id'", (args.id,))
    db.commit()
    db.execute("VACUUM")
    db.close()
    print("%s: %d ticks, %d bytes" % (args.out, args.ticks, os.path.getsize(args.out)))


if __name__ == "__main__":
    main()
