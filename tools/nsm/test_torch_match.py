"""The C++ forward pass (build/programs/nsm_forward) against the independent PyTorch reference
(tools/nsm/torch_reference.py) in float64, on random weights and inputs (tiny with edge padding,
nsm5, nsm3 with f16 weights): |C++ − torch64| ≤ the per-pixel rounding bound of spec §6 at every
pixel end to end, and each pass (encoder level, bottleneck, decoder level, head) from the C++'s
own stored inputs within that pass's bound (nsm_forward --dump). Prints observed/bound. Run: python3 -m pytest -s tools/nsm/test_torch_match.py
(SHADOWLAB_BUILD names the build folder; default build/)."""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
import pytest

torch = pytest.importorskip("torch")
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import nsmw_write  # noqa: E402
import torch_reference  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.environ.get("SHADOWLAB_BUILD", os.path.join(ROOT, "build"))
PROGRAM = os.path.join(BUILD, "programs", "nsm_forward")

CASES = [("tiny", "f32", 37, 29, 1), ("nsm5", "f32", 64, 48, 2), ("nsm3", "f16", 50, 30, 3)]


def run_case(tmp, arch, dtype, width, height, seed):
    levels, widths, bottleneck = nsmw_write.ARCHS[arch]
    tensors = nsmw_write.random_tensors(levels, widths, bottleneck, seed)
    if dtype == "f16":
        tensors = [(n, t.astype(np.float16).astype(np.float32)) for n, t in tensors]
    mean, std = [0.9, -0.1, 0.5, 2.0], [0.2, 0.3, 0.4, 1.5]
    weights = os.path.join(tmp, f"{arch}.nsmw")
    nsmw_write.write_nsmw(weights, levels, widths, bottleneck, tensors, mean, std, dtype)
    rng = np.random.default_rng(seed + 100)
    planes = (np.array(mean)[:, None, None] + np.array(std)[:, None, None] *
              rng.standard_normal((4, height, width))).astype(np.float32)
    planes_path = os.path.join(tmp, f"{arch}.f32")
    planes.astype("<f4").tofile(planes_path)
    out = os.path.join(tmp, f"out_{arch}")
    r = subprocess.run([PROGRAM, "--weights", weights, "--input", planes_path, "--width",
                        str(width), "--height", str(height), "--threads", "2", "--dump",
                        "--out", out],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    cpp = np.fromfile(os.path.join(out, "output.f32"), dtype="<f4").reshape(height, width)
    w = torch_reference.Weights(weights)
    ref = torch_reference.forward(w, planes, torch.float64)
    ref32 = torch_reference.forward(w, planes, torch.float32)
    b = torch_reference.bound(w, planes)
    index = json.load(open(os.path.join(out, "tensors.json")))
    tensors = {t["name"]: np.fromfile(os.path.join(out, "tensors", t["name"] + ".f32"), dtype="<f4")
               .reshape(t["height"], t["width"], t["channels"]) for t in index}
    passes = torch_reference.pass_checks(w, planes, tensors, cpp)
    return cpp.astype(np.float64), ref, ref32, b, passes


@pytest.mark.skipif(not os.path.exists(PROGRAM), reason="nsm_forward not built")
@pytest.mark.parametrize("arch,dtype,width,height,seed", CASES)
def test_cpp_matches_torch64_within_the_bound(arch, dtype, width, height, seed):
    torch.set_num_threads(2)
    with tempfile.TemporaryDirectory() as tmp:
        cpp, ref, ref32, b, passes = run_case(tmp, arch, dtype, width, height, seed)
    err = np.abs(cpp - ref)
    err32 = np.abs(ref32 - ref)
    print(f"\n{arch} {dtype} {width}x{height}: C++ max |err| {err.max():.3g}, bound max "
          f"{b.max():.3g}, min {b.min():.3g}, max err/bound {(err / b).max():.3g}; "
          f"torch fp32: max |err| {err32.max():.3g}, max err/bound {(err32 / b).max():.3g}")
    assert np.all(err <= b), f"{int((err > b).sum())} pixels over the bound"
    # Each pass from the C++'s own stored inputs, against its one-pass bound: tight, where the
    # end-to-end bound above grows by Σ|w| per layer and is loose at nsm5's depth.
    for name, e, bmax, ratio, over in passes:
        print(f"  pass {name:10s} max |err| {e:.3g}  max bound {bmax:.3g}  max err/bound {ratio:.3g}")
    for name, e, bmax, ratio, over in passes:
        assert over == 0, f"pass {name}: {over} values over the bound (max err/bound {ratio:.3g})"
    # The outputs are not all saturated: the comparison says something.
    assert 0.02 < np.median(ref) < 0.98 or ref.std() > 1e-3


def test_reference_equals_the_training_model():
    """torch_reference.py and the training model (tools/nsm/nsm_model.py, loaded by
    nsm_export.load_model) on one file in float64: the same network, two definitions."""
    nsm_export = pytest.importorskip("nsm_export")
    torch.set_num_threads(2)
    levels, widths, bottleneck = nsmw_write.ARCHS["nsm3"]
    tensors = nsmw_write.random_tensors(levels, widths, bottleneck, 11)
    mean, std = [0.9, -0.1, 0.5, 2.0], [0.2, 0.3, 0.4, 1.5]
    rng = np.random.default_rng(12)
    planes = (np.array(mean)[:, None, None] + np.array(std)[:, None, None] *
              rng.standard_normal((4, 32, 40))).astype(np.float32)
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "nsm3.nsmw")
        nsmw_write.write_nsmw(path, levels, widths, bottleneck, tensors, mean, std)
        net, _ = nsm_export.load_model(path)
        mine = torch_reference.forward(torch_reference.Weights(path), planes, torch.float64)
    with torch.no_grad():
        theirs = net.double()(torch.from_numpy(planes.astype(np.float64))[None])[0, 0].numpy()
    diff = np.abs(mine - theirs).max()
    print(f"\nreference vs training model, float64: max |diff| {diff:.3g}")
    assert diff <= 1e-12
