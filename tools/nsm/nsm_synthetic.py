"""A tiny synthetic NSM data set in the documented on-disk format, written with numpy alone
(the tests' fixture; no C++ build needed).

The target is a known function of the features, so a network can learn it from them: the
visibility is a soft step of z - z_f whose width grows with the light radius,
    v = clip(0.5 + (z - z_f) / (0.02 + 0.5 R), 0, 1),
with z - z_f a random-phase pattern of shadowed and lit patches over a smooth receiver. The perturbed
copies add a small deterministic jitter to every feature. Some pixels are uncovered (all
features 0, coverage 0, target 0).
"""
import json
import os
import struct

import numpy as np

from nsm_fnv import fnv1a64

FEATURES = ("d", "c_c", "z_minus_zf", "c_e_r", "z_over_zf")  # file order differs from the net's
RADII = (0.0, 0.03, 0.1, 0.2, 0.3)
# W*H is not a multiple of 16, so both the coverage planes and the last fp32 plane end off a
# 64-byte boundary: the padding between planes and before the hash is exercised.
W, H = 58, 42


def align64(n):
    return (n + 63) // 64 * 64


def target_of(z_minus_zf, radius):
    return np.clip(0.5 + z_minus_zf / (0.02 + 0.5 * radius), 0.0, 1.0).astype(np.float32)


def frame_planes(rng, w, h):
    yy, xx = np.mgrid[0:h, 0:w].astype(np.float64)
    z_f = 2.0 + 0.01 * xx + 0.005 * yy
    # Occluders: a random-phase pattern of shadowed and lit patches, about half of each.
    fx, fy = rng.uniform(0.15, 0.3, 2)
    px, py = rng.uniform(0, 2 * np.pi, 2)
    z = z_f + 0.2 * np.sin(fx * xx + px) * np.cos(fy * yy + py)
    c_e = 0.3 + 0.6 * np.cos(0.05 * xx)
    d = 1.0 + 0.02 * yy
    c_c = 0.8 - 0.001 * xx
    cov = np.ones((h, w), np.uint8)
    cov[: h // 8, : w // 4] = 0  # an uncovered corner
    copies = []
    for c in range(4):
        jitter = 0.0 if c == 0 else 0.002 * rng.standard_normal((h, w))
        zc = z + jitter
        feats = {"d": d, "c_c": c_c, "z_minus_zf": zc - z_f, "c_e_r": c_e, "z_over_zf": zc / z_f}
        planes = [np.where(cov != 0, feats[n], 0.0).astype(np.float32) for n in FEATURES]
        copies.append((planes, cov.copy()))
    refs = [np.where(cov != 0, target_of((z - z_f).astype(np.float32), r), 0).astype(np.float32)
            for r in RADII]
    return copies, refs


def write_frame(path, index, seed, w, h, pad_tail=False):
    rng = np.random.Generator(np.random.PCG64([seed, index]))
    copies, refs = frame_planes(rng, w, h)
    header = {"width": w, "height": h, "features": list(FEATURES), "copies": 4,
              "radii": list(RADII), "spp": 16, "scene": "synthetic", "frame": index,
              "seed": seed, "crop": [0, 0, w, h], "scale": 1.0}
    hj = json.dumps(header).encode()
    out = bytearray(b"NSMF" + struct.pack("<II", 1, len(hj)) + hj)

    def put(arr):
        out.extend(b"\0" * (align64(len(out)) - len(out)))
        out.extend(arr.astype(arr.dtype.newbyteorder("<")).tobytes())

    for planes, cov in copies:
        for p in planes:
            put(p)
        put(cov)
    for r in refs:
        put(r)
    if pad_tail:
        out.extend(b"\0" * (align64(len(out)) - len(out)))
    h64 = fnv1a64(bytes(out))
    out.extend(struct.pack("<Q", h64))
    with open(path, "wb") as f:
        f.write(out)
    return h64


def write_dataset(folder, n_train=6, n_val=2, w=W, h=H, seed=7):
    os.makedirs(os.path.join(folder, "frames"), exist_ok=True)
    names, hashes = [], []
    for i in range(n_train + n_val):
        name = f"{i:06d}.nsmf"
        hashes.append(write_frame(os.path.join(folder, "frames", name), i, seed, w, h,
                                  pad_tail=(i % 2 == 1)))
        names.append(name)
    ds_hash = fnv1a64(b"".join(struct.pack("<Q", x) for x in hashes))
    manifest = {"command": "nsm_synthetic", "commit": "none", "hash": f"{ds_hash:016x}",
                "splits": {"train": names[:n_train], "val": names[n_train:], "test": []},
                "scenes": {"train": ["synthetic"], "val": ["synthetic"], "test": []}}
    with open(os.path.join(folder, "manifest.json"), "w") as f:
        json.dump(manifest, f, indent=1)
    return folder


if __name__ == "__main__":
    import sys
    if len(sys.argv) != 2:
        sys.exit("usage: nsm_synthetic.py OUT_FOLDER  (writes the tests' synthetic data set)")
    write_dataset(sys.argv[1])
