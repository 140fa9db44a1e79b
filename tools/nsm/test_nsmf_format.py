"""Cross-language check of the .nsmf format: build/programs/nsm_data writes a tiny data set
(a 30x22 window: 660 coverage bytes, so the padding to 64 is exercised),
tools/nsm/nsmf_check.py reads it (skipped when the program is not built)."""
import json
import os
import struct
import subprocess
import sys

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
PROGRAM = os.path.join(os.environ.get("SHADOWLAB_BUILD", os.path.join(ROOT, "build")), "programs", "nsm_data")
sys.path.insert(0, HERE)
import nsmf_check  # noqa: E402


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    if not os.access(PROGRAM, os.X_OK):
        pytest.skip("build/programs/nsm_data is not built")
    out = tmp_path_factory.mktemp("nsm") / "data"
    subprocess.run([PROGRAM, "--width", "64", "--height", "48", "--crop", "30,22", "--frames", "2",
                    "--spp", "4", "--base-res", "64", "--threads", "2", "--out", str(out)],
                   check=True, capture_output=True)
    return out


def test_fnv1a_known_values():
    # The published FNV-1a 64 test vectors.
    assert nsmf_check.fnv1a64(b"") == 0xCBF29CE484222325
    assert nsmf_check.fnv1a64(b"a") == 0xAF63DC4C8601EC8C
    assert nsmf_check.fnv1a64(b"foobar") == 0x85944171F73967E8


def test_frames_read_and_hashes_match(dataset):
    manifest = json.loads((dataset / "manifest.json").read_text())
    names = sorted(sum(manifest["splits"].values(), []))
    assert names == ["000000.nsmf", "000001.nsmf"]
    hashes = b""
    for i, name in enumerate(names):
        header, planes = nsmf_check.read_nsmf(dataset / "frames" / name)
        assert (header["width"], header["height"], header["frame"]) == (30, 22, i)
        assert header["copies"] == 4 and header["spp"] == 4
        assert header["radii"] == [0, 0.075, 0.15, 0.225, 0.3]
        assert len(planes["copies"]) == 4
        c0 = planes["copies"][0]
        cov = c0["coverage"].astype(bool)
        assert cov.any()
        f = c0["features"]
        # The header's derived features from its raw ones, in float32 as the writer forms them.
        np.testing.assert_array_equal(f["z_minus_zf"][cov], (f["z"] - f["z_f"])[cov])
        np.testing.assert_array_equal(f["c_e_r"], f["c_e"])  # stored with r_e = 0
        # The hard reference is 0 or 1.
        assert np.isin(planes["reference"][0], (0.0, 1.0)).all()
        hashes += (dataset / "frames" / name).read_bytes()[-8:]
    # The data set hash: FNV-1a of the frames' hashes in order.
    assert manifest["hash"] == "%016x" % nsmf_check.fnv1a64(hashes)


def test_a_flipped_byte_is_caught(dataset, tmp_path):
    data = bytearray((dataset / "frames" / "000000.nsmf").read_bytes())
    data[len(data) // 2] ^= 1
    bad = tmp_path / "bad.nsmf"
    bad.write_bytes(bytes(data))
    with pytest.raises(nsmf_check.NsmfError, match="hash"):
        nsmf_check.read_nsmf(bad)
