"""The loss: SSIM against a brute force, the perturbation term, where its gradient goes."""
import math

import numpy as np
import pytest
import torch

import nsm_loss
from nsm_model import build


def ssim_brute(a, b, r=5, sigma=1.5):
    """Wang et al.'s SSIM at every valid centre, in float64, from the window's definition."""
    w = np.array([[math.exp(-((i - r) ** 2 + (j - r) ** 2) / (2 * sigma * sigma))
                   for j in range(2 * r + 1)] for i in range(2 * r + 1)])
    w /= w.sum()
    h, wd = a.shape
    out = np.zeros((h - 2 * r, wd - 2 * r))
    for y in range(r, h - r):
        for x in range(r, wd - r):
            pa, pb = a[y - r:y + r + 1, x - r:x + r + 1], b[y - r:y + r + 1, x - r:x + r + 1]
            ma, mb = (w * pa).sum(), (w * pb).sum()
            va, vb = (w * (pa - ma) ** 2).sum(), (w * (pb - mb) ** 2).sum()
            cv = (w * (pa - ma) * (pb - mb)).sum()
            c1, c2 = 0.01 ** 2, 0.03 ** 2
            out[y - r, x - r] = (2 * ma * mb + c1) * (2 * cv + c2) / ((ma * ma + mb * mb + c1) * (va + vb + c2))
    return out


def test_ssim_map_matches_the_brute_force():
    g = torch.Generator().manual_seed(1)
    a = torch.rand(1, 1, 17, 15, generator=g, dtype=torch.float64)
    b = (a + 0.2 * torch.rand(1, 1, 17, 15, generator=g, dtype=torch.float64)).clamp(0, 1)
    got = nsm_loss.ssim_map(a, b)[0, 0].numpy()
    want = ssim_brute(a[0, 0].numpy(), b[0, 0].numpy())
    assert got.shape == want.shape == (7, 5)
    assert np.abs(got - want).max() < 1e-9


def test_ssim_of_identical_images_is_one_and_of_constants_is_closed_form():
    a = torch.rand(2, 1, 20, 20)
    assert torch.allclose(nsm_loss.ssim_map(a, a), torch.ones(2, 1, 10, 10), atol=1e-6)
    x, y = 0.3, 0.7
    s = nsm_loss.ssim_map(torch.full((1, 1, 11, 11), x, dtype=torch.float64),
                          torch.full((1, 1, 11, 11), y, dtype=torch.float64))
    assert float(s) == pytest.approx((2 * x * y + 1e-4) / (x * x + y * y + 1e-4), rel=1e-12)


def test_pair_loss_weights_and_mask():
    y = torch.zeros(1, 1, 12, 12)
    t = torch.ones(1, 1, 12, 12)
    m = torch.ones(1, 1, 12, 12)
    s = (1e-4) / (1 + 1e-4)  # SSIM of constants 0 and 1
    assert float(nsm_loss.pair_loss(y, t, m)) == pytest.approx(0.9 * 1 + 0.1 * (1 - s), rel=1e-6)
    m0 = torch.zeros(1, 1, 12, 12)
    assert float(nsm_loss.pair_loss(y, t, m0)) == pytest.approx(0.1, rel=1e-6)  # nothing covered



def test_without_the_structural_term_the_loss_is_the_masked_l1_plus_cross_entropy():
    net = build("tiny", seed=0)
    x, cov, t = batch(seed=3)
    with torch.no_grad():
        z = net.logits(x[0]).double().numpy()
    y = 1 / (1 + np.exp(-z))
    tt, m = t.double().numpy(), cov[0].double().numpy()
    l1 = (np.abs(y - tt) * m).sum() / m.sum()
    bce = ((np.logaddexp(0, z) - tt * z) * m).sum() / m.sum()  # BCE with logits, by hand
    loss, parts = nsm_loss.nsm_loss(net, x, cov, t, perturbation=0.0, alpha=1.0)
    assert float(loss) == pytest.approx(l1 + bce, rel=1e-5)
    with_ssim, _ = nsm_loss.nsm_loss(net, x, cov, t, perturbation=0.0)
    assert abs(float(with_ssim) - (0.9 * l1 + bce)) > 1e-3  # the default does weigh SSIM in


def batch(seed=0, identical=False):
    g = torch.Generator().manual_seed(seed)
    x = torch.rand(4, 2, 4, 16, 16, generator=g)
    if identical:
        x[1:] = x[0]
    cov = torch.ones(4, 2, 1, 16, 16)
    cov[:, :, :, :3, :] = 0
    return x, cov, torch.rand(2, 1, 16, 16, generator=g)


def test_perturbation_term_is_zero_for_identical_copies():
    net = build("tiny", seed=0)
    x, cov, t = batch(identical=True)
    _, parts = nsm_loss.nsm_loss(net, x, cov, t)
    assert parts["perturbation"] == 0.0
    _, parts = nsm_loss.nsm_loss(net, *batch(identical=False))
    assert parts["perturbation"] > 0.0


def test_gradient_reaches_the_weights_only_through_x0():
    net = build("tiny", seed=0)
    x, cov, t = batch()
    x.requires_grad_(True)
    got = []  # per forward: did its output receive a gradient?

    def hook(_m, _i, out):
        flag = [False]
        got.append(flag)
        if out.requires_grad:
            out.register_hook(lambda g: flag.__setitem__(0, bool(g.abs().sum() > 0)))

    h = net.head.conv1.register_forward_hook(hook)  # every forward ends there, logits or not
    loss, _ = nsm_loss.nsm_loss(net, x, cov, t)
    loss.backward()
    h.remove()
    assert [f[0] for f in got] == [True, False, False, False]
    assert float(x.grad[0].abs().sum()) > 0 and float(x.grad[1:].abs().sum()) == 0
    # the weight gradients are those of the loss with the perturbed outputs as constants
    grads = [p.grad.clone() for p in net.parameters()]
    net.zero_grad()
    xd = x.detach()
    with torch.no_grad():
        consts = [net(xd[i]) for i in range(1, 4)]
    z0 = net.logits(xd[0])
    x0 = torch.sigmoid(z0)
    # the cross-entropy term written out: -(t log x0 + (1 - t) log(1 - x0)), masked mean
    bce = -(t * torch.log(x0) + (1 - t) * torch.log(1 - x0))
    bce = (bce * cov[0]).sum() / cov[0].sum()
    ref = (nsm_loss.pair_loss(x0, t, cov[0]) + bce +
           nsm_loss.perturbation_term(x0, consts, cov[0], list(cov[1:])))
    ref.backward()
    for g, p in zip(grads, net.parameters()):
        assert torch.allclose(g, p.grad, rtol=1e-5, atol=1e-8)
