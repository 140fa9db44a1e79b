"""The NSM data set drawn through the Python module instead of files: the frames nsm_data
would write for the same flags, made in memory by shadowlab.nsm_frame (the same bytes) and
read by nsm_data.Frame.from_bytes. A ModuleDataset stands in for nsm_data.Dataset in
nsm_train.train(dataset=...).

    python3 tools/nsm/nsm_module_data.py --frames 8 --steps 20   # times both sources
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time

from nsm_data import Dataset, Frame


class ModuleDataset:
    """nsm_data.Dataset's interface over frames made by shadowlab.nsm_frame(**flags)."""

    def __init__(self, **flags):
        import shadowlab
        self._sl = shadowlab
        self.flags = flags
        self.splits = {"train": [], "val": [], "test": []}
        for i, split in enumerate(shadowlab.nsm_frame_splits(**flags)):
            self.splits[split].append(i)
        self._frames = {}

    @property
    def dataset_hash(self):
        return None  # no manifest: the flags are the data set's identity

    def frame(self, index):
        if index not in self._frames:
            data = self._sl.nsm_frame(index, **self.flags)
            self._frames[index] = Frame.from_bytes(data, name=f"frame {index}")
        return self._frames[index]

    def frames(self, split):
        return [self.frame(i) for i in self.splits[split]]


def _flags_argv(flags):
    out = []
    for k, v in flags.items():
        out += ["--" + k.replace("_", "-"), ",".join(map(str, v)) if isinstance(v, tuple) else str(v)]
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description="time the module's frames against nsm_data's files")
    ap.add_argument("--frames", type=int, default=8)
    ap.add_argument("--steps", type=int, default=20)
    ap.add_argument("--build", default=os.environ.get("SHADOWLAB_BUILD", "build"))
    a = ap.parse_args(argv)
    flags = dict(frames=a.frames, width=256, height=192, crop=(128, 96), spp=64, base_res=256,
                 features="net", split_val=0.25, split_test=0.0)
    from nsm_train import train
    tmp = tempfile.mkdtemp(prefix="nsm_module_")
    try:
        t0 = time.perf_counter()
        subprocess.run([os.path.join(a.build, "programs", "nsm_data"), *_flags_argv(flags),
                        "--out", os.path.join(tmp, "ds")], check=True, capture_output=True)
        files = Dataset(os.path.join(tmp, "ds"))
        files.frames("train"), files.frames("val")
        t_files = time.perf_counter() - t0
        t0 = time.perf_counter()
        module = ModuleDataset(**flags)
        module.frames("train"), module.frames("val")
        t_module = time.perf_counter() - t0
        same = all(files.frame(n).inputs(0, ["d"], 0).tobytes() ==
                   module.frame(int(n.split(".")[0])).inputs(0, ["d"], 0).tobytes()
                   for n in files.splits["train"])
        times = {}
        for name, ds in (("files", files), ("module", module)):
            _, _, _, prov = train(os.path.join(tmp, "ds"), config="nsm3", steps=a.steps, batch=4,
                                  crop=64, log_every=0, dataset=ds)
            times[name] = prov["ms_per_step"]
        print(f"{a.frames} frames of 128x96: nsm_data + reading the files {t_files:.2f} s, "
              f"the module in memory {t_module:.2f} s; same planes: {same}")
        print(f"training ({a.steps} steps, nsm3, batch 4, crop 64): files {times['files']:.1f} "
              f"ms/step, module {times['module']:.1f} ms/step")
    finally:
        shutil.rmtree(tmp)


if __name__ == "__main__":
    sys.exit(main())
