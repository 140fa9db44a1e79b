"""Reads the NSM data set (docs/techniques/nsm.md, "Data set on disk") and yields training
samples.

A data set is a folder with manifest.json and frames/NNNNNN.nsmf. A frame file is: magic
"NSMF", u32 version 1, u32 header length H, H bytes of JSON, zero padding to a multiple of 64,
then 64-byte aligned little-endian planes (copy 0..3: every feature, then the u8 coverage; then
one fp32 reference visibility per radius), then the FNV-1a 64 of every byte before it. Every
check runs before a plane is read, and a frame whose hash differs is refused.
"""
import json
import math
import os
import struct

import numpy as np

from nsm_fnv import fnv1a64
from nsm_model import DEFAULT_FEATURES

R_MAX = 0.3          # m: c_e_r = c_e + 4 R / R_MAX
SCALE_REF = 3.12     # m: the default scene's |L - camera target|
COPIES = 4
MAGIC = b"NSMF"
VERSION = 1
MAX_HEADER = 1 << 20


class DataError(Exception):
    """A data set file that is not as documented: str() is "<file>: <reason>"."""


def align64(n):
    return (n + 63) // 64 * 64


def radius_code(radius):
    return 4.0 * radius / R_MAX


class Frame:
    """One .nsmf frame, checked and memory-mapped."""

    def __init__(self, path, verify=True, data=None):
        """`data`: the file's bytes, already in memory (shadowlab.nsm_frame makes them
        without a file); `path` then only names the frame in messages."""
        self.path = path
        self._data = data
        try:
            size = len(data) if data is not None else os.path.getsize(path)
            head = self._read(0, 12)
        except OSError as e:
            raise DataError(f"{path}: {e.strerror or e}")
        if len(head) < 12 or head[:4] != MAGIC:
            raise DataError(f"{path}: not an NSMF file (bad magic)")
        version, hlen = struct.unpack("<II", head[4:12])
        if version != VERSION:
            raise DataError(f"{path}: version {version}, expected {VERSION}")
        if hlen == 0 or hlen > MAX_HEADER or 12 + hlen + 8 > size:
            raise DataError(f"{path}: header length {hlen} does not fit the file")
        raw = self._read(12, hlen)
        try:
            hdr = json.loads(raw.decode("utf-8"))
        except (UnicodeDecodeError, json.JSONDecodeError) as e:
            raise DataError(f"{path}: header is not JSON ({e})")
        self.header = hdr
        self._check_header(hdr)
        # Layout: every plane starts 64-byte aligned; the hash is the file's last 8 bytes.
        offset = align64(12 + hlen)
        self.feature_offsets = []   # [copy][feature]
        self.coverage_offsets = []  # [copy]
        npx = self.width * self.height
        for _ in range(COPIES):
            row = []
            for _ in self.features:
                row.append(offset)
                offset = align64(offset + 4 * npx)
            self.feature_offsets.append(row)
            self.coverage_offsets.append(offset)
            offset = align64(offset + npx)
        self.reference_offsets = []
        end = offset
        for _ in self.radii:
            self.reference_offsets.append(offset)
            end = offset + 4 * npx
            offset = align64(end)
        # The writer may or may not zero-pad after the last plane: allow 0..63 bytes.
        if not (end + 8 <= size <= offset + 8):
            raise DataError(f"{path}: size {size} bytes, expected {end + 8} for {self.width}x"
                            f"{self.height}, {len(self.features)} features, {len(self.radii)} radii")
        self.size = size
        if verify:
            self.verify()

    def _check_header(self, h):
        p = self.path
        for key, kind in (("width", int), ("height", int), ("features", list), ("copies", int),
                          ("radii", list), ("scale", (int, float))):
            if key not in h:
                raise DataError(f"{p}: header has no \"{key}\"")
            if not isinstance(h[key], kind) or isinstance(h[key], bool):
                raise DataError(f"{p}: header \"{key}\" has the wrong type")
        self.width, self.height = h["width"], h["height"]
        if not (0 < self.width <= 1 << 15 and 0 < self.height <= 1 << 15):
            raise DataError(f"{p}: size {self.width}x{self.height} out of range")
        if h["copies"] != COPIES:
            raise DataError(f"{p}: copies {h['copies']}, expected {COPIES}")
        self.features = h["features"]
        if not self.features or not all(isinstance(n, str) for n in self.features) \
                or len(set(self.features)) != len(self.features):
            raise DataError(f"{p}: features must be distinct names")
        self.radii = h["radii"]
        if not self.radii or not all(isinstance(r, (int, float)) and not isinstance(r, bool)
                                     and math.isfinite(r) and 0 <= r <= R_MAX for r in self.radii):
            raise DataError(f"{p}: radii must be numbers in [0, {R_MAX}]")
        self.scale = float(h["scale"])
        self.scene = str(h.get("scene", ""))
        if not (math.isfinite(self.scale) and self.scale > 0):
            raise DataError(f"{p}: scale must be positive")

    @classmethod
    def from_bytes(cls, data, name="<memory>", verify=True):
        """A frame from the bytes of its file (shadowlab.nsm_frame)."""
        return cls(name, verify, bytes(data))

    def _read(self, offset, n):
        if self._data is not None:
            return self._data[offset:offset + n]
        with open(self.path, "rb") as f:
            f.seek(offset)
            return f.read(n)

    def verify(self):
        data = self._data if self._data is not None else self._read(0, self.size)
        stored = struct.unpack("<Q", data[-8:])[0]
        if fnv1a64(data[:-8]) != stored:
            raise DataError(f"{self.path}: FNV-1a 64 checksum mismatch (corrupt or truncated)")
        return stored

    def _plane(self, offset, dtype):
        # Mapped on each access and released with the array: a data set of thousands of frames
        # holds no file descriptor open between samples (a mapping keeps one).
        if self._data is not None:
            return np.frombuffer(self._data, dtype=dtype, count=self.width * self.height,
                                 offset=offset).reshape(self.height, self.width)
        return np.memmap(self.path, dtype=dtype, mode="r", offset=offset,
                         shape=(self.height, self.width))

    def feature(self, copy, name):
        if name not in self.features:
            raise DataError(f"{self.path}: feature \"{name}\" is not in the file")
        return self._plane(self.feature_offsets[copy][self.features.index(name)], "<f4")

    def coverage(self, copy):
        return self._plane(self.coverage_offsets[copy], np.uint8)

    def reference(self, radius_index):
        return self._plane(self.reference_offsets[radius_index], "<f4")

    def inputs(self, copy, names, radius_index, y0=0, x0=0, h=None, w=None):
        """[F, h, w] float32: the named features of one copy, cropped; c_e_r gets the radius
        code 4 R / R_MAX of radii[radius_index] added (the file stores it with r_e = 0)."""
        h = self.height if h is None else h
        w = self.width if w is None else w
        out = np.empty((len(names), h, w), np.float32)
        for i, n in enumerate(names):
            out[i] = self.feature(copy, n)[y0:y0 + h, x0:x0 + w]
            if n == "c_e_r":
                out[i] += np.float32(radius_code(self.radii[radius_index]))
        return out


class Dataset:
    """manifest.json + the frames of its splits."""

    def __init__(self, folder, verify=True):
        self.folder = folder
        mpath = os.path.join(folder, "manifest.json")
        try:
            with open(mpath, "rb") as f:
                self.manifest = json.loads(f.read().decode("utf-8"))
        except OSError as e:
            raise DataError(f"{mpath}: {e.strerror or e}")
        except (UnicodeDecodeError, json.JSONDecodeError) as e:
            raise DataError(f"{mpath}: not JSON ({e})")
        splits = self.manifest.get("splits") if isinstance(self.manifest, dict) else None
        if not isinstance(splits, dict):
            raise DataError(f"{mpath}: no \"splits\" object")
        self.splits = {}
        for name in ("train", "val", "test"):
            names = splits.get(name, [])
            if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
                raise DataError(f"{mpath}: split \"{name}\" must be a list of file names")
            for n in names:
                if os.path.isabs(n) or ".." in n.split("/"):
                    raise DataError(f"{mpath}: frame name \"{n}\" leaves the data set folder")
            self.splits[name] = names
        self.verify = verify
        self._frames = {}

    @property
    def dataset_hash(self):
        return self.manifest.get("hash")

    def frame_path(self, name):
        # Split entries are frame file names inside frames/ (a name with a folder is taken
        # relative to the data set folder).
        return os.path.join(self.folder, name if "/" in name else os.path.join("frames", name))

    def frame(self, name):
        if name not in self._frames:
            self._frames[name] = Frame(self.frame_path(name), self.verify)
        return self._frames[name]

    def frames(self, split):
        return [self.frame(n) for n in self.splits[split]]


def check_frames(frames, names=DEFAULT_FEATURES):
    """Before training: every frame has the network's features, and its feature planes (every
    copy) and references are finite (one pass over the memory-mapped planes)."""
    for fr in frames:
        missing = [n for n in names if n not in fr.features]
        if missing:
            raise DataError(f"{fr.path}: features {missing} are missing")
        for c in range(COPIES):
            for n in names:
                if not np.isfinite(fr.feature(c, n)).all():
                    raise DataError(f"{fr.path}: feature {n} of copy {c} has non-finite values")
        for k in range(len(fr.radii)):
            if not np.isfinite(fr.reference(k)).all():
                raise DataError(f"{fr.path}: reference {k} has non-finite values")


def feature_stats(frames, names=DEFAULT_FEATURES):
    """Per feature mean and std over the covered pixels of copy 0 of `frames`, in float64.
    For c_e_r every radius of a frame counts once per pixel (the reader draws radii uniformly),
    so its statistics are those of c_e + 4 R / R_MAX over the draws. A std below 1e-6 is 1."""
    s = np.zeros(len(names))
    ss = np.zeros(len(names))
    n = np.zeros(len(names))
    for fr in frames:
        cov = fr.coverage(0) != 0
        for i, name in enumerate(names):
            v = fr.feature(0, name)[cov].astype(np.float64)
            offsets = [radius_code(r) for r in fr.radii] if name == "c_e_r" else [0.0]
            for o in offsets:
                s[i] += (v + o).sum()
                ss[i] += ((v + o) ** 2).sum()
                n[i] += v.size
    n = np.maximum(n, 1)
    mean = s / n
    std = np.sqrt(np.maximum(ss / n - mean * mean, 0.0))
    std = np.where(std < 1e-6, 1.0, std)
    return mean.astype(np.float32), std.astype(np.float32)


def loss_mask(fr, copy):
    """The pixels that carry loss: covered, and facing the light where the frame stores c_e
    (the technique writes 0 on surfaces facing away, whatever the network says: the mask
    convention of docs/design.md §4)."""
    m = np.array(fr.coverage(copy)) != 0
    if "c_e" in fr.features:
        m &= np.array(fr.feature(copy, "c_e")) > 0
    return m


class Sampler:
    """Deterministic training samples from a seed: frames in a fresh random order each pass,
    per sample a radius drawn uniformly from the frame's radii and a crop position."""

    def __init__(self, frames, crop, multiple, seed, names=DEFAULT_FEATURES):
        if crop % multiple:
            raise ValueError(f"crop {crop} is not a multiple of {multiple}")
        for fr in frames:
            if fr.width < crop or fr.height < crop:
                raise DataError(f"{fr.path}: {fr.width}x{fr.height} is smaller than the crop {crop}")
        if not frames:
            raise ValueError("no training frames")
        self.frames, self.crop, self.names = frames, crop, names
        self.rng = np.random.Generator(np.random.PCG64(seed))
        self.order = []

    def sample(self):
        if not self.order:
            self.order = list(self.rng.permutation(len(self.frames)))
        fr = self.frames[self.order.pop(0)]
        k = int(self.rng.integers(len(fr.radii)))
        y0 = int(self.rng.integers(fr.height - self.crop + 1))
        x0 = int(self.rng.integers(fr.width - self.crop + 1))
        c = self.crop
        x = np.stack([fr.inputs(cp, self.names, k, y0, x0, c, c) for cp in range(COPIES)])
        cov = np.stack([loss_mask(fr, cp)[y0:y0 + c, x0:x0 + c] for cp in range(COPIES)])
        target = np.array(fr.reference(k)[y0:y0 + c, x0:x0 + c], np.float32)
        return x, cov.astype(np.float32), target

    def batch(self, n):
        """inputs [COPIES, n, F, c, c], coverage [COPIES, n, 1, c, c], target [n, 1, c, c]."""
        xs, covs, ts = zip(*(self.sample() for _ in range(n)))
        x = np.stack(xs, axis=1)
        cov = np.stack(covs, axis=1)[:, :, None]
        t = np.stack(ts)[:, None]
        return x, cov, t
