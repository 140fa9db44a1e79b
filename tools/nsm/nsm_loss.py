"""The training loss: L(y, t) = 0.9 |y - t| + 0.1 (1 - SSIM(y, t)), masked by coverage.

The paper's structural term is a VGG-19 perceptual loss, whose ImageNet weights cannot be
downloaded here; SSIM (11x11 Gaussian window, sigma 1.5, C1 = 0.01^2, C2 = 0.03^2, data
range 1: metric/ssim.h's constants) stands in for it as the term that rewards matching local
structure (edges, penumbra shape) rather than per-pixel values. The SSIM map covers the valid
window centres only (no padding), and is averaged over centres whose pixel is covered.

The whole loss (Datta et al. 2022, Eq. 2, with a cross-entropy term added to the first part):
L(x0, target) + BCE(z0, target) + lambda sum_i L(x0, x_i), z0 the logits of x0 = sigmoid(z0),
x_i the outputs on the 3 perturbed copies, evaluated under no_grad so gradients reach the
weights through x0 only. The cross-entropy on the logits keeps a gradient where the sigmoid
saturates: with L1 + SSIM alone, Adam drove nsm5's logits to +inf within ~20 steps on the
mostly lit data set (output 1.0 everywhere, zero gradient from then on).
"""
import math

import torch
import torch.nn.functional as F

ALPHA = 0.9
SSIM_WINDOW = 11
SSIM_SIGMA = 1.5
SSIM_C1 = 0.01 ** 2
SSIM_C2 = 0.03 ** 2


def gaussian_1d(size=SSIM_WINDOW, sigma=SSIM_SIGMA):
    r = size // 2
    w = torch.tensor([math.exp(-(i - r) ** 2 / (2.0 * sigma * sigma)) for i in range(size)],
                     dtype=torch.float64)
    return w / w.sum()


def _blur(x, g):
    """Valid separable Gaussian blur as a fixed-order sum of shifted slices (its backward is
    cheap, where a 1-channel conv2d's backward was most of a tiny network's step)."""
    n = g.numel()
    w = x.shape[-1] - n + 1
    h = x.shape[-2] - n + 1
    y = g[0] * x[..., :, 0:w]
    for i in range(1, n):
        y = y + g[i] * x[..., :, i:i + w]
    z = g[0] * y[..., 0:h, :]
    for i in range(1, n):
        z = z + g[i] * y[..., i:i + h, :]
    return z


def ssim_map(a, b):
    """[N, 1, H, W] pair -> [N, 1, H - 10, W - 10] local SSIM at the valid window centres."""
    g = gaussian_1d().to(a.dtype)  # normalized in float64, then rounded once
    n = a.shape[0]
    stats = _blur(torch.cat([a, b, a * a, b * b, a * b]), g)
    ma, mb, aa, bb, ab = stats[:n], stats[n:2 * n], stats[2 * n:3 * n], stats[3 * n:4 * n], stats[4 * n:]
    va, vb, cov = aa - ma * ma, bb - mb * mb, ab - ma * mb
    num = (2 * ma * mb + SSIM_C1) * (2 * cov + SSIM_C2)
    den = (ma * ma + mb * mb + SSIM_C1) * (va + vb + SSIM_C2)
    return num / den


def masked_mean(v, m):
    return (v * m).sum() / m.sum().clamp_min(1.0)


def centre_mask(m):
    r = SSIM_WINDOW // 2
    return m[..., r:-r, r:-r]


def pair_loss(y, t, mask, alpha=ALPHA):
    """alpha * masked L1 + (1 - alpha) * (1 - masked mean SSIM)."""
    l1 = masked_mean((y - t).abs(), mask)
    if alpha == 1.0:
        return l1
    s = masked_mean(ssim_map(y, t), centre_mask(mask))
    return alpha * l1 + (1.0 - alpha) * (1.0 - s)


def perturbation_term(x0, perturbed, cov0, covs, alpha=ALPHA):
    """sum_i L(x0, x_i) over the perturbed outputs (given as constants), each masked by the
    pixels covered in both copies."""
    total = x0.new_zeros(())
    for xi, ci in zip(perturbed, covs):
        total = total + pair_loss(x0, xi, cov0 * ci, alpha)
    return total


def nsm_loss(model, x, cov, target, perturbation=1.0, alpha=ALPHA):
    """perturbation: the weight of the perturbation term (0: none; 1: Eq. 2's); alpha: the L1
    share of L (1: no structural term).
    x [4, N, F, h, w] (copy 0, then the perturbed copies), cov [4, N, 1, h, w],
    target [N, 1, h, w]. Returns (loss, dict of float parts)."""
    z0 = model.logits(x[0])
    x0 = torch.sigmoid(z0)
    bce = masked_mean(F.binary_cross_entropy_with_logits(z0, target, reduction="none"), cov[0])
    main = pair_loss(x0, target, cov[0], alpha) + bce
    loss = main
    parts = {"main": float(main), "bce": float(bce),
             "l1": float(masked_mean((x0 - target).abs(), cov[0]))}
    if perturbation:
        with torch.no_grad():
            outs = [model(x[i]) for i in range(1, x.shape[0])]
        pert = perturbation_term(x0, outs, cov[0], [cov[i] for i in range(1, x.shape[0])], alpha)
        loss = loss + float(perturbation) * pert
        parts["perturbation"] = float(pert)
    return loss, parts
