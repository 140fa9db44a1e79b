"""The Neural Shadow Mapping network: the single Python definition (docs/techniques/nsm.md).

A UNet trimmed as in Datta et al. 2022: per level one 3x3 conv and one 1x1 conv, average
pooling down, bilinear x2 up, skips merged by sum, no skip at level 0, ReLU after every conv
but the last, a sigmoid output. The C++ inference implements the same math; the tensor names
and their order (`tensor_order`) are those of the .nsmw weights file.
"""
from dataclasses import dataclass

import torch
import torch.nn as nn
import torch.nn.functional as F

# The network's default input, in this order (the 4 pruned features of the paper's Table 1).
DEFAULT_FEATURES = ("z_over_zf", "z_minus_zf", "c_e_r", "d")
# Every candidate feature nsm_data can store (techniques/nsm/nsm_features.h), in its order.
CANDIDATE_FEATURES = ("d", "z", "z_f", "c_e", "c_c", "n_x", "n_y", "n_z", "z_minus_zf", "z_over_zf",
                      "cc_over_d", "c_e_r")
HEAD_WIDTH = 16


@dataclass(frozen=True)
class NetConfig:
    levels: int        # L >= 2
    widths: tuple      # C_0 .. C_{L-2}
    bottleneck: int    # B
    head: int = HEAD_WIDTH
    features: int = len(DEFAULT_FEATURES)

    def __post_init__(self):
        if self.levels < 2 or len(self.widths) != self.levels - 1:
            raise ValueError("levels L >= 2 needs L-1 widths")

    @property
    def multiple(self):
        """Input height and width must be multiples of this (2^(L-1))."""
        return 2 ** (self.levels - 1)


CONFIGS = {
    "nsm3": NetConfig(3, (16, 32), 64),
    "nsm3e": NetConfig(3, (16, 48), 128),
    "nsm5": NetConfig(5, (16, 32, 64, 128), 256),
    "nsm7": NetConfig(7, (16, 32, 64, 128, 256, 512), 1024),
    "nsm7e": NetConfig(7, (16, 32, 64, 96, 128, 192), 256),
    "tiny": NetConfig(3, (4, 8), 16),
}


class ConvPair(nn.Module):
    """A 3x3 conv (zero padding 1) and a 1x1 conv, each with bias, each followed by ReLU."""

    def __init__(self, cin, cmid, cout):
        super().__init__()
        self.conv3 = nn.Conv2d(cin, cmid, 3, padding=1)
        self.conv1 = nn.Conv2d(cmid, cout, 1)

    def forward(self, x):
        return F.relu(self.conv1(F.relu(self.conv3(x))))


class Head(nn.Module):
    def __init__(self, cin):
        super().__init__()
        self.conv1 = nn.Conv2d(cin, 1, 1)

    def forward(self, x):
        return torch.sigmoid(self.conv1(x))


def up2(x):
    """Bilinear x2 (weights 1/4 and 3/4, edge-clamped)."""
    return F.interpolate(x, scale_factor=2, mode="bilinear", align_corners=False)


class NsmNet(nn.Module):
    """Input [N, F, H, W] raw features (standardized inside with the stored mean/std), output
    [N, 1, H, W] visibility in (0, 1). H and W must be multiples of config.multiple."""

    def __init__(self, config: NetConfig):
        super().__init__()
        self.config = config
        c, L = config.widths, config.levels
        self.register_buffer("mean", torch.zeros(config.features))
        self.register_buffer("std", torch.ones(config.features))
        for l in range(L - 1):
            cin = config.features if l == 0 else c[l - 1]
            setattr(self, f"enc{l}", ConvPair(cin, c[l], c[l]))
        self.mid = ConvPair(c[L - 2], config.bottleneck, c[L - 2])
        for l in range(L - 2, 0, -1):
            setattr(self, f"dec{l}", ConvPair(c[l], c[l], c[l - 1]))
        self.dec0 = ConvPair(c[0], c[0], config.head)
        self.head = Head(config.head)
        self.reset_parameters()

    def reset_parameters(self):
        """He (Kaiming-normal, fan-in) weights for the ReLU convs and zero biases, so the
        activations keep their scale through the ~2L convs; the sigmoid head gets the same
        fan-in rule with gain 1. (PyTorch's default uniform init shrinks them layer by layer,
        and the tiny configuration often started or fell into a constant output.)"""
        for name, conv in self.conv_order():
            gain = 1.0 if name == "head.conv1" else 2.0
            fan_in = conv.weight[0].numel()
            with torch.no_grad():
                conv.weight.normal_(0.0, (gain / fan_in) ** 0.5)
                conv.bias.zero_()

    def set_standardization(self, mean, std):
        self.mean.copy_(torch.as_tensor(mean, dtype=torch.float32))
        self.std.copy_(torch.as_tensor(std, dtype=torch.float32))

    def forward(self, x):
        return torch.sigmoid(self.logits(x))

    def logits(self, x):
        """The head's output before the sigmoid (the loss's cross-entropy term reads it)."""
        L = self.config.levels
        m = self.config.multiple
        if x.shape[-1] % m or x.shape[-2] % m:
            raise ValueError(f"input {tuple(x.shape[-2:])} is not a multiple of {m}")
        x = (x - self.mean.view(1, -1, 1, 1)) / self.std.view(1, -1, 1, 1)
        skips = []
        for l in range(L - 1):
            e = getattr(self, f"enc{l}")(x)
            skips.append(e)
            x = F.avg_pool2d(e, 2)
        u = self.mid(x)
        for l in range(L - 2, 0, -1):
            u = getattr(self, f"dec{l}")(up2(u) + skips[l])
        u = self.dec0(up2(u))  # level 0: no skip
        return self.head.conv1(u)

    def conv_order(self):
        """(name, conv) in the network order of the weights file."""
        L = self.config.levels
        names = [f"enc{l}" for l in range(L - 1)] + ["mid"] + [f"dec{l}" for l in range(L - 2, -1, -1)]
        out = []
        for n in names:
            pair = getattr(self, n)
            out += [(f"{n}.conv3", pair.conv3), (f"{n}.conv1", pair.conv1)]
        out.append(("head.conv1", self.head.conv1))
        return out

    def tensor_order(self):
        """(name, tensor) pairs: each conv's weight [oc, ic, kh, kw] then its bias [oc]."""
        out = []
        for name, conv in self.conv_order():
            out += [(name + ".weight", conv.weight), (name + ".bias", conv.bias)]
        return out


def build(name_or_config, seed=None):
    cfg = CONFIGS[name_or_config] if isinstance(name_or_config, str) else name_or_config
    if seed is not None:
        torch.manual_seed(seed)
    return NsmNet(cfg)


def param_counts(model):
    """(weights without biases, weights with biases) of every conv."""
    convs = [c for _, c in model.conv_order()]
    w = sum(c.weight.numel() for c in convs)
    b = sum(c.bias.numel() for c in convs)
    return w, w + b


def macs_per_pixel(model, height=None, width=None, bias=False):
    """Multiply-adds per input pixel, measured by running a forward and counting each conv's
    output pixels times its weights per output (plus 1 per output for the bias if asked).
    Pooling, up-sampling, adds and activations are not counted (as in the paper's tables)."""
    m = model.config.multiple
    h = height or 2 * m
    w = width or 2 * m
    total = [0]
    hooks = []

    def hook(conv, _inp, out):
        per_out = conv.weight[0].numel() + (1 if bias else 0)
        total[0] += out.shape[-1] * out.shape[-2] * conv.out_channels * per_out

    for _, conv in model.conv_order():
        hooks.append(conv.register_forward_hook(hook))
    try:
        with torch.no_grad():
            model(torch.zeros(1, model.config.features, h, w))
    finally:
        for hk in hooks:
            hk.remove()
    return total[0] / (h * w)


def tensor_shapes(config: NetConfig):
    """(name, shape) in tensor order, without building the network (for readers checking a
    file's header before allocating anything); equals NsmNet(config).tensor_order()'s shapes."""
    c, L = config.widths, config.levels
    convs = []
    for l in range(L - 1):
        cin = config.features if l == 0 else c[l - 1]
        convs += [(f"enc{l}.conv3", c[l], cin, 3), (f"enc{l}.conv1", c[l], c[l], 1)]
    convs += [("mid.conv3", config.bottleneck, c[L - 2], 3), ("mid.conv1", c[L - 2], config.bottleneck, 1)]
    for l in range(L - 2, 0, -1):
        convs += [(f"dec{l}.conv3", c[l], c[l], 3), (f"dec{l}.conv1", c[l - 1], c[l], 1)]
    convs += [("dec0.conv3", c[0], c[0], 3), ("dec0.conv1", config.head, c[0], 1),
              ("head.conv1", 1, config.head, 1)]
    out = []
    for n, oc, ic, k in convs:
        out += [(n + ".weight", (oc, ic, k, k)), (n + ".bias", (oc,))]
    return out
