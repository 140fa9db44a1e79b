"""Bad input raises ValueError with the program's one-line message (less the program's name)."""
import math

import pytest

from conftest import run

# (call, the same input on the command line)
CASES = [
    (lambda sl: sl.scene("nosuch"), ["render", "--scene", "nosuch", "--technique", "csm"]),
    (lambda sl: sl.scene("default", width=0), ["render", "--width", "0", "--technique", "csm"]),
    (lambda sl: sl.scene("default", light_pos=(math.nan, 1.0, 0.0)),
     ["render", "--light-pos", "nan,1,0", "--technique", "csm"]),
    (lambda sl: sl.scene("default", light_radius=-0.5),
     ["render", "--light-radius", "-0.5", "--technique", "csm"]),
    (lambda sl: sl.scene("missing.obj"), ["render", "--scene", "missing.obj", "--technique", "csm"]),
    (lambda sl: sl.scene("default", eye=(0.0, 40.0, 0.0), target=(0.0, 41.0, 0.0)),
     ["render", "--eye", "0,40,0", "--target", "0,41,0", "--technique", "csm"]),
    (lambda sl: sl.render(sl.scene("default", width=64, height=48), "csm:res=0"),
     ["render", "--width", "64", "--height", "48", "--technique", "csm:res=0"]),
    (lambda sl: sl.render(sl.scene("default", width=64, height=48), "nosuch:res=64"),
     ["render", "--width", "64", "--height", "48", "--technique", "nosuch:res=64"]),
    (lambda sl: sl.render(sl.scene("default", width=64, height=48), "cvsm:blur=4"),
     ["render", "--width", "64", "--height", "48", "--technique", "cvsm:blur=4"]),
    (lambda sl: sl.resolution_sweep(resolutions=[0]), ["resolution_sweep", "--resolutions", "0"]),
    (lambda sl: sl.resolution_sweep(techniques="csm,,cvsm"),
     ["resolution_sweep", "--techniques", "csm,,cvsm"]),
    (lambda sl: sl.resolution_sweep(suite="nosuch"), ["resolution_sweep", "--suite", "nosuch"]),
    (lambda sl: sl.tune(space=["csm:nosuch=1|2"]), ["tune", "--space", "csm:nosuch=1|2"]),
    (lambda sl: sl.tune(objective="speed"), ["tune", "--objective", "speed"]),
    (lambda sl: sl.tune(budget_ms=[-1.0]), ["tune", "--budget-ms", "-1.0"]),
    (lambda sl: sl.nsm_frame(0, crop=(4, 4)), ["nsm_data", "--crop", "4,4"]),
]


@pytest.mark.parametrize("index", range(len(CASES)))
def test_errors_carry_the_programs_message(sl, tmp_path, index):
    call, argv = CASES[index]
    code, _, err = run(argv[0], *argv[1:], "--out", str(tmp_path / "o"), ok=False)
    assert code == 2
    line = err.strip()
    assert "\n" not in line and line.startswith(argv[0] + ": ")
    with pytest.raises(ValueError) as e:
        call(sl)
    assert argv[0] + ": " + str(e.value) == line


def test_module_only_refusals_name_what_is_wrong(sl, tmp_path):
    scene = sl.scene("default", width=64, height=48)
    with pytest.raises(ValueError, match=r"^--shard: "):
        sl._m.resolution_sweep(["--shard", "0/2"])
    with pytest.raises(ValueError, match=r"^--technique: features are the nsm technique's"):
        sl.nsm_features(scene, "csm")
    with pytest.raises(ValueError, match=r"^frame: must lie in \[0, 1\]"):
        sl.nsm_frame(2, frames=2)
    with pytest.raises(ValueError, match=r"^--out: a scene writes no files"):
        sl._m.scene(["--out", str(tmp_path)])
    with pytest.raises(ValueError, match=r"^--width: "):
        sl.scene("default", width=True)            # True is a switch: --width without a value
    with pytest.raises(TypeError):
        sl.scene("default", width=object())
    # A failed call leaves no output folder behind.
    with pytest.raises(ValueError):
        sl.resolution_sweep(scene, techniques="csm:pcf=2", out=str(tmp_path / "x"))
    assert not (tmp_path / "x").exists()
