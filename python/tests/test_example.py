"""examples/compare_two.py runs and draws its figure."""
import os
import subprocess
import sys

import numpy as np
from conftest import ROOT


def test_example_runs_and_draws(tmp_path):
    p = subprocess.run([sys.executable, os.path.join(ROOT, "examples", "compare_two.py"),
                        "--quick", "--out", str(tmp_path)], cwd=ROOT, capture_output=True,
                       text=True, timeout=600)
    assert p.returncode == 0, p.stderr
    lines = [l for l in p.stdout.splitlines() if " ms  total " in l]
    assert len(lines) == 6                       # 2 techniques x 3 resolutions
    import matplotlib.image as mpimg
    img = mpimg.imread(str(tmp_path / "compare_two.png"))
    assert img.shape[1] == 16 * 80 and img.shape[0] == int(3.6 * 80)
    # Not a blank figure: the masks put dark pixels in the right half.
    assert np.min(img[:, img.shape[1] // 2:, :3]) < 0.2
