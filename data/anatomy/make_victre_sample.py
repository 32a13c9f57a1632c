#!/usr/bin/python3
"""Make Palpa's bundled anatomy, victre-breast.mha, from a VICTRE breastPhantom volume.

Run (Debian's python3 with numpy; see README.md for how the phantom was made):

    /usr/bin/python3 make_victre_sample.py /path/to/p_12345.mhd --out victre-breast.mha

Steps: read the phantom's .mhd + .raw (or .raw.gz); downsample to --voxel mm by
taking each block's most common label (ties go to skin, then nipple, then the
other tissues in ascending label order, and to air last, so thin skin survives
as best it can); crop to the breast plus --margin voxels of air, keeping
--muscle mm of pectoral muscle under the breast; add two spherical "mass"
lesions (label 200, Palpa's addition, not VICTRE's) at the fixed positions in
LESIONS; write a zlib-compressed MetaImage (.mha, ElementDataFile = LOCAL).

World frame: ITK/MetaImage LPS (+X patient left, +Y posterior, +Z superior), mm.
Voxel axis i = VICTRE x (chest wall -> nipple) = world -Y (posterior -> anterior);
j = VICTRE y (lateral -> medial of this left breast) = world -X;
k = VICTRE z (inferior -> superior) = world +Z.  AnatomicalOrientation = PLI
(ITK's convention: each letter names the side its axis runs *from*).
The output is deterministic: the same input gives the same bytes.
"""
import argparse, gzip, os, zlib
import numpy as np

AIR, SKIN, NIPPLE, MUSCLE, MASS = 0, 2, 33, 40, 200
# (fraction of breast extent along j, along k, depth below skin as a fraction of
#  the local tissue thickness from the skin down to the first non-muscle voxel, radius mm)
LESIONS = [(0.36, 0.40, 0.45, 7.0), (0.64, 0.58, 0.50, 6.0)]


def read_mhd(path):
    hdr = dict(l.split("=", 1) for l in open(path) if "=" in l)
    hdr = {k.strip(): v.strip() for k, v in hdr.items()}
    assert hdr["ElementType"] == "MET_UCHAR", hdr["ElementType"]
    dims = [int(v) for v in hdr["DimSize"].split()]
    raw = os.path.join(os.path.dirname(path), hdr["ElementDataFile"])
    data = open(raw, "rb").read() if os.path.exists(raw) else gzip.open(raw + ".gz").read()
    vol = np.frombuffer(data, np.uint8).reshape(dims[::-1]).transpose(2, 1, 0)  # [x, y, z]
    return vol, np.array(hdr["ElementSpacing"].split(), float), np.array(hdr["Offset"].split(), float)


def mode_downsample(vol, f):
    pad = [(0, (-n) % f) for n in vol.shape]
    v = np.pad(vol, pad)
    b = v.reshape(v.shape[0] // f, f, v.shape[1] // f, f, v.shape[2] // f, f)
    present = [int(x) for x in np.unique(vol)]
    order = [l for l in (SKIN, NIPPLE) if l in present]
    order += [l for l in present if l not in (SKIN, NIPPLE, AIR)] + [AIR]
    best = np.zeros(b[:, 0, :, 0, :, 0].shape, np.uint8)
    best_n = np.full(best.shape, -1, np.int32)
    for lab in order:  # strict '>' keeps the earlier label on ties
        n = (b == lab).sum(axis=(1, 3, 5), dtype=np.int32)
        better = n > best_n
        best[better], best_n[better] = lab, n[better]
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("mhd")
    ap.add_argument("--out", default="victre-breast.mha")
    ap.add_argument("--voxel", type=float, default=1.0, help="output voxel size, mm")
    ap.add_argument("--margin", type=int, default=3, help="voxels of air kept around the breast")
    ap.add_argument("--muscle", type=float, default=6.0, help="mm of muscle kept under the breast")
    a = ap.parse_args()

    fine, sp, org = read_mhd(a.mhd)
    f = int(round(a.voxel / sp[0]))
    assert np.allclose(sp * f, a.voxel), (sp, a.voxel)
    vol = mode_downsample(fine, f)
    org = org + (f - 1) / 2.0 * sp  # centre of block 0 in VICTRE mm

    # crop: breast = any tissue but muscle; keep a muscle slab below its deepest x
    breast = (vol != AIR) & (vol != MUSCLE)
    idx = [np.flatnonzero(breast.any(axis=tuple(d for d in range(3) if d != ax))) for ax in range(3)]
    lo = [i[0] - a.margin for i in idx]
    hi = [i[-1] + a.margin + 1 for i in idx]
    lo[0] = max(idx[0][0] - int(round(a.muscle / a.voxel)), 0)  # chest-wall side: no air
    m = a.margin  # the phantom's own box can touch the breast: pad it with air first
    vol = np.pad(vol, [(0, m), (m, m), (m, m)])[lo[0]:hi[0], lo[1] + m:hi[1] + m, lo[2] + m:hi[2] + m].copy()
    org = org + np.array(lo) * a.voxel
    breast = (vol != AIR) & (vol != MUSCLE)

    # lesions: (j, k) from fractions of the breast's extent; i at a depth below the skin
    jb, kb = [np.flatnonzero(breast.any(axis=ax)) for ax in ((0, 2), (0, 1))]
    ii, jj, kk = np.meshgrid(*[np.arange(n) for n in vol.shape], indexing="ij")
    centres = []
    for fj, fk, depth, r in LESIONS:
        j = int(round(jb[0] + fj * (jb[-1] - jb[0])))
        k = int(round(kb[0] + fk * (kb[-1] - kb[0])))
        col = vol[:, j, k]
        skin = np.flatnonzero(col != AIR)[-1]                   # outermost tissue
        base = np.flatnonzero((col != AIR) & (col != MUSCLE))[0]  # first non-muscle tissue
        i = int(round(skin - depth * (skin - base)))
        sph = ((ii - i) ** 2 + (jj - j) ** 2 + (kk - k) ** 2) * a.voxel ** 2 <= r * r
        hit = np.unique(vol[sph])
        assert not set(hit.tolist()) & {AIR, SKIN, NIPPLE, MUSCLE, MASS}, (i, j, k, hit)
        vol[sph] = MASS
        centres.append(((i, j, k), r, skin - base, skin - i))

    # world LPS: X = -VICTRE y, Y = -VICTRE x, Z = VICTRE z
    offset = np.array([-org[1], -org[0], org[2]])
    world = lambda i, j, k: offset + a.voxel * np.array([-j, -i, k])
    body = zlib.compress(np.ascontiguousarray(vol.transpose(2, 1, 0)).tobytes(), 9)
    fmt = lambda v: " ".join("%.4f" % x for x in v)
    hdr = ["ObjectType = Image", "NDims = 3", "BinaryData = True",
           "BinaryDataByteOrderMSB = False", "CompressedData = True",
           "CompressedDataSize = %d" % len(body),
           "TransformMatrix = 0 -1 0 -1 0 0 0 0 1", "Offset = " + fmt(offset),
           "CenterOfRotation = 0 0 0", "AnatomicalOrientation = PLI",
           "ElementSpacing = " + fmt([a.voxel] * 3),
           "DimSize = %d %d %d" % vol.shape, "ElementType = MET_UCHAR",
           "ElementDataFile = LOCAL"]
    with open(a.out, "wb") as fh:
        fh.write(("\n".join(hdr) + "\n").encode() + body)

    print("dims (i j k) = %d %d %d, voxel %.2f mm, %s: %d bytes" % (*vol.shape, a.voxel, a.out, os.path.getsize(a.out)))
    print("offset (LPS mm) = %s; i: chest wall -> nipple = world -Y (anterior)" % fmt(offset))
    for (i, j, k), r, thick, depth in centres:
        print("lesion r=%.1f mm at ijk (%d, %d, %d) = LPS (%s) mm; %d mm below the skin of %d mm of tissue"
              % (r, i, j, k, fmt(world(i, j, k)), depth * a.voxel, thick * a.voxel))
    labs, counts = np.unique(vol, return_counts=True)
    print("labels: " + ", ".join("%d:%d" % lc for lc in zip(labs, counts)))


if __name__ == "__main__":
    main()
