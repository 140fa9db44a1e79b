"""shadowlab from Python: scenes, GBuffers, shadow techniques, the ray-traced reference, the
shadow metric with FLIP, resolution sweeps, tuning and the NSM features, in memory.

Every call runs the library code the programs run, with their flag rules: a keyword argument
``light_pos=(1, 2, 3)`` is the flag ``--light-pos 1,2,3``, and bad input raises ValueError
with the program's one-line message ("--light-pos: ..."). The GIL is released while a call
works; threads, determinism and the reference cache are the programs' (docs/python.md).

    >>> import shadowlab as sl
    >>> scene = sl.scene("default", width=320, height=240)
    >>> csm = sl.render(scene, "csm:res=1024")
    >>> ref = sl.reference(scene, spp=64)
    >>> sl.metric(csm, ref)["total"]
"""
from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _shadowlab as _m

__all__ = ["Scene", "GBuffer", "Result", "set_threads", "threads", "version", "scene",
           "gbuffer", "render", "reference", "metric", "resolution_sweep", "tune",
           "nsm_features", "nsm_frame", "nsm_frame_splits"]

Scene = _m.Scene
GBuffer = _m.GBuffer
Vec3 = Tuple[float, float, float]
Record = Dict[str, Union[str, int, float, None]]


def _text(value: Any) -> str:
    """A value as the programs' flags take it: numbers round-trip exactly (repr), sequences
    are comma-separated."""
    if isinstance(value, (bool, np.bool_)):
        raise TypeError("a switch takes True or False, not a value")
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    if isinstance(value, str):
        return value
    if isinstance(value, (list, tuple, np.ndarray)):
        return ",".join(_text(v) for v in value)
    raise TypeError(f"cannot pass {type(value).__name__} as a flag value")


def _flags(repeated: Sequence[str] = (), **options: Any) -> List[str]:
    """Keyword arguments as a program's flags: None and False are absent, True is a switch,
    `repeated` names the flags given once per item of a list (tune's --space)."""
    out: List[str] = []
    for key, value in options.items():
        if value is None or value is False:
            continue
        flag = "--" + key.replace("_", "-")
        if value is True:
            out.append(flag)
        elif key in repeated and isinstance(value, (list, tuple)):
            for item in value:
                out += [flag, _text(item)]
        else:
            out += [flag, _text(value)]
    return out


def set_threads(n: int) -> None:
    """Sets the worker threads of every later call (the programs' --threads; 1..1024).
    Results do not depend on it."""
    _m.set_threads(int(n))


def threads() -> int:
    """The worker threads calls use ($SHADOWLAB_THREADS or the core count by default)."""
    return _m.threads()


def version() -> str:
    """shadowlab's version and the commit the module was built from."""
    return f"{_m.version()} ({_m.commit()})"


def scene(name: str = "default", *, width: Optional[int] = None, height: Optional[int] = None,
          light_pos: Optional[Vec3] = None, light_radius: Optional[float] = None,
          eye: Optional[Vec3] = None, target: Optional[Vec3] = None,
          fov: Optional[float] = None, ground: bool = False, light: Optional[int] = None,
          camera: Optional[int] = None, alpha_cutoff: Optional[float] = None,
          no_alpha: bool = False, slide: Optional[str] = None,
          projector_pos: Optional[Vec3] = None, projector_target: Optional[Vec3] = None,
          projector_fov: Optional[float] = None, projector_aspect: Optional[float] = None,
          max_memory: Optional[float] = None) -> Scene:
    """A scene: a built-in name (default, foliage, bunny, grazing, ...), an .obj, .gltf/.glb
    or .json scene file, with the light, camera and projector set as the programs' common
    flags set them (docs/programs/common_flags.md). Raises ValueError for bad input."""
    return _m.scene(_flags(scene=name, width=width, height=height, light_pos=light_pos,
                           light_radius=light_radius, eye=eye, target=target, fov=fov,
                           ground=ground, light=light, camera=camera,
                           alpha_cutoff=alpha_cutoff, no_alpha=no_alpha, slide=slide,
                           projector_pos=projector_pos, projector_target=projector_target,
                           projector_fov=projector_fov, projector_aspect=projector_aspect,
                           max_memory=max_memory))


def gbuffer(scene: Scene, repeats: int = 1) -> GBuffer:
    """The camera pass: per pixel the world position and geometric normal (views of shape
    (height, width, 3)), view depth, mesh and triangle ids and coverage (views of shape
    (height, width)); camera_ms is the median over `repeats` timed runs."""
    return _m.gbuffer(scene, int(repeats))


class Result:
    """A technique's result. `mask` (float32, (height, width), 1 lit, 0 shadowed) and
    `texels` (uint32 texel index per pixel, or None) are views of the result's own buffers;
    `times` (ms per phase, medians), `work` (counts) and `faces` are dicts; `shaded()` makes
    the shaded picture (a copy, (height, width, 3), linear RGB)."""

    def __init__(self, raw: Any, scene: Scene, gbuffer: GBuffer):
        self._raw = raw
        self.scene = scene
        self.gbuffer = gbuffer

    @property
    def spec(self) -> str:
        return self._raw.spec

    @property
    def mask(self) -> np.ndarray:
        return self._raw.mask

    @property
    def texels(self) -> Optional[np.ndarray]:
        return self._raw.texels

    @property
    def times(self) -> Dict[str, float]:
        return self._raw.times

    @property
    def work(self) -> Dict[str, Union[int, float]]:
        return self._raw.work

    @property
    def faces(self) -> Dict[str, int]:
        return self._raw.faces

    @property
    def notes(self) -> str:
        return self._raw.notes

    def shaded(self, ambient: float = 0.1) -> np.ndarray:
        """The shaded picture (render's shaded.exr): albedo × (ambient + (1 − ambient) ×
        mask × N·L), linear RGB, a new array."""
        return self._raw.shaded(self.scene, self.gbuffer, float(ambient))

    def __repr__(self) -> str:
        t = self.times
        return (f"<shadowlab.Result {self.spec}: shadow {t['shadow_ms']:.3f} ms, "
                f"{self.mask.shape[1]}x{self.mask.shape[0]}>")


def render(scene: Scene, technique: str, *, gbuffer: Optional[GBuffer] = None,
           repeats: int = 1, cache: bool = True, texels: bool = True) -> Result:
    """Runs one technique spec ("csm:res=1024,pcf=3", "cmsm", "nsm", "rt:spp=256", ...; see
    `render --list-techniques`) on the scene's GBuffer (made here when not given), timed over
    `repeats` runs (the medians in .times). `cache`: the ray-traced reference may come from
    and go to the programs' disk cache."""
    g = gbuffer if gbuffer is not None else _m.gbuffer(scene, 1)
    return Result(_m.render(scene, technique, g, int(repeats), bool(cache), bool(texels)),
                  scene, g)


def reference(scene: Scene, spp: int = 256, *, gbuffer: Optional[GBuffer] = None,
              cache: bool = True) -> Result:
    """The ray-traced (Embree) reference at `spp` light samples per pixel: render(scene,
    f"rt:spp={spp}")."""
    return render(scene, f"rt:spp={int(spp)}", gbuffer=gbuffer, cache=cache)


ImageLike = Union[np.ndarray, Result]


def metric(test: ImageLike, ref: ImageLike, *, texels: Optional[np.ndarray] = None,
           shadow_ms: Optional[float] = None, fps: float = 30.0) -> Dict[str, float]:
    """The shadow metric of a test mask against a reference mask (float32 arrays of one shape,
    values in [0, 1], or Results): the keys of `metric --json` in its order (c10 ... psnr,
    flip_mean), full precision. A Result test brings its texel image (the detail score) unless
    `texels` is given; `shadow_ms` adds the performance score at `fps`."""
    if isinstance(test, Result):
        if texels is None:
            texels = test.texels
        test = test.mask
    if isinstance(ref, Result):
        ref = ref.mask
    return _m.metric(test, ref, texels, shadow_ms, float(fps))


def _scene_flags(scene: Union[str, Scene, None]) -> List[str]:
    if scene is None:
        return []
    if isinstance(scene, str):
        return ["--scene", scene]
    return list(scene.flags)


def resolution_sweep(scene: Union[str, Scene, None] = None, *, techniques: Union[str, Sequence[str]] = "csm",
                     resolutions: Optional[Sequence[int]] = None, spp: Optional[int] = None,
                     repeats: Optional[int] = None, quick: bool = False, cache: bool = True,
                     suite: Optional[str] = None, out: Optional[str] = None,
                     plot: Optional[str] = None, sheet: Optional[str] = None,
                     ambient: Optional[float] = None, flip_map: bool = False) -> List[Record]:
    """resolution_sweep: every technique at every resolution against the reference, one
    record per row (the reference first) with the columns of sweep.csv (empty cells None).
    `techniques` is a list of specs or the program's comma-separated text; `quick` is the
    CI size. With `out`, the program's files are written there too (sweep.csv, sweep.json,
    contact_sheet.png, the masks; `plot` an SVG in it). Records load in pandas:
    pandas.DataFrame(records)."""
    if not isinstance(techniques, str):
        techniques = ",".join(techniques)
    return _m.resolution_sweep(_scene_flags(scene) + _flags(
        techniques=techniques, resolutions=resolutions, spp=spp, repeats=repeats, quick=quick,
        no_cache=not cache, suite=suite, out=out, plot=plot, sheet=sheet, ambient=ambient,
        flip_map=flip_map))


def tune(scene: Union[str, Scene, None] = None, *, space: Optional[Sequence[str]] = None,
         budget_ms: Optional[Sequence[float]] = None,
         budget_bytes: Optional[Sequence[float]] = None, objective: Optional[str] = None,
         metric_weights: Optional[str] = None, strategy: Optional[str] = None,
         max_evals: Optional[int] = None, spp: Optional[int] = None,
         repeats: Optional[int] = None, quick: bool = False, cache: bool = True,
         suite: Optional[str] = None, out: Optional[str] = None,
         references_only: bool = False) -> List[Record]:
    """tune: parameter spaces ("csm:res=256..2048/x2,pcf=1|3|5", one per item of `space`)
    searched against the reference; one record per full-size evaluation with the columns of
    tune.csv. With `out`, the program's files (tune.csv, tune.json, tune.svg with the budget
    winners) are written there too."""
    return _m.tune(_scene_flags(scene) + _flags(
        repeated=("space",), space=space, budget_ms=budget_ms, budget_bytes=budget_bytes,
        objective=objective, metric_weights=metric_weights, strategy=strategy,
        max_evals=max_evals, spp=spp, repeats=repeats, quick=quick, no_cache=not cache,
        suite=suite, out=out, references_only=references_only))


def nsm_features(scene: Scene, technique: str = "nsm", *, gbuffer: Optional[GBuffer] = None,
                 every_candidate: bool = False) -> Dict[str, np.ndarray]:
    """The Neural Shadow Mapping network's input planes for the scene's GBuffer: the spec's
    base map rendered, then the features its weights read (z_over_zf, z_minus_zf, c_e_r, d
    for the shipped model) or every candidate feature; float32 (height, width) views, and
    "coverage" (uint8)."""
    g = gbuffer if gbuffer is not None else _m.gbuffer(scene, 1)
    return _m.nsm_features(scene, g, technique, bool(every_candidate))


def _nsm_data_flags(scenes=None, frames=None, width=None, height=None, crop=None, radii=None,
                    spp=None, base_res=None, seed=None, features=None, split_val=None,
                    split_test=None) -> List[str]:
    if scenes is not None and not isinstance(scenes, str):
        scenes = ",".join(scenes)
    if features is not None and not isinstance(features, str):
        features = ",".join(features)
    return _flags(scenes=scenes, frames=frames, width=width, height=height, crop=crop,
                  radii=radii, spp=spp, base_res=base_res, seed=seed, features=features,
                  split_val=split_val, split_test=split_test)


def nsm_frame(frame: int, *, scenes: Union[str, Sequence[str], None] = None,
              frames: Optional[int] = None, width: Optional[int] = None,
              height: Optional[int] = None, crop: Optional[Tuple[int, int]] = None,
              radii: Optional[Sequence[float]] = None, spp: Optional[int] = None,
              base_res: Optional[int] = None, seed: Optional[int] = None,
              features: Union[str, Sequence[str], None] = None,
              split_val: Union[float, str, None] = None,
              split_test: Union[float, str, None] = None) -> bytes:
    """Frame `frame` of the data set nsm_data's flags describe, as the bytes of its .nsmf file
    (tools/nsm/nsm_data.py reads them: Frame.from_bytes), made in memory: the same bytes
    `nsm_data` writes for the same flags."""
    return _m.nsm_frame(_nsm_data_flags(scenes, frames, width, height, crop, radii, spp,
                                        base_res, seed, features, split_val, split_test),
                        int(frame))


def nsm_frame_splits(**flags: Any) -> List[str]:
    """The split ("train", "val" or "test") of every frame of the data set that nsm_data's
    flags (nsm_frame's keywords) describe, as its manifest.json lists them."""
    return _m.nsm_frame_splits(_nsm_data_flags(**flags))
