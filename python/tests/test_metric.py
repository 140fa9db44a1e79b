"""The metric dict is `metric --json` of the same masks: the same keys in the same order, and
the same doubles (the program prints them shortest round-trip)."""
import json

import numpy as np

from conftest import run
from exr_read import read_exr


def _program_json(*args):
    _, out, _ = run("metric", *args, "--json")
    return json.loads(out)


def test_metric_dict_equals_metric_json(sl, tmp_path):
    scene = sl.scene("default", width=160, height=120)
    flags = ["--width", "160", "--height", "120", "--repeats", "1"]
    run("render", "--technique", "cvsm:res=256", "--out", str(tmp_path / "t"), *flags)
    run("render", "--technique", "rt:spp=16", "--no-cache", "--out", str(tmp_path / "r"), *flags)
    t, r = tmp_path / "t", tmp_path / "r"
    (test,) = read_exr(str(t / "mask.exr")).values()
    (ref,) = read_exr(str(r / "mask.exr")).values()
    (tex,) = read_exr(str(t / "texel.exr")).values()
    for extra, kw in [([], {}), (["--texels", str(t / "texel.exr")], {"texels": tex}),
                      (["--texels", str(t / "texel.exr"), "--shadow-ms", "12.5", "--fps", "60"],
                       {"texels": tex, "shadow_ms": 12.5, "fps": 60.0})]:
        expected = _program_json(str(t / "mask.exr"), str(r / "mask.exr"), *extra)
        got = sl.metric(test, ref, **kw)
        assert list(got) == list(expected)
        for k, v in got.items():
            assert v == expected[k], (k, extra)
    # A Result brings its texel image: the same as passing it.
    res = sl.render(scene, "cvsm:res=256")
    assert sl.metric(res, ref) == sl.metric(res.mask, ref, texels=res.texels)
    assert sl.metric(res, ref)["detail"] != sl.metric(res.mask, ref)["detail"]


def test_metric_refuses_what_it_would_otherwise_convert(sl):
    a = np.ones((8, 8), np.float32)
    for bad, word in [(a.astype(np.float64), "float64"), (a[None], "3 dimensions"),
                      (np.ones((0, 8), np.float32), "each side")]:
        try:
            sl.metric(bad, a)
        except ValueError as e:
            assert str(e).startswith("metric: test: ") and word in str(e), str(e)
        else:
            raise AssertionError(f"accepted {word}")
