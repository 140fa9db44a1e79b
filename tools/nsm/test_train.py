"""The training loop on the synthetic fixture: determinism, a falling loss, the export, and
the command line's bad-input lines. One thread (the machine is shared; bits repeat per
thread count)."""
import numpy as np

import nsm_export
import nsm_train
from nsm_data import Dataset
from nsm_model import DEFAULT_FEATURES

SMOKE = dict(config="tiny", batch=4, crop=32, threads=1, log_every=0)


def tensor_bytes(model):
    data = nsm_export.encode(model, DEFAULT_FEATURES, "f32")  # no provenance: no wall time
    return data


def test_same_seed_same_weight_bytes_other_seed_other_bytes(dataset_dir):
    runs = [nsm_train.train(dataset_dir, steps=5, seed=s, **SMOKE)[0] for s in (11, 11, 12)]
    a, b, c = (tensor_bytes(m) for m in runs)
    assert a == b
    assert a != c


def best_constant_l1(dataset_dir):
    vals = []
    for fr in Dataset(dataset_dir).frames("val"):
        cov = np.array(fr.coverage(0)) != 0
        vals += [np.array(fr.reference(k))[cov] for k in range(len(fr.radii))]
    v = np.concatenate(vals)
    return float(np.abs(v - np.median(v)).mean())


def test_smoke_training_learns_the_fixture_and_exports(dataset_dir, tmp_path):
    # lr 1e-2: 30 steps at the default 1e-3 barely move a network this small.
    model, hist, val, prov = nsm_train.train(dataset_dir, steps=30, lr=1e-2, seed=1, **SMOKE)
    loss = [h[1] for h in hist]
    first, last = np.mean(loss[:5]), np.mean(loss[-5:])
    print(f"loss first-5 {first:.4f} last-5 {last:.4f} ratio {last / first:.3f}; "
          f"validation L1 {val:.4f}, best constant {best_constant_l1(dataset_dir):.4f}")
    assert last < 0.7 * first
    # a real signal: the validation frames (unseen) beat the best constant output clearly
    assert val < 0.75 * best_constant_l1(dataset_dir)
    assert prov["steps"] == 30 and prov["seed"] == 1 and prov["dataset_hash"]
    assert prov["validation_l1"] == val and prov["params"] == 2624
    for dtype in ("f32", "f16"):
        path = str(tmp_path / f"m_{dtype}.nsmw")
        nsm_export.write(path, model, DEFAULT_FEATURES, dtype, prov)
        h, tensors = nsm_export.read(path)
        assert h["provenance"]["dataset_hash"] == prov["dataset_hash"]
        for name, t in model.tensor_order():
            want = t.detach().numpy()
            want = want if dtype == "f32" else want.astype(np.float16).astype(np.float32)
            assert np.array_equal(tensors[name], want)


def test_command_line_writes_weights_and_refuses_bad_input(dataset_dir, tmp_path, capsys):
    out = str(tmp_path / "w.nsmw")
    rc = nsm_train.main(["--data", dataset_dir, "--out", out, "--config", "tiny", "--steps", "2",
                         "--batch", "2", "--crop", "32", "--threads", "1", "--log-every", "1"])
    assert rc == 0
    h, _ = nsm_export.read(out)
    assert h["dtype"] == "f16" and h["provenance"]["command"].startswith("nsm_train --data")
    capsys.readouterr()
    bad = [(["--crop", "30"], "nsm_train: --crop: "),
           (["--steps", "0"], "nsm_train: --steps: "),
           (["--lr-min", "1"], "nsm_train: --lr-min: "),
           (["--data", str(tmp_path / "none")], "nsm_train: " + str(tmp_path / "none")),
           (["--out", str(tmp_path / "no" / "w.nsmw")], "nsm_train: --out: "),
           (["--features", "d,albedo"], "nsm_train: --features: "),
           (["--features", "d,d"], "nsm_train: --features: ")]
    for extra, prefix in bad:
        args = ["--data", dataset_dir, "--out", out, "--config", "tiny", "--crop", "32",
                "--steps", "1", "--threads", "1"] + extra
        assert nsm_train.main(args) == 2
        err = capsys.readouterr().err
        assert err.startswith(prefix) and err.count("\n") == 1, err


def test_a_feature_subset_trains_and_is_named_in_the_weights(dataset_dir, tmp_path):
    out = str(tmp_path / "sub.nsmw")
    rc = nsm_train.main(["--data", dataset_dir, "--out", out, "--config", "tiny", "--steps", "2",
                         "--batch", "2", "--crop", "32", "--threads", "1", "--log-every", "0",
                         "--features", "d,c_e_r"])
    assert rc == 0
    h, tensors = nsm_export.read(out)
    assert h["features"] == ["d", "c_e_r"] and len(h["mean"]) == 2
    assert tensors["enc0.conv3.weight"].shape[1] == 2  # the first conv reads 2 planes
