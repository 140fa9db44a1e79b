#!/usr/bin/env python3
"""An independent PyTorch reference of the NSM network (docs/techniques/nsm.md, "Network and
inference"), built from F.conv2d calls on the weights of a .nsmw file, for checking the C++
forward pass (techniques/nsm/nsm_network.h). It does not import tools/nsm/nsm_model.py, so the
two Python definitions check each other too.

forward(w, planes, dtype): the network in float64 or float32.
bound(w, planes): per pixel, a float64 bound on |fp32 result − exact result| for any
implementation whose convolutions are chains of at most n = ic·k·k + 1 rounded operations
(spec §6 "Correctness bound"): a "magnitude network" carries (x, e) through the layers,
    conv:     e' = |W| * e + γ_n (|W| * (|x| + e) + |b|),   γ_n = n·u / (1 − n·u), u = 2^−24
    ReLU:     e' = e
    pool:     e' = pool(e) + γ_3 pool(|x| + e)
    up:       e' = up(e) + γ_5 up(|x| + e)            (two blends of weights 3/4 and 1/4)
    skip add: e' = e_a + e_b + u (|a| + |b| + e_a + e_b)
    sigmoid:  e' = e / 4 + 4u σ(x)                    (expf, one add, one division)
    input:    e  = 2.001 u |x|                        ((f − mean) / std: two roundings)
"""
import json
import struct

import numpy as np
import torch
import torch.nn.functional as F

U = 2.0 ** -24


def gamma(n):
    return n * U / (1 - n * U)


def read_nsmw(path):
    """The header and the tensors (float32 numpy arrays by name) of a .nsmw file, checked."""
    data = open(path, "rb").read()
    assert data[:4] == b"NSMW", "magic"
    version, hlen = struct.unpack_from("<II", data, 4)
    assert version == 1, "version"
    h, mask = 0xCBF29CE484222325, (1 << 64) - 1
    for b in data[:-8]:
        h = ((h ^ b) * 0x100000001B3) & mask
    assert h == struct.unpack_from("<Q", data, len(data) - 8)[0], "checksum"
    header = json.loads(data[12:12 + hlen])
    dt = "<f2" if header["dtype"] == "f16" else "<f4"
    tensors = {}
    for t in header["tensors"]:
        count = int(np.prod(t["shape"]))
        arr = np.frombuffer(data, dtype=dt, count=count, offset=t["offset"]).astype(np.float32)
        tensors[t["name"]] = arr.reshape(t["shape"])
    return header, tensors


class Weights:
    def __init__(self, path):
        self.header, self.tensors = read_nsmw(path)
        self.levels = self.header["levels"]
        self.mean = np.array(self.header["mean"], dtype=np.float32)
        self.std = np.array(self.header["std"], dtype=np.float32)

    def conv(self, name, dtype):
        w = torch.from_numpy(self.tensors[name + ".weight"]).to(dtype)
        b = torch.from_numpy(self.tensors[name + ".bias"]).to(dtype)
        return w, b


def padded_input(w, planes, dtype):
    """(1, F, Hp, Wp) standardized planes, edge-replicated to a multiple of 2^(L−1)."""
    f = torch.from_numpy(planes.astype(np.float32)).to(dtype)[None]
    mean = torch.from_numpy(w.mean).to(dtype)[None, :, None, None]
    std = torch.from_numpy(w.std).to(dtype)[None, :, None, None]
    x = (f - mean) / std
    m = 2 ** (w.levels - 1)
    H, W = planes.shape[1:]
    ph, pw = (H + m - 1) // m * m, (W + m - 1) // m * m
    if (ph, pw) != (H, W):
        x = F.pad(x, (0, pw - W, 0, ph - H), mode="replicate")
    return x


def up(x):
    return F.interpolate(x, scale_factor=2, mode="bilinear", align_corners=False)


def forward(w, planes, dtype=torch.float64):
    """The network on planes (F, H, W) -> (H, W) numpy in `dtype`'s precision."""
    H, W = planes.shape[1:]
    L = w.levels
    x = padded_input(w, planes, dtype)

    def pair(x, name, relu_last=True):
        x = F.relu(F.conv2d(x, *w.conv(name + ".conv3", dtype), padding=1))
        x = F.conv2d(x, *w.conv(name + ".conv1", dtype))
        return F.relu(x) if relu_last else x

    with torch.no_grad():
        skips = {}
        for l in range(L - 1):
            x = pair(x, f"enc{l}")
            skips[l] = x
            x = F.avg_pool2d(x, 2)
        u = pair(x, "mid")
        for l in range(L - 2, 0, -1):
            u = pair(up(u) + skips[l], f"dec{l}")
        u = pair(up(u), "dec0")
        y = torch.sigmoid(F.conv2d(u, *w.conv("head.conv1", dtype)))
    return y[0, 0, :H, :W].double().numpy()


def bound(w, planes):
    """Per pixel (H, W): the float64 bound on an fp32 forward pass's error (module docstring)."""
    d = torch.float64
    H, W = planes.shape[1:]
    L = w.levels
    x = padded_input(w, planes, d)
    e = 2.001 * U * x.abs()

    def conv(x, e, name, relu):
        wt, b = w.conv(name, d)
        n = wt.shape[1] * wt.shape[2] * wt.shape[3] + 1
        pad = wt.shape[2] // 2
        y = F.conv2d(x, wt, b, padding=pad)
        mag = F.conv2d(x.abs() + e, wt.abs(), b.abs(), padding=pad)
        e = F.conv2d(e, wt.abs(), padding=pad) + gamma(n) * mag
        return (F.relu(y) if relu else y), e

    def pair(x, e, name):
        x, e = conv(x, e, name + ".conv3", True)
        return conv(x, e, name + ".conv1", True)

    def pool(x, e):
        return F.avg_pool2d(x, 2), F.avg_pool2d(e, 2) + gamma(3) * F.avg_pool2d(x.abs() + e, 2)

    def upsample(x, e):
        return up(x), up(e) + gamma(5) * up(x.abs() + e)

    with torch.no_grad():
        skips = {}
        for l in range(L - 1):
            x, e = pair(x, e, f"enc{l}")
            skips[l] = (x, e)
            x, e = pool(x, e)
        x, e = pair(x, e, "mid")
        for l in range(L - 2, 0, -1):
            ux, ue = upsample(x, e)
            sx, se = skips[l]
            x = ux + sx
            e = ue + se + U * (ux.abs() + sx.abs() + ue + se)
            x, e = pair(x, e, f"dec{l}")
        x, e = upsample(x, e)
        x, e = pair(x, e, "dec0")
        x, e = conv(x, e, "head.conv1", False)
        s = torch.sigmoid(x)
        e = e / 4 + 4 * U * s
    return e[0, 0, :H, :W].numpy()


def _conv(w, x, e, name, relu):
    """One conv in float64 with its (value, error bound), as in bound()."""
    wt, b = w.conv(name, torch.float64)
    n = wt.shape[1] * wt.shape[2] * wt.shape[3] + 1
    pad = wt.shape[2] // 2
    y = F.conv2d(x, wt, b, padding=pad)
    mag = F.conv2d(x.abs() + e, wt.abs(), b.abs(), padding=pad)
    e = F.conv2d(e, wt.abs(), padding=pad) + gamma(n) * mag
    return (F.relu(y) if relu else y), e


def _pair(w, x, e, name):
    x, e = _conv(w, x, e, name + ".conv3", True)
    return _conv(w, x, e, name + ".conv1", True)


def pass_checks(w, planes, tensors, output):
    """Each pass of the C++ forward from the C++'s own stored inputs (`tensors`: name -> numpy
    [h][w][c] fp32, as nsm_forward --dump writes them; `output` (H, W)), in float64 with the
    bound of that pass alone (module docstring, started from e = 0). Returns a list of
    (pass name, max |C++ − torch64|, max bound, max |err|/bound, pixels over the bound)."""
    d = torch.float64
    L = w.levels
    H, W = planes.shape[1:]

    def t(name):
        a = tensors[name]
        return torch.from_numpy(a.astype(np.float64)).permute(2, 0, 1)[None]

    rows = []

    def check(name, got, ref, e):
        err = (got - ref).abs()
        ratio = err / e
        rows.append((name, float(err.max()), float(e.max()), float(ratio.max()),
                     int((err > e).sum())))

    with torch.no_grad():
        x = padded_input(w, planes, d)
        check("input", t("input"), x, 2.001 * U * x.abs())
        for l in range(L - 1):
            src = t("input") if l == 0 else t(f"pool{l - 1}")
            y, e = _pair(w, src, torch.zeros_like(src), f"enc{l}")
            if l > 0:
                check(f"enc{l}", t(f"enc{l}"), y, e)
            p = F.avg_pool2d(y, 2)
            pe = F.avg_pool2d(e, 2) + gamma(3) * F.avg_pool2d(y.abs() + e, 2)
            check(f"pool{l}", t(f"pool{l}"), p, pe)
        src = t(f"pool{L - 2}")
        y, e = _pair(w, src, torch.zeros_like(src), "mid")
        check("mid", t("mid"), y, e)
        for l in range(L - 2, -1, -1):
            u = t("mid") if l == L - 2 else t(f"dec{l + 1}")
            ux = up(u)
            ue = gamma(5) * up(u.abs())
            if l > 0:
                s = t(f"enc{l}")
                x = ux + s
                e = ue + U * (ux.abs() + s.abs() + ue)
            else:
                x, e = ux, ue
            y, e = _pair(w, x, e, f"dec{l}")
            if l > 0:
                check(f"dec{l}", t(f"dec{l}"), y, e)
        y, e = _conv(w, y, e, "head.conv1", False)
        s = torch.sigmoid(y)
        e = e / 4 + 4 * U * s
        got = torch.from_numpy(output.astype(np.float64))
        check("dec0+head", got, s[0, 0, :H, :W], e[0, 0, :H, :W])
    return rows
