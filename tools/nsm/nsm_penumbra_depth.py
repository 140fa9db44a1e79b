#!/usr/bin/env python3
"""Error against penumbra width for networks of different depth (supplemental Figs. 3/4,
docs/results/nsm.md "Tables 4/5"): is a network accurate only where its receptive field
covers the penumbra?

Each (frame, soft radius R) of the chosen splits is a case. Its penumbra width is predicted,
not measured: at every covered pixel facing the light that the base map says is occluded
(z / z_f < 0.99), the width of the penumbra cast by the map's blocker onto a receiver facing
the light is

    w = 2R (z_f - z) / z                      (light diameter times receiver-to-blocker over
                                               blocker distance; z, z_f from the light)

in metres, and in screen pixels w / (d tan(fov_y / 2) 2 / H) at the pixel's view depth d
(the receiver seen face on: an upper bound on its projected size). The case's width is the
95th percentile of w over those pixels, as in the paper. Cases are binned by that width and,
per bin and network, the L1 against the ray-traced reference is pooled over the penumbra
pixels (0.02 < reference < 0.98, covered, facing the light) and over every covered pixel
facing the light.

The receptive field of each network is measured: the extent of the input pixels whose
gradient at the centre output is non-zero (random weights, float64).

  python3 tools/nsm/nsm_penumbra_depth.py --data DATASET --weights nsm3=A.nsmw,nsm5=B.nsmw
"""
import argparse
import json
import math
import sys

import numpy as np
import torch

import nsm_export
from nsm_data import Dataset
from nsm_model import build

PROGRAM = "nsm_penumbra_depth"

# Vertical field of view of each built-in scene's camera (scenes/*.cpp, `camera.fov_y_deg`);
# nsm_data's trajectories move the eye but keep the field of view.
SCENE_FOV_Y_DEG = {"default": 60.0, "plane": 60.0, "grazing": 55.0, "contact": 55.0,
                   "depth_range": 60.0, "cluttered": 60.0, "room100k": 60.0, "foliage": 50.0,
                   "bunny": 30.0}
BIN_EDGES = (0.0, 4.0, 8.0, 16.0, 32.0, 64.0, 128.0, math.inf)
PENUMBRA = (0.02, 0.98)


def receptive_field(config, size=None):
    """Side in pixels of the square of inputs that reach the centre output (random weights)."""
    torch.manual_seed(0)
    net = build(config).double()
    m = net.config.multiple
    size = size or max(16 * m, 256)  # the field is 2^(L+2) - 2 px: 30, 126, 510
    x = torch.randn(1, net.config.features, size, size, dtype=torch.float64, requires_grad=True)
    y = net.logits(x)
    y[0, 0, size // 2, size // 2].backward()
    g = x.grad[0].abs().sum(0).numpy()
    ys, xs = np.nonzero(g)
    return int(max(ys.max() - ys.min(), xs.max() - xs.min()) + 1)


def width_px_per_metre(fr):
    """95th percentile, over the frame's occluded covered pixels facing the light, of the
    predicted penumbra width in pixels for a light of radius 1 m (the width is proportional to
    R, so a radius's case width is R times this); None if no pixel is occluded."""
    fov = SCENE_FOV_Y_DEG.get(fr.scene)
    if fov is None:
        raise SystemExit(f"{PROGRAM}: frame of scene '{fr.scene}': unknown field of view "
                         f"(known: {', '.join(sorted(SCENE_FOV_Y_DEG))})")
    H = fr.header["frame_size"][1]
    z = np.array(fr.feature(0, "z"), np.float64)
    zf = np.array(fr.feature(0, "z_f"), np.float64)
    d = np.array(fr.feature(0, "d"), np.float64)
    c_e = np.array(fr.feature(0, "c_e"), np.float64)
    cov = np.array(fr.coverage(0)) != 0
    occluded = cov & (c_e > 0) & (z < 0.99 * zf) & (z > 0) & (d > 0)
    if not occluded.any():
        return None
    z, zf, d = z[occluded], zf[occluded], d[occluded]
    w_m = 2.0 * (1.0 / fr.scale) * (zf - z) / z             # scene units (metres / s)
    px = d * 2.0 * math.tan(math.radians(fov) / 2.0) / H    # scene units per pixel
    return float(np.percentile(w_m / px, 95))


def bin_of(w):
    for i in range(len(BIN_EDGES) - 1):
        if BIN_EDGES[i] <= w < BIN_EDGES[i + 1]:
            return i
    return len(BIN_EDGES) - 2


def main(argv=None):
    p = argparse.ArgumentParser(prog=PROGRAM, description=__doc__.splitlines()[0])
    p.add_argument("--data", required=True)
    p.add_argument("--weights", required=True, help="LABEL=FILE,... (one column per network)")
    p.add_argument("--splits", default="val,test")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--json", help="write the table as JSON here")
    a = p.parse_args(argv)
    torch.set_num_threads(a.threads)
    nets = []
    for item in a.weights.split(","):
        label, _, path = item.partition("=")
        if not path:
            raise SystemExit(f"{PROGRAM}: --weights: '{item}' is not LABEL=FILE")
        model, header = nsm_export.load_model(path)
        model.eval()
        nets.append((label, model, header["features"]))
    needed = {"z", "z_f", "d", "c_e"}
    ds = Dataset(a.data)
    frames = [f for s in a.splits.split(",") for f in ds.frames(s)]
    if frames and not needed <= set(frames[0].features):
        raise SystemExit(f"{PROGRAM}: --data: frames lack {sorted(needed - set(frames[0].features))}")
    nb = len(BIN_EDGES) - 1
    # per bin: cases, then per network [penumbra abs sum, penumbra n, all abs sum, all n]
    acc = [[0, [[0.0, 0, 0.0, 0] for _ in nets]] for _ in range(nb)]
    with torch.no_grad():
        for fr in frames:
            per_metre = width_px_per_metre(fr)
            if per_metre is None:
                continue
            cov_full = (np.array(fr.coverage(0)) != 0) & (np.array(fr.feature(0, "c_e")) > 0)
            for k, radius in enumerate(fr.radii):
                if radius <= 0:
                    continue
                b = bin_of(radius * per_metre)
                acc[b][0] += 1
                t_full = np.array(fr.reference(k), np.float64)
                for j, (label, model, feats) in enumerate(nets):
                    m = model.config.multiple
                    h, wd = fr.height // m * m, fr.width // m * m
                    x = torch.from_numpy(fr.inputs(0, feats, k, 0, 0, h, wd))[None]
                    y = model(x)[0, 0].numpy().astype(np.float64)
                    t, cov = t_full[:h, :wd], cov_full[:h, :wd]
                    pen = cov & (t > PENUMBRA[0]) & (t < PENUMBRA[1])
                    e = np.abs(y - t)
                    s = acc[b][1][j]
                    s[0] += float(e[pen].sum()); s[1] += int(pen.sum())
                    s[2] += float(e[cov].sum()); s[3] += int(cov.sum())
    rf = {label: receptive_field(model.config) for label, model, _ in nets}
    labels = [n[0] for n in nets]
    print("receptive field (px): " + ", ".join(f"{l} {rf[l]}" for l in labels))
    print(f"{'width (px)':>12s} {'cases':>5s} " + " ".join(f"{l:>15s}" for l in labels))
    print(f"{'':>12s} {'':>5s} " + " ".join(f"{'penumbra  all':>15s}" for _ in labels))
    rows = []
    for b in range(nb):
        cases, per = acc[b]
        if not cases:
            continue
        lo, hi = BIN_EDGES[b], BIN_EDGES[b + 1]
        rng = f"{lo:g}-{hi:g}" if hi != math.inf else f">={lo:g}"
        cells = []
        for s in per:
            cells.append((s[0] / s[1] if s[1] else float("nan"), s[2] / s[3] if s[3] else float("nan"), s[1]))
        print(f"{rng:>12s} {cases:5d} " + " ".join(f"{c[0]:7.4f} {c[1]:7.4f}" for c in cells))
        rows.append({"width_px": [lo, None if hi == math.inf else hi], "cases": cases,
                     "networks": {l: {"l1_penumbra": c[0], "l1_all": c[1], "penumbra_pixels": c[2]}
                                  for l, c in zip(labels, cells)}})
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"receptive_field_px": rf, "splits": a.splits, "rows": rows}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
