#!/usr/bin/python3
"""A valid format-2 session of N identical ticks (one contact sample of data/sessions/light.palpa
repeated every millisecond), written directly as sample_blocks of up to 65536 ticks: every
column is a constant or a constant step, so a block is about a hundred bytes and 72 million
ticks (20 hours at 1 kHz, the most a session may hold) fit in about 120 kB. The file a
reader that holds every sample in memory is amplified by (docs/session-format.md).

    from constant_session import write_constant_session
    write_constant_session(path, repo, ticks=4_000_000)

or from a shell:
    /usr/bin/python3 tests/tools/constant_session.py REPO OUT.palpa TICKS
"""
import os
import shutil
import sqlite3
import struct
import sys
import zlib

BLOCK_TICKS = 65536  # the most a block may declare
# (column, decimal exponent) in the order of the format (docs/session-format.md).
COLUMNS = (("tick", 0), ("t", 6), ("x", 6), ("y", 6), ("z", 6), ("fx", 3), ("fy", 3), ("fz", 3),
           ("body", 0), ("u", 6), ("v", 6), ("depth", 6), ("buttons", 0), ("overrun", 0), ("fault", 0))
PERIOD_US = 1000  # 1 kHz


def column(first, step, count, exponent):
    """A column whose integers are first, first + step, ...: order 2, so every residual after
    the first two (first, step - first) is zero (width 0: nothing stored for them)."""
    head = min(2, count)
    return bytes([2, 0, exponent]) + struct.pack("<%dq" % head, *[first, step - first][:head])


def block(first_tick, count, sample):
    """The zlib data of `count` ticks from `first_tick`, each `sample` (a dict of integers in
    the columns' units) with t advancing one period a tick."""
    raw = b""
    for name, exponent in COLUMNS:
        if name == "tick":
            raw += column(first_tick, 1, count, exponent)
        elif name == "t":
            raw += column(first_tick * PERIOD_US, PERIOD_US, count, exponent)
        else:
            raw += column(sample[name], 0, count, exponent)
    return zlib.compress(raw, 9)


def contact_sample(db):
    """One contact sample of the session open in `db` (format 1), quantized to the block units."""
    names = [name for name, _ in COLUMNS[2:]]
    row = db.execute("select %s from samples where body is not null and depth > 0 order by tick limit 1 offset 500"
                     % ", ".join(names)).fetchone()
    return {name: int(round(value * 10 ** exponent)) for (name, exponent), value in zip(COLUMNS[2:], row)}


def write_constant_session(path, repo, ticks):
    """`path`: a copy of light.palpa turned into format 2 with `ticks` identical ticks,
    its end event at the last tick."""
    shutil.copy(os.path.join(repo, "data", "sessions", "light.palpa"), path)
    db = sqlite3.connect(path)
    sample = contact_sample(db)
    db.execute("DROP TABLE samples")
    db.execute("CREATE TABLE sample_blocks(\n  first_tick INTEGER PRIMARY KEY,\n  count INTEGER NOT NULL,\n"
               "  data BLOB NOT NULL\n)")
    for first in range(0, ticks, BLOCK_TICKS):
        count = min(BLOCK_TICKS, ticks - first)
        db.execute("INSERT INTO sample_blocks VALUES (?, ?, ?)", (first, count, block(first, count, sample)))
    db.execute("UPDATE meta SET value = '2' WHERE key = 'format_version'")
    db.execute("UPDATE events SET t = ? WHERE kind = 'end'", ((ticks - 1) * PERIOD_US / 1e6,))
    db.execute("PRAGMA user_version = 2")
    db.commit()
    db.execute("VACUUM")
    db.close()


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    write_constant_session(sys.argv[2], sys.argv[1], int(sys.argv[3]))
