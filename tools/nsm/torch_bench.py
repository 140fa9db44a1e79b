#!/usr/bin/env python3
"""Times PyTorch's CPU forward pass of the NSM network on the weights of a .nsmw file (the same
network as build/programs/nsm_forward --repeats N; docs/techniques/nsm.md, "Network and
inference"): eager NCHW, eager channels_last, and torch.jit.trace + freeze +
optimize_for_inference, all under inference_mode with torch.set_num_threads(THREADS); batch 1,
fp32, random standardized inputs. Prints the median of --repeats after --warmup runs, GMAC/s and
the bytes of every intermediate tensor the eager pass allocates.

    python3 tools/nsm/torch_bench.py --weights nsm5.nsmw [--width 1024 --height 768]
"""
import argparse
import os
import platform
import statistics
import sys
import time

import torch
import torch.nn as nn
import torch.nn.functional as F

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import torch_reference  # noqa: E402


class Net(nn.Module):
    """The network as nn.Conv2d modules (so that freezing can fold and fuse them)."""

    def __init__(self, w):
        super().__init__()
        self.levels = w.levels
        self.convs = nn.ModuleDict()
        for key in w.tensors:
            if key.endswith(".weight"):
                name = key[:-len(".weight")]
                t = torch.from_numpy(w.tensors[key])
                c = nn.Conv2d(t.shape[1], t.shape[0], t.shape[2], padding=t.shape[2] // 2)
                c.weight.data.copy_(t)
                c.bias.data.copy_(torch.from_numpy(w.tensors[name + ".bias"]))
                self.convs[name.replace(".", "_")] = c
        self.register_buffer("mean", torch.from_numpy(w.mean)[None, :, None, None])
        self.register_buffer("std", torch.from_numpy(w.std)[None, :, None, None])
        self.count = None  # a list: the eager pass appends each intermediate's bytes

    def _t(self, x):
        if self.count is not None:
            self.count.append(x.numel() * x.element_size())
        return x

    def _pair(self, x, name):
        x = self._t(F.relu(self._t(self.convs[name + "_conv3"](x))))
        return self._t(F.relu(self._t(self.convs[name + "_conv1"](x))))

    def forward(self, f):
        x = self._t((f - self.mean) / self.std)
        skips = []
        for l in range(self.levels - 1):
            x = self._pair(x, f"enc{l}")
            skips.append(x)
            x = self._t(F.avg_pool2d(x, 2))
        u = self._pair(x, "mid")
        for l in range(self.levels - 2, 0, -1):
            u = self._pair(self._t(self._t(F.interpolate(u, scale_factor=2.0, mode="bilinear", align_corners=False)) + skips[l]), f"dec{l}")
        u = self._pair(self._t(F.interpolate(u, scale_factor=2.0, mode="bilinear", align_corners=False)), "dec0")
        return self._t(torch.sigmoid(self._t(self.convs["head_conv1"](u))))


def time_it(fn, x, warmup, repeats):
    for _ in range(warmup):
        fn(x)
    t = []
    for _ in range(repeats):
        s = time.perf_counter()
        fn(x)
        t.append((time.perf_counter() - s) * 1e3)
    return statistics.median(t), min(t), max(t)


def cpu_model():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--weights", required=True)
    p.add_argument("--width", type=int, default=1024)
    p.add_argument("--height", type=int, default=768)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--repeats", type=int, default=11)
    p.add_argument("--warmup", type=int, default=3)
    a = p.parse_args()
    torch.set_num_threads(a.threads)
    w = torch_reference.Weights(a.weights)
    net = Net(w).eval()
    m = 2 ** (w.levels - 1)
    assert a.width % m == 0 and a.height % m == 0, f"size must be a multiple of {m}"
    g = torch.Generator().manual_seed(1)
    f = (torch.randn(1, len(w.mean), a.height, a.width, generator=g) * net.std + net.mean).contiguous()
    macs = 0.0
    for key, t in w.tensors.items():
        if key.endswith(".weight"):
            name = key[:-len(".weight")]
            level = w.levels - 1 if name.startswith("mid") else (0 if name.startswith("head") else int(name[3]))
            macs += t.size * a.width * a.height / 4 ** level
    with torch.inference_mode():
        net.count = []
        net(f)
        act_bytes = sum(net.count)
        net.count = None
    print(f"torch {torch.__version__}, {a.threads} threads, CPU {cpu_model()}, mkldnn "
          f"{torch.backends.mkldnn.is_available()}; {a.width}x{a.height}, {macs * 1e-9:.3f} GMAC, "
          f"eager intermediates {act_bytes * 1e-6:.1f} MB")
    results = {}
    with torch.inference_mode():
        results["eager NCHW"] = time_it(net, f, a.warmup, a.repeats)
        net_cl = Net(w).eval().to(memory_format=torch.channels_last)
        f_cl = f.contiguous(memory_format=torch.channels_last)
        results["eager channels_last"] = time_it(net_cl, f_cl, a.warmup, a.repeats)
    with torch.no_grad():
        traced = torch.jit.trace(Net(w).eval(), f)
        frozen = torch.jit.optimize_for_inference(torch.jit.freeze(traced.eval()))
    with torch.inference_mode():
        results["jit trace+freeze+optimize_for_inference"] = time_it(frozen, f, a.warmup, a.repeats)
    for name, (med, lo, hi) in results.items():
        print(f"{name:42s} median {med:9.2f} ms  min {lo:9.2f}  max {hi:9.2f}  {macs * 1e-6 / med:7.1f} GMAC/s")
    best = min(results, key=lambda k: results[k][0])
    print(f"fastest: {best}, {results[best][0]:.2f} ms")
    # A STREAM-like copy at the same thread count: 256 MiB copied, read + write bytes per second
    # (the memory bandwidth a memory-bound forward could reach).
    src = torch.ones(64 << 20)
    dst = torch.empty_like(src)
    times = []
    for _ in range(a.warmup + a.repeats):
        t0 = time.perf_counter()
        dst.copy_(src)
        times.append(time.perf_counter() - t0)
    gbs = 2 * src.numel() * 4 / statistics.median(times[a.warmup:]) * 1e-9
    print(f"stream copy (torch copy_ of 256 MiB, {a.threads} threads): {gbs:.1f} GB/s")


if __name__ == "__main__":
    main()
