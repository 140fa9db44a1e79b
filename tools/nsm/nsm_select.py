#!/usr/bin/env python3
"""Feature selection by sensitivity (the supplemental's Table 1, docs/results/nsm.md): trains a
network on every candidate feature and measures each input's sensitivity -- how much the
validation L1 rises when that input is held at its training mean (0 after standardization).
Then, for each size k of --sizes, trains on the k - 1 most sensitive inputs plus c_e_r (the only
input that carries the emitter's size, so always kept), on the paper's pruned four
(DEFAULT_FEATURES) and on --small. The pruned set is the smallest of the ranked sets whose
validation L1 is within --prune (1.5 %, the paper's rule) of the all-candidates network's.
Prints one row per training: features, validation L1.

  python3 tools/nsm/nsm_select.py --data DATA [--config nsm3 --steps 1000] [--json OUT]
"""
import argparse
import json
import sys

import numpy as np
import torch

import nsm_train
from nsm_model import CANDIDATE_FEATURES, DEFAULT_FEATURES

# c_e is left out of the candidates: c_e_r = c_e + r_e carries it together with the emitter
# size, and with both the network could read r_e off their difference, which the paper's
# feature set (one modulated c_e) does not allow.
CANDIDATES = tuple(f for f in CANDIDATE_FEATURES if f != "c_e")


def sensitivities(model, frames, features):
    """{feature: relative rise of the validation L1 with that input held at its mean}."""
    base = nsm_train.validation_l1(model, frames, features)
    out = {}
    for i, name in enumerate(features):
        saved = model.std[i].item(), model.mean[i].item()
        with torch.no_grad():
            # (x - mean) / std = 0 for every x: an infinite std holds the input at its mean.
            model.std[i] = float("inf")
        out[name] = (nsm_train.validation_l1(model, frames, features) - base) / base
        with torch.no_grad():
            model.std[i], model.mean[i] = saved
    return base, out


def main(argv=None):
    p = argparse.ArgumentParser(prog="nsm_select", description=__doc__.splitlines()[0])
    p.add_argument("--data", required=True)
    p.add_argument("--config", default="nsm3")
    p.add_argument("--steps", type=int, default=1000)
    p.add_argument("--prune", type=float, default=0.015)
    p.add_argument("--small", default="z_minus_zf,c_e_r")
    p.add_argument("--sizes", default="6,4", help="sizes of the ranked sets to train")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--json")
    a = p.parse_args(argv)
    rows = []

    def run(features):
        model, _, val, prov = nsm_train.train(a.data, a.config, a.steps, seed=a.seed,
                                              threads=a.threads, log_every=0, features=features)
        rows.append({"features": list(features), "validation_l1": val,
                     "wall_s": prov["wall_s"]})
        print(f"{len(features):2d} features  validation L1 {val:.5f}  ({', '.join(features)})",
              flush=True)
        return model

    model = run(CANDIDATES)
    from nsm_data import Dataset
    base, sens = sensitivities(model, Dataset(a.data).frames("val"), list(CANDIDATES))
    print("sensitivity (relative rise of the validation L1 with the input held at its mean):")
    for name, v in sorted(sens.items(), key=lambda kv: -kv[1]):
        print(f"  {name:11s} {100 * v:+7.2f} %{'' if v >= a.prune else '  pruned'}")
    ranked = [f for f, _ in sorted(sens.items(), key=lambda kv: -kv[1]) if f != "c_e_r"]
    within = None
    for k in sorted((int(v) for v in a.sizes.split(",")), reverse=True):
        features = ranked[:k - 1] + ["c_e_r"]
        run(features)
        if rows[-1]["validation_l1"] <= (1 + a.prune) * rows[0]["validation_l1"]:
            within = features
    run(list(DEFAULT_FEATURES))
    run(a.small.split(","))
    print(f"pruned set (smallest ranked set within {100 * a.prune:g} %): "
          f"{', '.join(within) if within else 'none'}")
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"config": a.config, "steps": a.steps, "prune": a.prune,
                       "sensitivity": sens, "rows": rows}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
