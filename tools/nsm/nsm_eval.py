#!/usr/bin/env python3
"""Error of a trained network on each split of a data set (docs/techniques/nsm.md,
"Generalization"): the masked L1 of copy 0's output against the ray-traced reference over the
covered pixels that face the light (c_e > 0; the technique writes 0 on the others), per split
and per light radius, beside two baselines computed from the same frames:
  - hard: the plain base map's depth test with a 1 % relative bias, z / z_f >= 0.99 (what the
    network starts from, without any filtering);
  - constant: the best constant output of that split and radius (the median of the reference).
The train split is sampled every `--train-every`-th frame (it is large and seen in training).

  python3 tools/nsm/nsm_eval.py --data DATASET --weights FILE [--json OUT]
"""
import argparse
import json
import sys

import numpy as np
import torch

import nsm_export
from nsm_data import Dataset
from nsm_loss import centre_mask, ssim_map

PROGRAM = "nsm_eval"


def split_errors(model, features, frames, multiple):
    """{radius: (network L1, hard L1, constant L1, pixels, network SSIM)} pooled over the frames
    (SSIM: nsm_loss's 11x11 local SSIM against the reference, averaged over the same pixels
    at least 5 from the crop's edge)."""
    acc = {}
    with torch.no_grad():
        for fr in frames:
            h, w = fr.height // multiple * multiple, fr.width // multiple * multiple
            c_e = np.array(fr.feature(0, "c_e")[:h, :w]) if "c_e" in fr.features else None
            cov = np.array(fr.coverage(0)[:h, :w]) != 0
            if c_e is not None:
                cov &= c_e > 0
            zr = np.array(fr.feature(0, "z_over_zf")[:h, :w])
            for k, radius in enumerate(fr.radii):
                x = torch.from_numpy(fr.inputs(0, features, k, 0, 0, h, w))[None]
                y = model(x)[0, 0].numpy().astype(np.float64)
                t = np.array(fr.reference(k)[:h, :w], np.float64)
                hard = (zr >= 0.99).astype(np.float64)
                a = acc.setdefault(radius, [0.0, 0.0, [], 0, 0.0, 0])
                a[0] += float(np.abs(y - t)[cov].sum())
                s = ssim_map(torch.from_numpy(y.astype(np.float32))[None, None],
                             torch.from_numpy(t.astype(np.float32))[None, None])[0, 0].numpy()
                c = centre_mask(cov)
                a[4] += float(s[c].sum())
                a[5] += int(c.sum())
                a[1] += float(np.abs(hard - t)[cov].sum())
                a[2].append(t[cov])
                a[3] += int(cov.sum())
    out = {}
    for radius, (net, hard, refs, n, ssim, ns) in sorted(acc.items()):
        ref = np.concatenate(refs)
        const = float(np.abs(ref - np.median(ref)).mean()) if n else float("nan")
        out[radius] = (net / n, hard / n, const, n, ssim / ns if ns else float("nan"))
    return out


def main(argv=None):
    p = argparse.ArgumentParser(prog=PROGRAM, description=__doc__.splitlines()[0])
    p.add_argument("--data", required=True)
    p.add_argument("--weights", required=True)
    p.add_argument("--train-every", type=int, default=5)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--json", help="write the table as JSON here")
    a = p.parse_args(argv)
    torch.set_num_threads(a.threads)
    model, header = nsm_export.load_model(a.weights)
    model.eval()
    features = header["features"]
    ds = Dataset(a.data)
    table = {}
    for split in ("train", "val", "test"):
        frames = ds.frames(split)
        if split == "train":
            frames = frames[::a.train_every]
        if not frames:
            continue
        scenes = sorted({f.scene for f in frames})
        table[split] = {"frames": len(frames), "scenes": scenes,
                        "radii": split_errors(model, features, frames, model.config.multiple)}
    print(f"{'split':6s} {'frames':>6s} {'radius':>7s} {'network':>8s} {'hard':>8s} {'constant':>8s} {'ssim':>8s}")
    for split, t in table.items():
        for radius, (net, hard, const, n, ssim) in t["radii"].items():
            print(f"{split:6s} {t['frames']:6d} {radius:7.3f} {net:8.4f} {hard:8.4f} {const:8.4f} {ssim:8.4f}")
        nets = [v[0] * v[3] for v in t["radii"].values()]
        ns = [v[3] for v in t["radii"].values()]
        ssim = np.mean([v[4] for v in t["radii"].values()])  # every radius has the same pixels
        print(f"{split:6s} {t['frames']:6d} {'all':>7s} {sum(nets) / sum(ns):8.4f} {'':8s} {'':8s} {ssim:8.4f}"
              f"   scenes: {', '.join(t['scenes'])}")
    if a.json:
        with open(a.json, "w") as f:
            json.dump({s: {"frames": t["frames"], "scenes": t["scenes"],
                           "radii": {str(r): dict(zip(("network", "hard", "constant", "pixels", "ssim"), v))
                                     for r, v in t["radii"].items()}} for s, t in table.items()},
                      f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
