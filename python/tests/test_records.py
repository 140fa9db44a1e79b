"""A sweep's records are its sweep.csv, a tune's its tune.csv: the same columns, and each
value the text the file holds."""
import csv
import io

from conftest import run

# sweep.csv's number formats (lab/sweep.cpp write_sweep_csv, lab/output_files.cpp).
FOUR = {"psnr", "shadow_ms", "map_ms", "lookup_ms", "faces_ms", "render_ms", "filter_ms",
        "taps_per_pixel"}


def _csv_rows(path):
    lines = [l for l in open(path) if not l.startswith("#")]
    return list(csv.DictReader(io.StringIO("".join(lines))))


def _sweep_text(key, v):
    if v is None:
        return ""
    if isinstance(v, str) or isinstance(v, int):
        return str(v)
    return f"{v:.4f}" if key in FOUR else f"{v:.6f}"


SWEEP = dict(techniques=["csm", "cevsm:blur=3"], resolutions=[64, 128], spp=8, repeats=1,
             cache=False)
SMALL = dict(width=96, height=72)


def test_sweep_records_equal_the_csv_the_call_writes(sl, tmp_path):
    scene = sl.scene("default", **SMALL)
    records = sl.resolution_sweep(scene, out=str(tmp_path), **SWEEP)
    rows = _csv_rows(tmp_path / "sweep.csv")
    assert len(records) == len(rows) == 5
    for rec, row in zip(records, rows):
        assert list(rec) == list(row)
        for k in row:
            assert _sweep_text(k, rec[k]) == row[k], (k, rec[k], row[k])
    assert records[0]["label"] == "RT 8spp" and records[0]["performance"] is None
    assert [r["res"] for r in records[1:]] == [64, 128, 64, 128]


def test_sweep_scores_equal_the_programs(sl, tmp_path):
    run("resolution_sweep", "--techniques", "csm,cevsm:blur=3", "--resolutions", "64,128",
        "--spp", "8", "--repeats", "1", "--no-cache", "--width", "96", "--height", "72",
        "--out", str(tmp_path))
    rows = _csv_rows(tmp_path / "sweep.csv")
    records = sl.resolution_sweep(sl.scene("default", **SMALL), **SWEEP)
    timed = FOUR | {"performance", "total"}   # follow the times of the run
    for rec, row in zip(records, rows):
        for k in row:
            if k not in timed:
                assert _sweep_text(k, rec[k]) == row[k], (k, rec[k], row[k])


def test_tune_records_equal_its_csv(sl, tmp_path):
    records = sl.tune(sl.scene("default", **SMALL), space=["csm:res=64|128", "cvsm:res=64"],
                      budget_ms=[1000], spp=8, repeats=1, cache=False, out=str(tmp_path))
    rows = _csv_rows(tmp_path / "tune.csv")
    assert len(records) == len(rows) == 3
    for rec, row in zip(records, rows):
        assert list(rec) == list(row)
        for k, text in row.items():
            v = rec[k]
            if isinstance(v, float):
                assert v == float(text), (k, v, text)   # written shortest round-trip
            else:
                assert str(v) == text, (k, v, text)
    assert [r["spec"] for r in records] == ["csm:res=64", "csm:res=128", "cvsm:res=64"]
