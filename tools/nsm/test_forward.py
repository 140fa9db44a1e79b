"""The PyTorch network against a float64 numpy forward written from the interfaces' text
(conv zero padding 1, ReLU, 2x2 average pool, bilinear x2 with weights 1/4 and 3/4 clamped at
the edges, skips added at levels >= 1 only, sigmoid head, standardized inputs)."""
import numpy as np
import torch

from nsm_model import build


def conv(x, w, b):
    """x [C, H, W], w [O, C, k, k] (k = 1 or 3, zero padding k // 2), b [O]."""
    k = w.shape[-1]
    p = k // 2
    c, h, wd = x.shape
    xp = np.zeros((c, h + 2 * p, wd + 2 * p))
    xp[:, p:p + h, p:p + wd] = x
    out = np.zeros((w.shape[0], h, wd)) + b[:, None, None]
    for ky in range(k):
        for kx in range(k):
            out += np.einsum("oc,chw->ohw", w[:, :, ky, kx], xp[:, ky:ky + h, kx:kx + wd])
    return out


def pool(x):
    return 0.25 * (x[:, 0::2, 0::2] + x[:, 1::2, 0::2] + x[:, 0::2, 1::2] + x[:, 1::2, 1::2])


def up_1d(x, axis):
    n = x.shape[axis]
    idx = np.arange(n)
    prev = np.take(x, np.maximum(idx - 1, 0), axis)
    nxt = np.take(x, np.minimum(idx + 1, n - 1), axis)
    even = 0.25 * prev + 0.75 * x  # output 2i sits at input i - 1/4
    odd = 0.75 * x + 0.25 * nxt    # output 2i + 1 sits at input i + 1/4
    out = np.stack([even, odd], axis + 1)
    shape = list(x.shape)
    shape[axis] *= 2
    return out.reshape(shape)


def up(x):
    return up_1d(up_1d(x, 1), 2)


def forward(p, levels, x, mean, std):
    relu = lambda v: np.maximum(v, 0)  # noqa: E731
    pair = lambda n, v: relu(conv(relu(conv(v, *p[n + ".conv3"])), *p[n + ".conv1"]))  # noqa: E731
    x = (x - mean[:, None, None]) / std[:, None, None]
    skips = []
    for l in range(levels - 1):
        e = pair(f"enc{l}", x)
        skips.append(e)
        x = pool(e)
    u = pair("mid", x)
    for l in range(levels - 2, 0, -1):
        u = pair(f"dec{l}", up(u) + skips[l])
    u = pair("dec0", up(u))
    return conv(u, *p["head.conv1"])  # the logits; the output is their sigmoid


def test_network_matches_the_numpy_forward_of_the_interfaces():
    for name, (h, w) in (("tiny", (12, 8)), ("nsm3", (8, 16))):
        net = build(name, seed=4)
        with torch.no_grad():
            for _, t in net.tensor_order():
                t.normal_(0.0, 0.3)  # non-zero biases; ReLUs neither all on nor all off
        mean = np.array([0.5, -0.25, 1.0, 2.0])
        std = np.array([2.0, 0.5, 1.5, 0.75])
        net.set_standardization(mean, std)
        x = np.random.Generator(np.random.PCG64(9)).normal(size=(4, h, w))
        params = {}
        for n, t in net.tensor_order():
            conv_name, kind = n.rsplit(".", 1)
            params.setdefault(conv_name, [None, None])[kind == "bias"] = t.detach().double().numpy()
        logits = []
        hook = net.head.conv1.register_forward_hook(lambda _m, _i, out: logits.append(out))
        want = forward(params, net.config.levels, x, mean, std)[0]
        with torch.no_grad():
            got = net(torch.from_numpy(x).float()[None])[0, 0].double().numpy()
        hook.remove()
        got_logits = logits[0][0, 0].double().numpy()
        scale = np.abs(want).max()
        assert want.std() > 0.1 * scale, name  # a varied output, so a difference would show
        # fp32 against float64: ~1e-7 of the scale here; structural differences are >> 1e-3
        assert np.abs(got_logits - want).max() < 1e-5 * scale, name
        assert np.abs(got - 1 / (1 + np.exp(-want))).max() < 1e-5, name
