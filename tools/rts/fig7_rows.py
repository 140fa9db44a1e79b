#!/usr/bin/env python3
"""Ray tracing + denoising, the third baseline of Neural Shadow Mapping's Fig. 7: rts rows on
the default scene at 1024 x 768 against the 256-spp reference, light radius 0, 0.15 and 0.3 m,
in the columns of docs/results/nsm.md's table.

    PYTHONPATH=build/python python3 tools/rts/fig7_rows.py
"""
import shadowlab as sl
print("| R | technique | RMSE | SSIM | FLIP | shadow ms |")
print("|---|---|---|---|---|---|")
for R in (0.0, 0.15, 0.3):
    sc = sl.scene("default", light_radius=R)
    g = sl.gbuffer(sc)
    ref = sl.reference(sc, spp=256, gbuffer=g)
    specs = ["rts:hard=1"] if R == 0 else ["rts:spp=1", "rts:spp=4", "rts:spp=1,denoise=atrous",
             "rts:spp=4,denoise=atrous", "rts:spp=1,denoise=atrous,sigma_v=4", "rts:spp=4,denoise=atrous,sigma_v=4",
             "rts:spp=16"]
    for s in specs:
        r = sl.render(sc, s, gbuffer=g, repeats=3)
        m = sl.metric(r.mask, ref.mask)
        print(f"| {R:g} | `{r.spec}` | {m['rmse']:.4f} | {m['ssim']:.4f} | {m['flip_mean']:.4f} | {r.times['shadow_ms']:.1f} |", flush=True)
