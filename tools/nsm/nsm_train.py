#!/usr/bin/env python3
"""Trains an NSM network on a data set and writes its .nsmw weights (docs/techniques/nsm.md,
"Training").

    python3 tools/nsm/nsm_train.py --data DIR --out model.nsmw [--config nsm5] [--steps 2500]
        [--batch 8] [--crop 128] [--lr 1e-3] [--lr-min 1e-5] [--seed 1] [--threads 2]
        [--log-every 50] [--dtype f16|f32] [--no-perturbation] [--fixed-batch]

Deterministic: the seed fixes the initial weights (torch.manual_seed) and the sample order
(frames, radii, crops from one PCG64 stream); torch runs deterministic algorithms on a fixed
thread count. Bits repeat per machine kind and thread count (oneDNN picks its kernels by ISA),
so both are in the provenance.
"""
import argparse
import dataclasses
import math
import os
import platform
import subprocess
import sys
import time

import numpy as np
import torch

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import nsm_export  # noqa: E402
from nsm_data import DataError, Dataset, Sampler, check_frames, feature_stats, loss_mask  # noqa: E402
from nsm_loss import ALPHA, nsm_loss  # noqa: E402
from nsm_model import CANDIDATE_FEATURES, CONFIGS, DEFAULT_FEATURES, build, macs_per_pixel, param_counts  # noqa: E402

PROGRAM = "nsm_train"


class UsageError(Exception):
    """str() is "<flag>: <reason>"."""


def setup_torch(seed, threads):
    torch.manual_seed(seed)
    torch.use_deterministic_algorithms(True)
    torch.set_num_threads(threads)


def cosine_lr(step, steps, lr, lr_min):
    """lr at `step` (0-based): lr at the first step, lr_min at the last."""
    if steps <= 1:
        return lr
    return lr_min + 0.5 * (lr - lr_min) * (1.0 + math.cos(math.pi * step / (steps - 1)))


def validation_l1(model, frames, names=DEFAULT_FEATURES):
    """Masked L1 of copy 0's output against the reference over every pixel of nsm_data.loss_mask
    (covered, facing the light) of every frame and radius (pooled), each frame cropped at the top left to multiples of 2^(L-1)."""
    if not frames:
        return None
    m = model.config.multiple
    total, count = 0.0, 0.0
    with torch.no_grad():
        for fr in frames:
            h, w = fr.height // m * m, fr.width // m * m
            if h == 0 or w == 0:
                continue
            cov = torch.from_numpy(np.array(loss_mask(fr, 0)[:h, :w], np.float32))
            for k in range(len(fr.radii)):
                x = torch.from_numpy(fr.inputs(0, names, k, 0, 0, h, w))[None]
                t = torch.from_numpy(np.array(fr.reference(k)[:h, :w], np.float32))
                y = model(x)[0, 0]
                total += float(((y - t).abs() * cov).double().sum())
                count += float(cov.double().sum())
    return total / count if count else None


def git_commit():
    try:
        rev = subprocess.run(["git", "-C", HERE, "rev-parse", "HEAD"], capture_output=True,
                             text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", HERE, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, check=True).stdout.strip()
        return rev + ("-dirty" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            info = f.read()
        name = next((l.split(":", 1)[1].strip() for l in info.splitlines()
                     if l.startswith("model name")), platform.processor())
        flags = next((l.split(":", 1)[1].split() for l in info.splitlines()
                      if l.startswith("flags")), [])
        isa = "avx512" if "avx512f" in flags else "avx2" if "avx2" in flags else "other"
        return name, isa
    except OSError:
        return platform.processor(), "unknown"


def train(data, config="nsm5", steps=2500, batch=8, crop=128, lr=1e-3, lr_min=1e-5, seed=1,
          threads=2, log_every=50, perturbation=True, fixed_batch=False, log=print, dataset=None,
          clip=0.0, features=DEFAULT_FEATURES, structural=1.0 - ALPHA):
    """Returns (model, history [(step, loss, parts)], validation L1, provenance dict).
    `features`: the network's inputs, in order (names of techniques/nsm/nsm_features.h)."""
    setup_torch(seed, threads)
    commit = git_commit()  # the code that trains, read before the tree can change
    t_start = time.time()
    ds = dataset or Dataset(data)
    train_frames = ds.frames("train")
    val_frames = ds.frames("val")
    if not train_frames:
        raise DataError(f"{os.path.join(data, 'manifest.json')}: the train split is empty")
    features = list(features)
    check_frames(train_frames + val_frames, features)
    mean, std = feature_stats(train_frames, features)
    cfg = CONFIGS[config] if isinstance(config, str) else config
    cfg = dataclasses.replace(cfg, features=len(features))
    model = build(cfg)  # after manual_seed: the initial weights follow the seed
    model.set_standardization(mean, std)
    sampler = Sampler(train_frames, crop, model.config.multiple, seed, features)
    opt = torch.optim.Adam(model.parameters(), lr=lr, betas=(0.9, 0.999))
    history = []
    t_loop = time.time()
    for step in range(steps):
        for g in opt.param_groups:
            g["lr"] = cosine_lr(step, steps, lr, lr_min)
        if step == 0 or not fixed_batch:
            x, cov, t = (torch.from_numpy(a) for a in sampler.batch(batch))
        loss, parts = nsm_loss(model, x, cov, t, perturbation, 1.0 - structural)
        opt.zero_grad(set_to_none=True)
        loss.backward()
        if clip > 0:
            torch.nn.utils.clip_grad_norm_(model.parameters(), clip)
        opt.step()
        history.append((step, float(loss), parts))
        if log_every and ((step + 1) % log_every == 0 or step + 1 == steps):
            ms = 1000.0 * (time.time() - t_loop) / (step + 1)
            recent = [h[1] for h in history[-log_every:]]
            log(f"step {step + 1}/{steps} loss {np.mean(recent):.5f} (last {len(recent)}) "
                f"lr {cosine_lr(step, steps, lr, lr_min):.2e} {ms:.0f} ms/step")
    loop_s = time.time() - t_loop
    model.eval()
    val = validation_l1(model, val_frames, features)
    if log_every:
        log(f"validation L1 {val if val is None else f'{val:.6f}'} over {len(val_frames)} frames")
    cpu, isa = cpu_model()
    w, wb = param_counts(model)
    prov = {"program": PROGRAM, "dataset_hash": ds.dataset_hash, "dataset": os.path.abspath(data),
            "train_frames": len(train_frames), "val_frames": len(val_frames),
            "commit": commit, "seed": seed, "steps": steps, "batch": batch, "crop": crop,
            "lr": lr, "lr_min": lr_min, "clip": clip, "schedule": "cosine", "optimizer": "Adam(0.9,0.999)",
            "loss": (f"{1 - structural:g} L1 + {structural:g} (1 - SSIM 11x11 sigma 1.5) + BCE(logits)"
                     if structural else "L1 + BCE(logits)")
                    + (f" + {float(perturbation):g} x perturbation (3 copies, no_grad)" if perturbation else ""),
            "perturbation": float(perturbation), "fixed_batch": fixed_batch,
            "config": config if isinstance(config, str) else str(config), "features": features,
            "macs_per_pixel": macs_per_pixel(model), "params": w, "params_with_bias": wb,
            "validation_l1": val, "final_loss": history[-1][1] if history else None,
            "wall_s": round(time.time() - t_start, 3), "ms_per_step": round(1000 * loop_s / max(steps, 1), 2),
            "threads": threads, "cpu": cpu, "isa": isa, "torch": torch.__version__}
    return model, history, val, prov


def parse(argv):
    p = argparse.ArgumentParser(prog=PROGRAM, description=__doc__.split("\n")[0])
    p.add_argument("--data", required=True, help="data set folder (manifest.json, frames/)")
    p.add_argument("--out", required=True, help="weights file to write (.nsmw)")
    p.add_argument("--config", default="nsm5", choices=sorted(CONFIGS))
    p.add_argument("--steps", type=int, default=2500)
    p.add_argument("--batch", type=int, default=8)
    p.add_argument("--crop", type=int, default=128)
    p.add_argument("--lr", type=float, default=1e-3)
    p.add_argument("--lr-min", type=float, default=1e-5)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--log-every", type=int, default=50)
    p.add_argument("--dtype", default="f16", choices=["f16", "f32"])
    p.add_argument("--fixed-batch", action="store_true",
                   help="draw one batch and train on it every step (the smoke test's overfit check)")
    p.add_argument("--no-perturbation", action="store_true",
                   help="drop the perturbation term (the ablation)")
    p.add_argument("--features", default=",".join(DEFAULT_FEATURES),
                   help="the network's inputs, comma-separated (default: the pruned four)")
    p.add_argument("--clip", type=float, default=0.0,
                   help="clip the gradient's global norm to this (0: no clipping)")
    p.add_argument("--structural-weight", type=float, default=1.0 - ALPHA,
                   help="the SSIM term's share of L, 1 - alpha (default 0.1; 0: L1 alone)")
    p.add_argument("--perturbation-weight", type=float, default=1.0,
                   help="weight of the perturbation term (1: the paper's Eq. 2)")
    a = p.parse_args(argv)
    checks = [("--steps", a.steps >= 1, "must be >= 1"), ("--batch", 1 <= a.batch <= 1024, "must be in [1, 1024]"),
              ("--crop", 1 <= a.crop <= 4096 and a.crop % CONFIGS[a.config].multiple == 0,
               f"must be a positive multiple of {CONFIGS[a.config].multiple} for {a.config}"),
              ("--lr", math.isfinite(a.lr) and a.lr > 0, "must be positive"),
              ("--lr-min", math.isfinite(a.lr_min) and 0 <= a.lr_min <= a.lr, "must be in [0, --lr]"),
              ("--seed", 0 <= a.seed < 2 ** 63, "must be in [0, 2^63)"),
              ("--threads", 1 <= a.threads <= 256, "must be in [1, 256]"),
              ("--log-every", a.log_every >= 0, "must be >= 0"),
              ("--clip", math.isfinite(a.clip) and a.clip >= 0, "must be >= 0"),
              ("--structural-weight", 0 <= a.structural_weight < 1, "must be in [0, 1)"),
              ("--features", bool(a.features) and all(f in CANDIDATE_FEATURES for f in a.features.split(","))
               and len(set(a.features.split(","))) == len(a.features.split(",")),
               f"must be distinct names of {', '.join(CANDIDATE_FEATURES)}"),
              ("--perturbation-weight", math.isfinite(a.perturbation_weight) and 0 <= a.perturbation_weight <= 100,
               "must be in [0, 100]")]
    for flag, ok, why in checks:
        if not ok:
            raise UsageError(f"{flag}: {why}")
    if not os.path.isdir(os.path.dirname(os.path.abspath(a.out))):
        raise UsageError(f"--out: folder {os.path.dirname(os.path.abspath(a.out))} does not exist")
    return a


def main(argv=None):
    try:
        a = parse(sys.argv[1:] if argv is None else argv)
        model, _, val, prov = train(a.data, a.config, a.steps, a.batch, a.crop, a.lr, a.lr_min,
                                    a.seed, a.threads, a.log_every,
                                    0.0 if a.no_perturbation else a.perturbation_weight,
                                    a.fixed_batch, clip=a.clip, features=a.features.split(","),
                                    structural=a.structural_weight)
        prov["command"] = " ".join([PROGRAM] + (sys.argv[1:] if argv is None else list(argv)))
        nsm_export.write(a.out, model, a.features.split(","), a.dtype, prov)
        print(f"wrote {a.out} ({a.dtype}, {prov['params_with_bias']} parameters, "
              f"validation L1 {val}, {prov['wall_s']} s)")
        return 0
    except (UsageError, DataError) as e:
        print(f"{PROGRAM}: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
