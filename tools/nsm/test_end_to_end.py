"""The whole chain on data the C++ writes: nsm_data makes a small data set, the trainer trains the
tiny network on it for 30 steps (the loss must fall), the exporter writes f16 weights, and the
C++ forward pass (nsm_forward) on a frame's own feature planes equals the PyTorch reference of
those weights within the per-pixel rounding bound (torch_reference.bound). Skipped when the
programs are not built (SHADOWLAB_BUILD names the build folder; default build/)."""
import os
import subprocess
import sys

import numpy as np
import pytest

torch = pytest.importorskip("torch")
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import nsm_export  # noqa: E402
import nsm_train  # noqa: E402
import torch_reference  # noqa: E402
from nsm_data import Dataset  # noqa: E402
from nsm_model import DEFAULT_FEATURES  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(HERE))
BUILD = os.environ.get("SHADOWLAB_BUILD", os.path.join(ROOT, "build"))
DATA = os.path.join(BUILD, "programs", "nsm_data")
FORWARD = os.path.join(BUILD, "programs", "nsm_forward")


@pytest.mark.skipif(not (os.access(DATA, os.X_OK) and os.access(FORWARD, os.X_OK)),
                    reason="nsm_data and nsm_forward are not built")
def test_cpp_data_trains_exports_and_the_cpp_forward_equals_torch(tmp_path):
    data = tmp_path / "data"
    subprocess.run([DATA, "--scenes", "default,plane", "--width", "128", "--height", "96",
                    "--crop", "64,48", "--frames", "8", "--spp", "16", "--base-res", "256",
                    "--features", "net", "--split-val", "0.25", "--split-test", "0",
                    "--threads", "2", "--out", str(data)], check=True, capture_output=True)
    torch.set_num_threads(2)
    model, hist, val, prov = nsm_train.train(str(data), config="tiny", steps=30, batch=4, crop=32,
                                             lr=1e-2, seed=1, threads=2, log_every=0)
    loss = [h[1] for h in hist]
    first, last = np.mean(loss[:5]), np.mean(loss[-5:])
    print(f"\nloss first-5 {first:.4f} last-5 {last:.4f}; validation L1 {val:.4f}")
    assert last < 0.8 * first
    weights = str(tmp_path / "tiny.nsmw")
    nsm_export.write(weights, model, DEFAULT_FEATURES, "f16", prov)

    # The training frame with the most shadow, its copy-0 features, with c_e_r at its largest
    # radius's size code.
    frames = Dataset(str(data)).frames("train")
    frame = min(frames, key=lambda f: float(np.mean(f.reference(len(f.radii) - 1))))
    w = torch_reference.Weights(weights)
    r_code = 4.0 * frame.radii[-1] / 0.3
    planes = []
    for name in DEFAULT_FEATURES:
        p = np.array(frame.feature(0, name), dtype=np.float32)
        planes.append(p + np.float32(r_code) if name == "c_e_r" else p)
    planes = np.stack(planes)
    height, width = planes.shape[1:]
    planes_path = tmp_path / "planes.f32"
    planes.astype("<f4").tofile(planes_path)
    out = tmp_path / "forward"
    r = subprocess.run([FORWARD, "--weights", weights, "--input", str(planes_path), "--width",
                        str(width), "--height", str(height), "--threads", "2", "--out", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    cpp = np.fromfile(out / "output.f32", dtype="<f4").reshape(height, width).astype(np.float64)
    ref = torch_reference.forward(w, planes, torch.float64)
    bound = torch_reference.bound(w, planes)
    err = np.abs(cpp - ref)
    print(f"C++ against torch float64 on the frame's features: max |err| {err.max():.3g}, "
          f"max err/bound {(err / bound).max():.3g}")
    assert np.all(err <= bound)
    # Not a saturated output: the comparison says something.
    print(f"output range {ref.min():.4f}..{ref.max():.4f}, std {ref.std():.3g}")
    assert ref.min() < 0.9
