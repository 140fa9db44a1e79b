"""Writes and reads the .nsmw weights file (docs/techniques/nsm.md).

Layout, little-endian: magic "NSMW", u32 version 1, u32 header length, the JSON header, zero
padding to a multiple of 64, the tensors in network order (each conv's weight [oc][ic][kh][kw]
then its bias [oc]), each 64-byte aligned, then the FNV-1a 64 of every byte before it.
Tensor offsets count from the file start. f16 tensors are IEEE binary16 (round to nearest
even from the fp32 weights); the reader decodes them to fp32, which is exact.
"""
import json
import math
import os
import struct
import sys

import numpy as np

from nsm_fnv import fnv1a64
from nsm_model import HEAD_WIDTH, NetConfig, NsmNet, tensor_shapes

MAGIC = b"NSMW"
VERSION = 1
R_MAX = 0.3
SCALE_REF = 3.12
MAX_HEADER = 1 << 20


class WeightsError(Exception):
    """str() is "<file>: <reason>"."""


def align64(n):
    return (n + 63) // 64 * 64


def json_safe(v):
    """Provenance values as strict JSON: a non-finite float becomes its name ("nan", "inf")."""
    if isinstance(v, float) and not math.isfinite(v):
        return str(v)
    if isinstance(v, dict):
        return {str(k): json_safe(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [json_safe(x) for x in v]
    return v


def encode(model, features, dtype="f16", provenance=None):
    """The bytes of a .nsmw for `model` (its mean/std buffers are the standardization)."""
    if dtype not in ("f32", "f16"):
        raise ValueError("dtype must be f32 or f16")
    cfg = model.config
    np_dtype = np.dtype("<f2") if dtype == "f16" else np.dtype("<f4")
    arrays = [(n, t.detach().cpu().numpy().astype(np.float32)) for n, t in model.tensor_order()]
    for n, a in arrays:
        if not np.isfinite(a).all():
            raise ValueError(f"tensor {n} has non-finite values")
        if dtype == "f16" and np.abs(a).max(initial=0.0) > 65504.0:
            raise ValueError(f"tensor {n} exceeds binary16's range (65504)")
    blobs = [(n, a.shape, a.astype(np_dtype).tobytes()) for n, a in arrays]
    mean = [float(v) for v in model.mean.detach().cpu().numpy().astype(np.float32)]
    std = [float(v) for v in model.std.detach().cpu().numpy().astype(np.float32)]
    start = 0
    while True:  # offsets depend on the header length, which depends on the offsets' digits
        offsets, pos = [], start
        for _, _, b in blobs:
            pos = align64(pos)
            offsets.append(pos)
            pos += len(b)
        header = {"levels": cfg.levels, "widths": list(cfg.widths), "bottleneck": cfg.bottleneck,
                  "head": cfg.head, "features": list(features), "mean": mean, "std": std,
                  "r_max": R_MAX, "scale_ref": SCALE_REF, "dtype": dtype,
                  "tensors": [{"name": n, "shape": list(s), "offset": o}
                              for (n, s, _), o in zip(blobs, offsets)],
                  "provenance": json_safe(provenance or {})}
        hj = json.dumps(header, allow_nan=False).encode()
        data_start = align64(12 + len(hj))
        if data_start == start:
            break
        start = data_start
    out = bytearray(MAGIC + struct.pack("<II", VERSION, len(hj)) + hj)
    for (_, _, b), o in zip(blobs, offsets):
        out.extend(b"\0" * (o - len(out)))
        out.extend(b)
    out.extend(struct.pack("<Q", fnv1a64(bytes(out))))
    return bytes(out)


def write(path, model, features, dtype="f16", provenance=None):
    data = encode(model, features, dtype, provenance)
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(data)
    os.replace(tmp, path)  # never a half-written weights file under the final name
    return data


def decode(data, name="<bytes>"):
    """(header, {tensor name: float32 array}) from .nsmw bytes; every check before use."""
    if len(data) < 12 + 8 or data[:4] != MAGIC:
        raise WeightsError(f"{name}: not an NSMW file (bad magic)")
    version, hlen = struct.unpack("<II", data[4:12])
    if version != VERSION:
        raise WeightsError(f"{name}: version {version}, expected {VERSION}")
    if hlen == 0 or hlen > MAX_HEADER or 12 + hlen + 8 > len(data):
        raise WeightsError(f"{name}: header length {hlen} does not fit the file")
    if fnv1a64(data[:-8]) != struct.unpack("<Q", data[-8:])[0]:
        raise WeightsError(f"{name}: FNV-1a 64 checksum mismatch (corrupt or truncated)")
    try:
        h = json.loads(data[12:12 + hlen].decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as e:
        raise WeightsError(f"{name}: header is not JSON ({e})")
    if h.get("dtype") not in ("f32", "f16"):
        raise WeightsError(f"{name}: dtype must be f32 or f16")
    size = 2 if h["dtype"] == "f16" else 4
    np_dtype = "<f2" if size == 2 else "<f4"
    expected = expected_shapes(h, name)
    tensors = {}
    body_end = len(data) - 8
    entries = h.get("tensors")
    if not isinstance(entries, list) or len(entries) != len(expected):
        raise WeightsError(f"{name}: expected {len(expected)} tensors")
    for e, (ename, eshape) in zip(entries, expected):
        if not isinstance(e, dict) or e.get("name") != ename or e.get("shape") != list(eshape):
            raise WeightsError(f"{name}: tensor {ename} {list(eshape)} expected, found {e}")
        off = e.get("offset")
        n = math.prod(eshape) * size
        if not isinstance(off, int) or off % 64 or off < align64(12 + hlen) or off + n > body_end:
            raise WeightsError(f"{name}: tensor {ename} offset {off} is not valid")
        tensors[ename] = np.frombuffer(data, np_dtype, math.prod(eshape), off) \
            .astype(np.float32).reshape(eshape)
    return h, tensors


def expected_shapes(h, name="<bytes>"):
    try:
        cfg = NetConfig(int(h["levels"]), tuple(int(w) for w in h["widths"]), int(h["bottleneck"]),
                        int(h["head"]), len(h["features"]))
    except (KeyError, TypeError, ValueError) as e:
        raise WeightsError(f"{name}: architecture fields missing or invalid ({e})")
    if cfg.head != HEAD_WIDTH or min(cfg.widths + (cfg.bottleneck,)) < 1 or cfg.levels > 12 \
            or max(cfg.widths + (cfg.bottleneck,)) > 4096:
        raise WeightsError(f"{name}: architecture out of range")
    return tensor_shapes(cfg)


def read(path):
    with open(path, "rb") as f:
        return decode(f.read(), path)


def load_model(path):
    """An NsmNet with the file's weights and standardization."""
    import torch
    h, tensors = read(path)
    net = NsmNet(NetConfig(h["levels"], tuple(h["widths"]), h["bottleneck"], h["head"],
                           len(h["features"])))
    with torch.no_grad():
        for n, t in net.tensor_order():
            t.copy_(torch.from_numpy(tensors[n]))
        net.set_standardization(h["mean"], h["std"])
    return net, h


if __name__ == "__main__":
    hdr, ts = read(sys.argv[1])
    print(json.dumps({k: v for k, v in hdr.items() if k != "tensors"}, indent=1))
    print(f"{len(ts)} tensors, {sum(t.size for t in ts.values())} values")
