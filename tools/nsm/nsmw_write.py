#!/usr/bin/env python3
"""Writes a .nsmw weights file of random weights for a named NSM architecture (the file layout of
techniques/nsm/nsm_weights.h; docs/techniques/nsm.md). For the inference tests and benchmarks
only: trained weights come from tools/nsm/nsm_export.py.

    python3 tools/nsm/nsmw_write.py --arch nsm5 --seed 1 [--dtype f16] OUT.nsmw
"""
import argparse
import json
import struct

import numpy as np

ARCHS = {
    "nsm3": (3, [16, 32], 64),
    "nsm5": (5, [16, 32, 64, 128], 256),
    "nsm7e": (7, [16, 32, 64, 96, 128, 192], 256),
    "tiny": (3, [4, 8], 16),
}
FEATURES = ["z_over_zf", "z_minus_zf", "c_e_r", "d"]
FNV_OFFSET, FNV_PRIME = 0xCBF29CE484222325, 0x100000001B3


def conv_list(levels, widths, bottleneck, head=16, features=4):
    """(name, oc, ic, k) of every conv in the file's order (nsm_interfaces: the network order)."""
    out = []
    for l in range(levels - 1):
        cin = features if l == 0 else widths[l - 1]
        out += [(f"enc{l}.conv3", widths[l], cin, 3), (f"enc{l}.conv1", widths[l], widths[l], 1)]
    inner = widths[levels - 2]
    out += [("mid.conv3", bottleneck, inner, 3), ("mid.conv1", inner, bottleneck, 1)]
    for l in range(levels - 2, 0, -1):
        out += [(f"dec{l}.conv3", widths[l], widths[l], 3), (f"dec{l}.conv1", widths[l - 1], widths[l], 1)]
    out += [("dec0.conv3", widths[0], widths[0], 3), ("dec0.conv1", head, widths[0], 1), ("head.conv1", 1, head, 1)]
    return out


def fnv1a64(data: bytes) -> int:
    h, mask = FNV_OFFSET, (1 << 64) - 1
    for b in data:  # about 1 s for nsm5's 2.6 MB
        h = ((h ^ b) * FNV_PRIME) & mask
    return h


def random_tensors(levels, widths, bottleneck, seed, head=16, features=4):
    rng = np.random.default_rng(seed)
    tensors = []
    for name, oc, ic, k in conv_list(levels, widths, bottleneck, head, features):
        bound = 1.3 / np.sqrt(ic * k * k)  # keeps activations of order 1 through the levels
        tensors.append((name + ".weight", rng.uniform(-bound, bound, (oc, ic, k, k)).astype(np.float32)))
        tensors.append((name + ".bias", (0.1 * rng.uniform(-bound, bound, (oc,))).astype(np.float32)))
    return tensors


def write_nsmw(path, levels, widths, bottleneck, tensors, mean, std, dtype="f32", head=16,
               features=FEATURES, provenance=None):
    blobs = [t.astype("<f2" if dtype == "f16" else "<f4").tobytes() for _, t in tensors]
    header = {"levels": levels, "widths": widths, "bottleneck": bottleneck, "head": head,
              "features": list(features), "mean": [float(m) for m in mean],
              "std": [float(s) for s in std], "r_max": 0.3, "scale_ref": 3.12, "dtype": dtype,
              "tensors": [], "provenance": provenance or {"writer": "tools/nsm/nsmw_write.py"}}
    for _ in range(4):  # the offsets' digits change the header's length: iterate to a fixed point
        text = json.dumps(header, separators=(",", ":")).encode()
        at = (12 + len(text) + 63) // 64 * 64
        entries = []
        for (name, t), blob in zip(tensors, blobs):
            entries.append({"name": name, "shape": list(t.shape), "offset": at})
            at = (at + len(blob) + 63) // 64 * 64
        header["tensors"] = entries
    text = json.dumps(header, separators=(",", ":")).encode()
    out = bytearray(b"NSMW" + struct.pack("<II", 1, len(text)) + text)
    for entry, blob in zip(header["tensors"], blobs):
        out += b"\0" * (entry["offset"] - len(out))
        out += blob
    out += b"\0" * ((len(out) + 63) // 64 * 64 - len(out))
    out += struct.pack("<Q", fnv1a64(bytes(out)))
    with open(path, "wb") as f:
        f.write(out)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("out")
    p.add_argument("--arch", default="nsm5", choices=sorted(ARCHS))
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--dtype", default="f32", choices=["f32", "f16"])
    a = p.parse_args()
    levels, widths, bottleneck = ARCHS[a.arch]
    tensors = random_tensors(levels, widths, bottleneck, a.seed)
    if a.dtype == "f16":  # the stored values, so that both readers use the same fp32 weights
        tensors = [(n, t.astype(np.float16).astype(np.float32)) for n, t in tensors]
    write_nsmw(a.out, levels, widths, bottleneck, tensors, mean=[0.9, -0.1, 0.5, 2.0],
               std=[0.2, 0.3, 0.4, 1.5], dtype=a.dtype,
               provenance={"writer": "tools/nsm/nsmw_write.py", "arch": a.arch, "seed": a.seed})


if __name__ == "__main__":
    main()
