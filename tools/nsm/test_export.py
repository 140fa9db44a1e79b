"""The .nsmw weights file: round trip, f16 rounding, checksum."""
import struct

import numpy as np
import pytest
import torch

import nsm_export
from nsm_export import WeightsError
from nsm_fnv import fnv1a64, fnv1a64_python
from nsm_model import DEFAULT_FEATURES, build


def model(seed=3):
    net = build("tiny", seed=seed)
    with torch.no_grad():
        for _, t in net.tensor_order():
            t.normal_(0.0, 0.5)  # non-zero biases too
    net.set_standardization([1.0, -2.0, 0.5, 3.0], [0.25, 2.0, 1.5, 0.125])
    return net


def test_fnv1a64_published_vectors():
    # FNV-1a 64 test vectors from the algorithm's reference (Fowler, Noll, Vo).
    for data, h in ((b"", 0xCBF29CE484222325), (b"a", 0xAF63DC4C8601EC8C),
                    (b"foobar", 0x85944171F73967E8)):
        assert fnv1a64(data) == h == fnv1a64_python(data)


def test_f32_round_trip_is_bit_exact_and_laid_out_as_documented():
    net = model()
    data = nsm_export.encode(net, DEFAULT_FEATURES, "f32", {"seed": 3})
    assert data[:4] == b"NSMW" and struct.unpack("<I", data[4:8])[0] == 1
    assert struct.unpack("<Q", data[-8:])[0] == fnv1a64(data[:-8])
    h, tensors = nsm_export.decode(data)
    assert h["levels"] == 3 and h["widths"] == [4, 8] and h["bottleneck"] == 16 and h["head"] == 16
    assert h["features"] == list(DEFAULT_FEATURES) and h["r_max"] == 0.3 and h["scale_ref"] == 3.12
    assert h["mean"] == [1.0, -2.0, 0.5, 3.0] and h["std"] == [0.25, 2.0, 1.5, 0.125]
    assert h["provenance"] == {"seed": 3}
    hlen = struct.unpack("<I", data[8:12])[0]
    prev_end = 12 + hlen
    for e, (name, t) in zip(h["tensors"], net.tensor_order()):
        assert e["name"] == name and e["offset"] % 64 == 0 and e["offset"] >= prev_end
        raw = t.detach().numpy().astype("<f4")
        assert data[e["offset"]:e["offset"] + raw.nbytes] == raw.tobytes()
        assert tensors[name].view(np.uint32).tolist() == raw.view(np.uint32).tolist()
        prev_end = e["offset"] + raw.nbytes
    assert prev_end == len(data) - 8


def test_f16_is_exact_for_representable_values_and_rounds_to_nearest_even_otherwise():
    net = model()
    exact = {}
    with torch.no_grad():
        for i, (name, t) in enumerate(net.tensor_order()):
            if i % 2 == 0:  # weights: make them binary16 values
                t.copy_(t.half().float())
                exact[name] = t.detach().numpy().copy()
    originals = {n: t.detach().numpy().copy() for n, t in net.tensor_order()}
    _, tensors = nsm_export.decode(nsm_export.encode(net, DEFAULT_FEATURES, "f16"))
    for name, v in originals.items():
        if name in exact:
            assert np.array_equal(tensors[name].view(np.uint32), v.view(np.uint32))
        # numpy's float32 -> float16 cast rounds to nearest even (IEEE 754)
        assert np.array_equal(tensors[name], v.astype(np.float16).astype(np.float32))
    # a hand-checked tie: 1 + 2^-11 lies halfway between 1 and 1 + 2^-10 -> 1 (even)
    with torch.no_grad():
        net.head.conv1.bias.fill_(1.0 + 2.0 ** -11)
    _, tensors = nsm_export.decode(nsm_export.encode(net, DEFAULT_FEATURES, "f16"))
    assert tensors["head.conv1.bias"][0] == 1.0


def test_every_flipped_byte_class_and_truncation_are_refused():
    data = nsm_export.encode(model(), DEFAULT_FEATURES, "f32")
    h, _ = nsm_export.decode(data)
    for pos in (0, 10, 20, h["tensors"][3]["offset"] + 1, len(data) - 9, len(data) - 1):
        bad = bytearray(data)
        bad[pos] ^= 0x10
        with pytest.raises(WeightsError):
            nsm_export.decode(bytes(bad), "w.nsmw")
    with pytest.raises(WeightsError, match="w.nsmw: "):
        nsm_export.decode(data[:-100], "w.nsmw")


def test_loaded_model_computes_the_same_output(tmp_path):
    net = model()
    path = str(tmp_path / "m.nsmw")
    nsm_export.write(path, net, DEFAULT_FEATURES, "f32", {"k": 1})
    loaded, h = nsm_export.load_model(path)
    x = torch.rand(1, 4, 8, 12) * 4
    with torch.no_grad():
        assert torch.equal(net(x), loaded(x))
    assert h["provenance"] == {"k": 1}


def test_non_finite_or_out_of_range_weights_are_not_exported():
    net = model()
    with torch.no_grad():
        net.mid.conv3.bias[0] = 70000.0  # beyond binary16's largest finite value, 65504
    nsm_export.encode(net, DEFAULT_FEATURES, "f32")
    with pytest.raises(ValueError, match="mid.conv3.bias"):
        nsm_export.encode(net, DEFAULT_FEATURES, "f16")
    with torch.no_grad():
        net.mid.conv3.bias[0] = float("nan")
    with pytest.raises(ValueError, match="non-finite"):
        nsm_export.encode(net, DEFAULT_FEATURES, "f32")
    h, _ = nsm_export.decode(nsm_export.encode(model(), DEFAULT_FEATURES, "f32", {"v": float("nan")}))
    assert h["provenance"] == {"v": "nan"}
