"""Reads one .nsmf frame file of the Neural Shadow Mapping data set and checks it.

The format (docs/programs/nsm_data.md): magic NSMF, u32 version 1, u32 header length H, H bytes
of JSON, zero padding to a multiple of 64, then the planes, each starting at a multiple of 64
(little-endian, row-major, y down): for copy 0..3 every feature of the header (float32, W*H)
then the coverage (uint8, W*H); then one float32 reference plane per radius. The last 8 bytes
are the FNV-1a 64 of every byte before them.

Usage: python3 tools/nsm/nsmf_check.py FILE.nsmf   (prints the header and plane statistics;
exit 1 when the file is malformed or its hash does not match)
"""
import json
import struct
import sys

import numpy as np

FNV_OFFSET = 0xCBF29CE484222325
FNV_PRIME = 0x100000001B3
MASK = 0xFFFFFFFFFFFFFFFF


def fnv1a64(data: bytes) -> int:
    """FNV-1a 64 of the bytes (a plain loop: seconds for a full-size frame)."""
    h = FNV_OFFSET
    for b in data:
        h = ((h ^ b) * FNV_PRIME) & MASK
    return h


def align64(n: int) -> int:
    return (n + 63) // 64 * 64


class NsmfError(ValueError):
    pass


def read_nsmf(path, check_hash=True):
    """Returns (header dict, {"copies": [{"features": {name: HxW f32}, "coverage": HxW u8}] * 4,
    "reference": {radius: HxW f32}}). Raises NsmfError on any inconsistency."""
    with open(path, "rb") as f:
        data = f.read()
    if len(data) < 12 + 8 or data[:4] != b"NSMF":
        raise NsmfError("not an .nsmf file (magic)")
    version, hlen = struct.unpack_from("<II", data, 4)
    if version != 1:
        raise NsmfError(f"version {version}, expected 1")
    if 12 + hlen > len(data) - 8:
        raise NsmfError("header length past the end")
    header = json.loads(data[12:12 + hlen].decode("utf-8"))
    if any(data[12 + hlen:align64(12 + hlen)]):
        raise NsmfError("non-zero header padding")
    stored = struct.unpack_from("<Q", data, len(data) - 8)[0]
    if check_hash and fnv1a64(data[:-8]) != stored:
        raise NsmfError("FNV-1a hash mismatch")
    w, h = header["width"], header["height"]
    n = w * h
    pos = align64(12 + hlen)

    def plane(dtype, size):
        nonlocal pos
        end = pos + n * size
        if end > len(data) - 8:
            raise NsmfError("planes past the end of the file")
        a = np.frombuffer(data, dtype=dtype, count=n, offset=pos).reshape(h, w)
        pos = align64(end)
        return a

    copies = []
    for _ in range(header["copies"]):
        feats = {name: plane("<f4", 4) for name in header["features"]}
        copies.append({"features": feats, "coverage": plane("u1", 1)})
    reference = {r: plane("<f4", 4) for r in header["radii"]}
    if pos != len(data) - 8:
        raise NsmfError(f"{len(data) - 8 - pos} unexpected bytes before the hash")
    for c in copies:
        cov = c["coverage"]
        if not np.isin(cov, (0, 1)).all():
            raise NsmfError("coverage other than 0/1")
        for name, a in c["features"].items():
            if not np.isfinite(a).all():
                raise NsmfError(f"non-finite {name}")
            if (a[cov == 0] != 0).any():
                raise NsmfError(f"{name} non-zero on an uncovered pixel")
    for r, a in reference.items():
        if not ((a >= 0) & (a <= 1)).all():
            raise NsmfError(f"reference at radius {r} outside [0, 1]")
    return header, {"copies": copies, "reference": reference}


def main(argv):
    if len(argv) != 2:
        print(__doc__.strip().splitlines()[-3], file=sys.stderr)
        return 2
    try:
        header, planes = read_nsmf(argv[1])
    except (OSError, NsmfError, ValueError, KeyError) as e:
        print(f"nsmf_check: {argv[1]}: {e}", file=sys.stderr)
        return 1
    print(json.dumps(header))
    for i, c in enumerate(planes["copies"]):
        cov = c["coverage"].astype(bool)
        for name, a in c["features"].items():
            v = a[cov]
            lo, hi = (float(v.min()), float(v.max())) if v.size else (0.0, 0.0)
            print(f"copy {i} {name:>11}: min {lo:.6g} max {hi:.6g}")
    for r, a in planes["reference"].items():
        print(f"reference R={r}: mean {float(a.mean()):.4f}")
    print("ok: hash matches")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
