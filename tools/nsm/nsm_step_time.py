#!/usr/bin/env python3
"""Time per training step (forward + backward of x0, 3 no_grad forwards of the perturbed
copies, SSIM, Adam) for each named configuration, on a synthetic 256x192 data set written to
a temporary folder. Prints the median of the timed steps after the warm-up ones.

    python3 tools/nsm/nsm_step_time.py [--configs tiny,nsm3,nsm5] [--batch 8] [--crop 128]
        [--threads 2] [--steps 8] [--warmup 2]
"""
import argparse
import os
import sys
import tempfile
import time

import numpy as np
import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import nsm_synthetic  # noqa: E402
from nsm_data import Dataset, Sampler, feature_stats  # noqa: E402
from nsm_loss import nsm_loss  # noqa: E402
from nsm_model import build, macs_per_pixel  # noqa: E402
from nsm_train import cpu_model, setup_torch  # noqa: E402


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--configs", default="tiny,nsm3,nsm5")
    p.add_argument("--batch", type=int, default=8)
    p.add_argument("--crop", type=int, default=128)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--steps", type=int, default=8)
    p.add_argument("--warmup", type=int, default=2)
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as d:
        nsm_synthetic.write_dataset(d, n_train=4, n_val=0, w=256, h=192)
        frames = Dataset(d).frames("train")
        mean, std = feature_stats(frames)
        print(f"cpu {cpu_model()[0]} ({cpu_model()[1]}), {a.threads} threads, batch {a.batch}, "
              f"crop {a.crop}, torch {torch.__version__}, mkldnn {torch.backends.mkldnn.is_available()}")
        for name in a.configs.split(","):
            setup_torch(1, a.threads)
            net = build(name)
            net.set_standardization(mean, std)
            opt = torch.optim.Adam(net.parameters(), lr=1e-3)
            sampler = Sampler(frames, a.crop, net.config.multiple, 1)
            times = []
            for i in range(a.warmup + a.steps):
                x, cov, t = (torch.from_numpy(v) for v in sampler.batch(a.batch))
                t0 = time.perf_counter()
                loss, _ = nsm_loss(net, x, cov, t)
                opt.zero_grad(set_to_none=True)
                loss.backward()
                opt.step()
                if i >= a.warmup:
                    times.append(time.perf_counter() - t0)
            ms = 1000 * float(np.median(times))
            gmac = 6 * macs_per_pixel(net) * a.batch * a.crop * a.crop / 1e9
            print(f"{name}: {ms:.0f} ms/step (median of {a.steps}; min {1000 * min(times):.0f}, "
                  f"max {1000 * max(times):.0f}), ~{gmac:.2f} GMAC/step (6 forward-equivalents) "
                  f"= {gmac / ms * 1000:.1f} GMAC/s")


if __name__ == "__main__":
    main()
