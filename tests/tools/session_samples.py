"""A session's samples from Python's standard library, whatever its format
(docs/session-format.md): format 1's `samples` rows as they are, format 2's `sample_blocks`
decoded into the same rows. For tests that look at the ticks of a session Palpa wrote.

    from session_samples import sample_rows
    rows = sample_rows(db)  # (tick, t, x, y, z, fx, fy, fz, body, u, v, depth, buttons, overrun, fault)

Out of contact, body, u, v and depth are None, as in format 1.
"""
import struct
import zlib
from itertools import accumulate

COLUMNS = ("tick", "t", "x", "y", "z", "fx", "fy", "fz", "body", "u", "v", "depth", "buttons", "overrun", "fault")
FORMATS = {1: "b", 2: "h", 4: "i", 8: "q"}


def decode_block(count, data):
    """One block of sample_blocks as {column: [value per tick]}, in SI units (s, m, N)."""
    raw, at, out = zlib.decompress(data), 0, {}
    for name in COLUMNS:
        order, width, exponent = raw[at], raw[at + 1], raw[at + 2]
        at += 3
        head = min(order, count)
        values = list(struct.unpack_from("<%dq" % head, raw, at))
        at += 8 * head
        if width:
            values += struct.unpack_from("<%d%s" % (count - head, FORMATS[width]), raw, at)
            at += width * (count - head)
        else:
            values += [0] * (count - head)
        for _ in range(order):
            values = list(accumulate(values))
        out[name] = values if exponent == 0 else [v / 10 ** exponent for v in values]
    return out


def format_version(db):
    return int(db.execute("select value from meta where key = 'format_version'").fetchone()[0])


def sample_rows(db):
    """Every tick of the session open in `db` (an sqlite3 connection), in tick order."""
    if format_version(db) < 2:
        return db.execute("select tick, t, x, y, z, fx, fy, fz, body, u, v, depth, buttons, overrun, fault "
                          "from samples order by tick").fetchall()
    rows = []
    for count, data in db.execute("select count, data from sample_blocks order by first_tick"):
        block = decode_block(count, data)
        for k in range(count):
            row = [block[name][k] for name in COLUMNS]
            if row[8] < 0:  # not in contact
                row[8:12] = [None] * 4
            rows.append(tuple(row))
    return rows
