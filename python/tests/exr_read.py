"""A reader of single-part scanline OpenEXR files, independent of shadowlab's (OpenEXR's C++
library): the header's channel list and data window, then each chunk inflated (zlib), its
predictor undone and its two byte halves interleaved back, as the OpenEXR file layout
specifies for ZIP and ZIPS compression; uncompressed files too. Returns {channel: array}.
"""
import struct
import zlib

import numpy as np

_LINES = {0: 1, 2: 1, 3: 16}          # NONE, ZIPS, ZIP: scanlines per chunk
_TYPES = {0: np.uint32, 1: np.float16, 2: np.float32}


def _undo_zip(raw, size):
    data = zlib.decompress(raw)
    if len(data) != size:
        raise ValueError(f"chunk inflates to {len(data)} bytes, expected {size}")
    t = np.frombuffer(data, dtype=np.uint8).astype(np.int32)
    # predictor: each byte stored as the difference to the previous one, plus 128
    t = (np.cumsum(np.concatenate([t[:1], t[1:] - 128])) & 0xFF).astype(np.uint8)
    half = (size + 1) // 2
    out = np.empty(size, dtype=np.uint8)
    out[0::2] = t[:half]
    out[1::2] = t[half:]
    return out.tobytes()


def read_exr(path):
    b = open(path, "rb").read()
    if b[:4] != b"\x76\x2f\x31\x01":
        raise ValueError(f"{path}: not an OpenEXR file")
    flags = struct.unpack_from("<I", b, 4)[0]
    if flags & 0x200 or flags & 0x1000:
        raise ValueError(f"{path}: tiled or multi-part")
    p = 8
    attrs = {}
    while b[p] != 0:
        e = b.index(b"\0", p)
        name = b[p:e].decode()
        p = e + 1
        e = b.index(b"\0", p)
        p = e + 1
        size = struct.unpack_from("<i", b, p)[0]
        p += 4
        attrs[name] = b[p:p + size]
        p += size
    p += 1
    channels = []
    c = attrs["channels"]
    q = 0
    while c[q] != 0:
        e = c.index(b"\0", q)
        name = c[q:e].decode()
        ptype = struct.unpack_from("<i", c, e + 1)[0]
        channels.append((name, _TYPES[ptype]))
        q = e + 1 + 16
    xmin, ymin, xmax, ymax = struct.unpack("<4i", attrs["dataWindow"])
    w, h = xmax - xmin + 1, ymax - ymin + 1
    comp = attrs["compression"][0]
    per = _LINES[comp]
    chunks = (h + per - 1) // per
    offsets = struct.unpack_from(f"<{chunks}Q", b, p)
    line_bytes = sum(w * np.dtype(t).itemsize for _, t in channels)
    planes = {name: np.empty((h, w), dtype=t) for name, t in channels}
    for i, off in enumerate(offsets):
        y0, size = struct.unpack_from("<ii", b, off)
        lines = min(per, ymax + 1 - y0)
        expected = lines * line_bytes
        raw = b[off + 8:off + 8 + size]
        data = raw if (comp == 0 or size == expected) else _undo_zip(raw, expected)
        o = 0
        for line in range(lines):
            for name, t in channels:
                n = w * np.dtype(t).itemsize
                planes[name][y0 - ymin + line] = np.frombuffer(data[o:o + n], dtype=t)
                o += n
    return planes
