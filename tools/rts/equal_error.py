#!/usr/bin/env python3
"""rts: error against samples per pixel, raw and denoised, and the equal-error sample count
(how many raw samples give the denoised error), per scene and light, against a 1024-spp
reference; printed as the Markdown tables of docs/results/rts.md.

    PYTHONPATH=build/python python3 tools/rts/equal_error.py [--width 512 --height 384]
"""
import argparse
import math
import time

import shadowlab as sl

SCENES = ["default", "foliage", "bunny", "grazing", "contact", "depth_range", "cluttered"]
RAW = [1, 2, 4, 8, 16, 32, 64]
DENOISED = [1, 2, 4, 8]


def equal_error_spp(raw, target):
    """The raw spp whose RMSE is `target`, interpolated in log-log between measured points
    (None beyond the measured range)."""
    pts = sorted(raw.items())
    for (s0, e0), (s1, e1) in zip(pts, pts[1:]):
        if e0 >= target >= e1 and e0 > e1:
            t = (math.log(e0) - math.log(target)) / (math.log(e0) - math.log(e1))
            return math.exp(math.log(s0) + t * (math.log(s1) - math.log(s0)))
    return None if target < pts[-1][1] else float(pts[0][0]) * (pts[0][1] / target) ** 2


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--width", type=int, default=512)
    ap.add_argument("--height", type=int, default=384)
    ap.add_argument("--ref-spp", type=int, default=1024)
    ap.add_argument("--sigma-v", default="1", help="the a-trous value term's scale (the key sigma_v)")
    a = ap.parse_args()
    print(f"{a.width}x{a.height}, reference rt:spp={a.ref_spp}, sigma_v={a.sigma_v}, {sl.threads()} threads, "
          f"shadowlab {sl.version()}\n")
    print("| scene | light radius | raw RMSE at 1 / 4 / 16 / 64 spp | denoised RMSE at 1 / 2 / 4 / 8 spp "
          "| equal-error raw spp (× the denoised spp) | rays/s, M | denoiser ms / rays ms at 4 spp |")
    print("|---|---|---|---|---|---|---|")
    ratios = []
    for name in SCENES:
        base = sl.scene(name, width=a.width, height=a.height)
        for radius in (base.light_radius, 0.15):
            if radius <= 0:
                continue
            scene = sl.scene(name, width=a.width, height=a.height, light_radius=radius)
            g = sl.gbuffer(scene)
            ref = sl.reference(scene, spp=a.ref_spp, gbuffer=g)
            raw = {s: sl.metric(sl.render(scene, f"rts:spp={s}", gbuffer=g).mask, ref.mask)["rmse"]
                   for s in RAW}
            den, cells, cost = {}, [], ""
            for s in DENOISED:
                r = sl.render(scene, f"rts:spp={s},denoise=atrous,sigma_v={a.sigma_v}", gbuffer=g, repeats=3)
                den[s] = sl.metric(r.mask, ref.mask)["rmse"]
                eq = equal_error_spp(raw, den[s])
                cells.append("—" if eq is None else f"{eq:.1f} ({eq / s:.1f}×)")
                if eq is not None:
                    ratios.append(eq / s)
                if s == 4:
                    t = r.times
                    rays = r.work["rays"]
                    cost = (f"{rays / (t['rays_ms'] * 1e3):.1f} | "
                            f"{t['denoise_ms']:.1f} / {t['rays_ms']:.1f}")
            print(f"| {name} | {radius:.3g} | " + " / ".join(f"{raw[s]:.4f}" for s in (1, 4, 16, 64))
                  + " | " + " / ".join(f"{den[s]:.4f}" for s in DENOISED) + " | "
                  + " / ".join(cells) + f" | {cost} |", flush=True)
    if ratios:
        ratios.sort()
        print(f"\nequal-error ratio over every scene, light and spp: median {ratios[len(ratios) // 2]:.1f}×, "
              f"range {ratios[0]:.1f}–{ratios[-1]:.1f}×")


if __name__ == "__main__":
    t0 = time.time()
    main()
    print(f"({time.time() - t0:.0f} s)")
