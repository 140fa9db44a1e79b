"""The data set reader against the synthetic fixture (written by nsm_synthetic.py with numpy
in the documented format)."""
import json
import os
import shutil
import struct

import numpy as np
import pytest

import nsm_synthetic
from nsm_data import DataError, Dataset, Frame, Sampler, check_frames, feature_stats
from nsm_fnv import fnv1a64
from nsm_model import DEFAULT_FEATURES

W, H = nsm_synthetic.W, nsm_synthetic.H


def frame_path(d, i):
    return os.path.join(d, "frames", f"{i:06d}.nsmf")


def test_reader_picks_features_by_name_and_adds_the_radius_code(dataset_dir):
    ds = Dataset(dataset_dir)
    fr = ds.frame("000000.nsmf")
    assert (fr.width, fr.height) == (W, H) and fr.features == list(nsm_synthetic.FEATURES)
    rng = np.random.Generator(np.random.PCG64([7, 0]))  # the fixture's own generator
    copies, refs = nsm_synthetic.frame_planes(rng, W, H)
    planes0 = dict(zip(nsm_synthetic.FEATURES, copies[0][0]))
    x = fr.inputs(0, DEFAULT_FEATURES, 4, 3, 5, 16, 20)  # radius 0.3: code 4
    for i, name in enumerate(DEFAULT_FEATURES):
        want = planes0[name][3:19, 5:25] + (np.float32(4.0) if name == "c_e_r" else 0)
        assert np.array_equal(x[i], want), name
    x2 = fr.inputs(2, ["c_e_r"], 1)  # radius 0.03: code 0.4
    assert np.array_equal(x2[0], copies[2][0][nsm_synthetic.FEATURES.index("c_e_r")] + np.float32(0.4))
    assert np.array_equal(fr.coverage(3), copies[3][1])
    assert np.array_equal(fr.reference(2), refs[2])


def test_both_tail_paddings_are_read(dataset_dir):
    # odd frames are zero-padded to 64 before the hash, even ones are not
    a, b = Frame(frame_path(dataset_dir, 0)), Frame(frame_path(dataset_dir, 1))
    assert (a.size - 8) % 64 != 0 and (b.size - 8) % 64 == 0 and b.size > a.size
    assert a.reference_offsets[-1] % 64 == 0 and a.coverage_offsets[1] % 64 == 0


@pytest.mark.parametrize("where", ["header", "plane", "hash"])
def test_a_flipped_byte_is_refused(dataset_dir, tmp_path, where):
    src = frame_path(dataset_dir, 0)
    data = bytearray(open(src, "rb").read())
    pos = {"header": 20, "plane": len(data) // 2, "hash": len(data) - 3}[where]
    data[pos] ^= 0x01
    p = tmp_path / "f.nsmf"
    p.write_bytes(bytes(data))
    with pytest.raises(DataError, match=f"{p}: "):
        Frame(str(p))


def test_truncated_bad_magic_and_bad_header_are_refused(dataset_dir, tmp_path):
    data = open(frame_path(dataset_dir, 0), "rb").read()
    cases = {"trunc": data[:-64], "magic": b"NSMX" + data[4:], "short": data[:10],
             "hlen": data[:8] + struct.pack("<I", 1 << 30) + data[12:]}
    hdr = json.loads(data[12:12 + struct.unpack("<I", data[8:12])[0]])
    for key, val in (("copies", 3), ("radii", [0.5]), ("width", "64")):
        h = dict(hdr, **{key: val})
        hj = json.dumps(h).encode()
        cases[key] = b"NSMF" + struct.pack("<II", 1, len(hj)) + hj + data[12 + len(json.dumps(hdr)):]
    for name, blob in cases.items():
        p = tmp_path / f"{name}.nsmf"
        p.write_bytes(blob)
        with pytest.raises(DataError):
            Frame(str(p))


def test_feature_statistics_match_a_direct_computation(dataset_dir):
    ds = Dataset(dataset_dir)
    mean, std = feature_stats(ds.frames("train"))
    for i, name in enumerate(DEFAULT_FEATURES):
        vals = []
        for n in ds.splits["train"]:
            rng = np.random.Generator(np.random.PCG64([7, int(n[:6])]))
            copies, _ = nsm_synthetic.frame_planes(rng, W, H)
            v = copies[0][0][nsm_synthetic.FEATURES.index(name)][copies[0][1] != 0].astype(np.float64)
            codes = [4 * r / 0.3 for r in nsm_synthetic.RADII] if name == "c_e_r" else [0.0]
            vals += [v + c for c in codes]
        v = np.concatenate(vals)
        assert mean[i] == pytest.approx(v.mean(), rel=1e-5, abs=1e-6)
        assert std[i] == pytest.approx(v.std(), rel=1e-4)


def test_sampler_is_deterministic_and_crops_are_multiples(dataset_dir):
    frames = Dataset(dataset_dir).frames("train")
    a = Sampler(frames, 32, 4, seed=5).batch(3)
    b = Sampler(frames, 32, 4, seed=5).batch(3)
    c = Sampler(frames, 32, 4, seed=6).batch(3)
    assert all(np.array_equal(u, v) for u, v in zip(a, b))
    assert not np.array_equal(a[0], c[0])
    assert a[0].shape == (4, 3, 4, 32, 32) and a[1].shape == (4, 3, 1, 32, 32) and a[2].shape == (3, 1, 32, 32)
    with pytest.raises(ValueError):
        Sampler(frames, 30, 4, seed=5)


def test_manifest_errors_name_the_file(tmp_path, dataset_dir):
    d = tmp_path / "ds"
    shutil.copytree(dataset_dir, d)
    (d / "manifest.json").write_text('{"splits": {"train": ["../x.nsmf"]}}')
    with pytest.raises(DataError, match="manifest.json: "):
        Dataset(str(d))
    (d / "manifest.json").write_text("not json")
    with pytest.raises(DataError, match="manifest.json: "):
        Dataset(str(d))


def test_non_finite_features_and_missing_features_are_refused(tmp_path):
    p = str(tmp_path / "f.nsmf")
    nsm_synthetic.write_frame(p, 0, 7, W, H)
    check_frames([Frame(p)])
    data = bytearray(open(p, "rb").read())
    fr = Frame(p)
    off = fr.feature_offsets[2][fr.features.index("d")] + 4 * 7
    data[off:off + 4] = np.float32(np.nan).tobytes()
    data[-8:] = struct.pack("<Q", fnv1a64(bytes(data[:-8])))  # a valid checksum: the values are bad
    open(p, "wb").write(bytes(data))
    with pytest.raises(DataError, match="feature d of copy 2 has non-finite values"):
        check_frames([Frame(p)])
    with pytest.raises(DataError, match="are missing"):
        check_frames([Frame(p)], names=["d", "n_x"])


def test_open_frames_hold_no_file_descriptors(dataset_dir):
    import resource
    soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    resource.setrlimit(resource.RLIMIT_NOFILE, (min(64, hard), hard))
    try:
        frames = [Frame(frame_path(dataset_dir, i % 6), verify=False) for i in range(200)]
        s = Sampler(frames, 32, 4, seed=1)
        for _ in range(50):
            s.batch(4)
    finally:
        resource.setrlimit(resource.RLIMIT_NOFILE, (soft, hard))
