"""The NSM training's frames drawn through the module: the same splits and planes as the
data set nsm_data writes for the same flags."""
import json
import os
import sys

import numpy as np

from conftest import ROOT, run

sys.path.insert(0, os.path.join(ROOT, "tools", "nsm"))

FLAGS = dict(frames=6, width=64, height=48, crop=(32, 24), spp=4, base_res=64, features="net",
             split_val=0.34, split_test=0.17)
ARGV = ["--frames", "6", "--width", "64", "--height", "48", "--crop", "32,24", "--spp", "4",
        "--base-res", "64", "--features", "net", "--split-val", "0.34", "--split-test", "0.17"]


def test_module_frames_are_the_data_sets(sl, tmp_path):
    from nsm_data import Dataset
    from nsm_module_data import ModuleDataset
    run("nsm_data", *ARGV, "--out", str(tmp_path))
    files = Dataset(str(tmp_path))
    module = ModuleDataset(**FLAGS)
    manifest = json.load(open(tmp_path / "manifest.json"))["splits"]
    for split in ("train", "val", "test"):
        assert [f"{i:06d}.nsmf" for i in module.splits[split]] == manifest[split], split
    assert sum(len(v) for v in module.splits.values()) == 6
    for name in files.splits["train"] + files.splits["val"]:
        a, b = files.frame(name), module.frame(int(name.split(".")[0]))
        for copy in range(4):
            assert np.array_equal(a.inputs(copy, a.features, 2), b.inputs(copy, b.features, 2))
            assert np.array_equal(a.coverage(copy), b.coverage(copy))
        for k in range(len(a.radii)):
            assert np.array_equal(a.reference(k), b.reference(k))
