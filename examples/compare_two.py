#!/usr/bin/env python3
"""Two shadow techniques against the ray-traced reference, in memory: the error of each
(1 - the metric's total, and mean FLIP) against its shadow time over map resolutions, and the
masks beside the reference's. Writes compare_two.png into --out.

    PYTHONPATH=build/python python3 examples/compare_two.py --out out/compare_two
"""
import argparse
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

import shadowlab as sl


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="out/compare_two")
    ap.add_argument("--first", default="csm:pcf=3", help="a technique spec without res")
    ap.add_argument("--second", default="cpcss", help="a technique spec without res")
    ap.add_argument("--quick", action="store_true", help="320x240, 64 spp, 3 resolutions")
    args = ap.parse_args()
    first, second = args.first, args.second
    size = dict(width=320, height=240) if args.quick else {}
    resolutions = [128, 256, 512] if args.quick else [128, 256, 512, 1024]
    scene = sl.scene("default", **size)
    g = sl.gbuffer(scene)
    ref = sl.reference(scene, spp=64 if args.quick else 256, gbuffer=g)

    fig, axes = plt.subplots(1, 4, figsize=(16, 3.6))
    for spec in (first, second):
        times, errors, flips = [], [], []
        for res in resolutions:
            sep = "," if ":" in spec else ":"
            r = sl.render(scene, f"{spec}{sep}res={res}", gbuffer=g, repeats=3)
            m = sl.metric(r, ref)
            times.append(r.times["shadow_ms"])
            errors.append(1.0 - m["total"])
            flips.append(m["flip_mean"])
            print(f"{r.spec:24s} {r.times['shadow_ms']:8.2f} ms  total {m['total']:.3f}  "
                  f"FLIP {m['flip_mean']:.4f}")
        axes[0].plot(times, errors, "o-", label=spec)
        axes[1].plot(times, flips, "o-", label=spec)
        for t, e, res in zip(times, errors, resolutions):
            axes[0].annotate(str(res), (t, e), fontsize=7)
        last = r
        axes[2 if spec == first else 3].imshow(last.mask, cmap="gray", vmin=0, vmax=1)
        axes[2 if spec == first else 3].set_title(f"{last.spec} mask")
    for ax, name in ((axes[0], "1 - total"), (axes[1], "mean FLIP")):
        ax.set_xscale("log")
        ax.set_xlabel("shadow time, ms (log)")
        ax.set_ylabel(name)
        ax.legend()
    for ax in axes[2:]:
        ax.axis("off")
    fig.suptitle(f"{scene.name} {scene.width}x{scene.height}, reference {ref.spec}")
    fig.tight_layout()
    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, "compare_two.png")
    fig.savefig(path, dpi=80)
    print("wrote", path)


if __name__ == "__main__":
    main()
