"""The module's arrays are the programs' files, bit for bit (read by an independent EXR
reader), and its views are views."""
import os
import warnings

import numpy as np

from conftest import run
from exr_read import read_exr

SMALL = ["--width", "160", "--height", "120"]


def test_mask_texels_and_shaded_equal_renders_files(sl, tmp_path):
    for spec in ["csm:res=256,pcf=3", "cmsm:res=128", "tvsm:res=128", "dpcss:res=128"]:
        out = tmp_path / spec.replace(":", "_").replace(",", "_").replace("=", "")
        run("render", "--technique", spec, "--repeats", "1", "--out", str(out), *SMALL)
        scene = sl.scene("default", width=160, height=120)
        r = sl.render(scene, spec)
        mask = read_exr(str(out / "mask.exr"))
        (name,) = mask.keys()
        assert r.mask.dtype == np.float32 and r.mask.shape == (120, 160)
        assert r.mask.tobytes() == mask[name].tobytes(), spec
        texel = read_exr(str(out / "texel.exr"))
        (tname,) = texel.keys()
        assert r.texels.dtype == np.uint32
        assert r.texels.tobytes() == texel[tname].astype(np.uint32).tobytes(), spec
        shaded = read_exr(str(out / "shaded.exr"))
        rgb = np.stack([shaded["R"], shaded["G"], shaded["B"]], axis=-1)
        assert r.shaded().tobytes() == rgb.astype(np.float32).tobytes(), spec


def test_reference_equals_renders_file(sl, tmp_path):
    run("render", "--technique", "rt:spp=16", "--no-cache", "--repeats", "1", "--out",
        str(tmp_path), *SMALL)
    ref = sl.reference(sl.scene("default", width=160, height=120), spp=16, cache=False)
    (name,) = read_exr(str(tmp_path / "mask.exr")).items()
    assert ref.mask.tobytes() == name[1].tobytes()


def test_scene_flags_reach_the_scene(sl, tmp_path):
    # A light and a view set by keyword, the same flags on the command line: the same mask.
    kw = dict(width=96, height=72, light_pos=(0.25, 2.5, -0.5), light_radius=0.05,
              eye=(2.0, 1.5, 3.0), target=(0.0, 0.25, 0.0), fov=50.0)
    flags = ["--width", "96", "--height", "72", "--light-pos", "0.25,2.5,-0.5",
             "--light-radius", "0.05", "--eye", "2,1.5,3", "--target", "0,0.25,0", "--fov", "50"]
    run("render", "--technique", "cvsm:res=128", "--repeats", "1", "--out", str(tmp_path), *flags)
    scene = sl.scene("default", **kw)
    assert scene.light_position == (0.25, 2.5, -0.5)
    assert abs(scene.light_radius - 0.05) < 1e-7
    (name,) = read_exr(str(tmp_path / "mask.exr")).items()
    assert sl.render(scene, "cvsm:res=128").mask.tobytes() == name[1].tobytes()


def test_images_are_views_that_keep_their_owner_alive(sl):
    scene = sl.scene("default", width=64, height=48)
    r = sl.render(scene, "csm:res=64")
    mask = r.mask
    assert not mask.flags.owndata and mask.base is not None
    assert np.shares_memory(mask, r.mask)          # the same buffer on every access
    copy = mask.copy()
    del r                                          # the view keeps the result alive
    assert np.array_equal(mask, copy)
    g = sl.gbuffer(scene)
    pos = g.position
    assert pos.shape == (48, 64, 3) and pos.dtype == np.float32 and not pos.flags.owndata


def test_gbuffer_depth_is_the_distance_along_the_view_axis(sl):
    # Independent of the raster: depth = (p - eye) . forward for the positions it reports.
    scene = sl.scene("default", width=128, height=96)
    g = sl.gbuffer(scene)
    eye, target = np.array(scene.eye), np.array(scene.target)
    forward = (target - eye) / np.linalg.norm(target - eye)
    cov = g.covered.astype(bool)
    assert cov.sum() > 0.5 * cov.size
    along = (g.position[cov].astype(np.float64) - eye) @ forward
    assert np.max(np.abs(along - g.depth[cov]) / along) < 1e-5
    assert np.all(np.isinf(g.depth[~cov]))
    assert np.all(g.mesh_id[~cov] == 0xFFFFFFFF) and np.all(g.mesh_id[cov] < scene.meshes)
    n = g.geo_normal[cov].astype(np.float64)
    assert np.max(np.abs(np.linalg.norm(n, axis=1) - 1.0)) < 1e-5


def test_results_do_not_depend_on_the_thread_count(sl):
    scene = sl.scene("foliage", width=128, height=96)
    sl.set_threads(1)
    one = sl.render(scene, "cpcss:res=256").mask.copy()
    sl.set_threads(2)
    two = sl.render(scene, "cpcss:res=256").mask
    assert one.tobytes() == two.tobytes()


def test_nsm_frame_is_the_file_nsm_data_writes(sl, tmp_path):
    flags = ["--frames", "2", "--width", "64", "--height", "48", "--crop", "32,24",
             "--spp", "4", "--base-res", "64", "--features", "net"]
    run("nsm_data", *flags, "--out", str(tmp_path))
    data = sl.nsm_frame(1, frames=2, width=64, height=48, crop=(32, 24), spp=4, base_res=64,
                        features="net")
    assert data == (tmp_path / "frames" / "000001.nsmf").read_bytes()


def test_nsm_features_follow_their_definitions(sl):
    # d = depth / s and z_f = |p - L| / s, from the GBuffer's own views; s from the scene
    # (|L - target| / 3.12 m; the light moved so that s is not 1).
    scene = sl.scene("default", width=96, height=72, light_pos=(0.5, 2.0, 0.3))
    g = sl.gbuffer(scene)
    f = sl.nsm_features(scene, gbuffer=g, every_candidate=True)
    cov = f["coverage"].astype(bool)
    assert np.array_equal(cov, g.covered.astype(bool))
    s = np.linalg.norm(np.array(scene.light_position) - np.array(scene.target)) / 3.12
    d = g.depth[cov] / s
    assert np.max(np.abs(f["d"][cov] - d) / d) < 1e-5
    zf = np.linalg.norm(g.position[cov].astype(np.float64) - np.array(scene.light_position),
                        axis=1) / s
    assert np.max(np.abs(f["z_f"][cov] - zf) / zf) < 1e-5
    assert np.all(f["d"][~cov] == 0)
    net = sl.nsm_features(scene, gbuffer=g)
    assert list(net) == ["z_over_zf", "z_minus_zf", "c_e_r", "d", "coverage"]


def _write_gltf(path):
    """A floor quad and a smaller quad above it, as glTF 2.0 with an embedded buffer."""
    import base64
    import json
    import struct
    pos = [(-2, 0, -2), (2, 0, -2), (2, 0, 2), (-2, 0, 2),
           (-0.5, 1, -0.5), (0.5, 1, -0.5), (0.5, 1, 0.5), (-0.5, 1, 0.5)]
    idx = [0, 2, 1, 0, 3, 2, 4, 6, 5, 4, 7, 6]
    data = b"".join(struct.pack("<3f", *p) for p in pos) + struct.pack(f"<{len(idx)}H", *idx)
    doc = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 96},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 24}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                       "min": [-2, 0, -2], "max": [2, 1, 2]},
                      {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}]}
    path.write_text(json.dumps(doc))


def test_scene_files_load_as_the_programs_load_them(sl, tmp_path):
    gltf = tmp_path / "quads.gltf"
    _write_gltf(gltf)
    cases = [("assets/scenes/two_bunnies.json", {}, []),
             ("assets/bunny/stanford-bunny.obj", {}, []),
             (str(gltf), dict(light_pos=(0.3, 3.0, 0.2), eye=(3.0, 2.5, 3.0), target=(0.0, 0.0, 0.0)),
              ["--light-pos", "0.3,3,0.2", "--eye", "3,2.5,3", "--target", "0,0,0"])]
    for i, (name, kw, flags) in enumerate(cases):
        out = tmp_path / str(i)
        _, _, err = run("render", "--scene", name, "--technique", "cmsm:res=256", "--repeats",
                        "1", "--out", str(out), *SMALL, *flags)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            scene = sl.scene(name, width=160, height=120, **kw)
        # The program's notes (after its run) are the module's warnings, line for line.
        notes = [l for l in err.splitlines() if l.startswith("note: ")]
        assert [str(w.message) for w in caught] == notes, name
        assert len(notes) == (2 if name.endswith(".gltf") else 0)
        mask = sl.render(scene, "cmsm:res=256").mask
        (expected,) = read_exr(str(out / "mask.exr")).values()
        assert mask.tobytes() == expected.tobytes(), name
        assert 0.01 < float((mask < 0.5).mean()) < 0.95, name   # a shadow in view
