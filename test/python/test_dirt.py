"""The Python module against the engine's own oracles: the Embree engine
(same seed, the same paths), progressive accumulation (1 + 1 + 2 samples
= 4, bit for bit) and the engine's error ids. Runs against whichever `dirt`
package is on the path: the build tree's (meson test python) or the
installed one (test install)."""
import json
import math
import os
import struct

import numpy as np
import pytest

import dirt

SIZE = dict(width=48, height=36)


def rel_mse(img, ref):
    """The engine's relative MSE (dirt_image_rel_mse): RGB, (img - ref)^2 /
    (ref^2 + 1e-2), the mean in double."""
    a = img[..., :3].astype(np.float64)
    b = ref[..., :3].astype(np.float64)
    return float(np.mean((a - b) ** 2 / (b * b + 1e-2)))


@pytest.fixture(scope="module")
def scene():
    return dirt.Scene()


def test_dirt_equals_embree(scene):
    images = {}
    for engine in ("dirt", "embree"):
        with dirt.Session(scene, engine=engine, seed=3, bounces=2, **SIZE) as s:
            s.add_samples(2)
            images[engine] = s.image()
            assert images[engine].shape == (36, 48, 4)
            assert images[engine].dtype == np.float32
            assert s.stats()["samples"] == 2
    assert images["dirt"][..., :3].mean() > 0.05  # lit, not black
    err = rel_mse(images["dirt"], images["embree"])
    assert err <= 1e-6, err
    # A different seed gives different paths: the comparison can fail.
    with dirt.Session(scene, engine="embree", seed=4, bounces=2, **SIZE) as s:
        s.add_samples(2)
        assert rel_mse(images["dirt"], s.image()) > 1e-4


def test_progressive_equals_one_render(scene):
    with dirt.Session(scene, engine="dirt", seed=5, bounces=2, **SIZE) as s:
        for n in (1, 1, 2):
            s.add_samples(n)
        assert s.samples == 4
        progressive = s.image()
        s.reset()
        s.add_samples(4)
        assert np.array_equal(progressive, s.image())
        s.set_options(seed=6)
        s.add_samples(4)
        assert not np.array_equal(progressive, s.image())
        # The same 4 samples in slices of one smallest piece: a sample spans
        # several calls, the image meanwhile is the completed samples'.
        s.set_options(seed=5)
        calls, shown = 0, None
        while s.samples < 4:
            if s.advance(0):
                shown = s.image()
            elif shown is not None:
                assert s.sample_part > 0 and np.array_equal(shown, s.image())
            calls += 1
        assert calls > 8 and s.sample_part == 0
        assert np.array_equal(progressive, s.image())
        with pytest.raises(dirt.Error) as e:
            s.advance(-1)
        assert e.value.id == "ARGUMENT"


def test_aovs_stats_options_and_outputs(scene, tmp_path):
    with dirt.Session(scene, engine="embree", seed=1, bounces=1, **SIZE) as s:
        s.add_samples(1)
        assert sorted(s.aovs()) == sorted(["albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z",
                                          "Z", "ID"])
        assert s.aov("albedo").shape == (36, 48, 3)
        assert np.array_equal(s.aov("albedo")[..., 1], s.aov("albedo.G"))
        z, ids = s.aov("Z"), s.aov("ID")
        assert z.shape == (36, 48) and np.all(np.isfinite(z[ids >= 0]))
        assert np.all(ids < scene.triangles) and np.all(ids >= -1)
        with pytest.raises(KeyError):
            s.aov("nope")
        st = s.stats()
        assert st["engine"] == "embree" and st["samples"] == 1 and st["rays"] > 0
        assert st["width"] == 48 and st["height"] == 36 and st["device"] == "CPU"
        assert len(st["paths_at_event"]) == st["events"] + 1
        assert all(p["name"] and p["clock"] in ("cpu", "gpu", "none") for p in st["passes"])
        assert "ads" not in st and "mmrt" not in st
        opts = s.options
        assert opts["engine"] == "embree" and opts["seed"] == 1 and opts["bounces"] == 1
        assert s.size == (48, 36)
        s.write(tmp_path / "x.exr")
        s.write(tmp_path / "x.png", exposure=1, tonemap="aces")
        assert (tmp_path / "x.exr").stat().st_size > 1000
        assert (tmp_path / "x.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_structure_stats(scene):
    with dirt.Session(scene, engine="dirt", seed=1, bounces=1, **SIZE) as s:
        s.add_samples(1)
        st = s.stats()
        assert st["ads"]["primitives"] == scene.triangles
        assert st["ads"]["tiles"] > 0 and st["ads"]["nodes"] > 0
        assert st["aborted"] == 0


def _trace_option(scene, name):
    """Renders with DIRT's trace option `name` off and on (2 samples, work
    counted) and checks the images are equal bit for bit, then turns it on
    in an open session: the structure is rebuilt (0 samples) and 2 samples
    give the image with it again. Returns the stats off, on, and after the
    change."""
    images, stats = {}, {}
    for on in (False, True):
        with dirt.Session(scene, engine="dirt", seed=2, bounces=2, count_work=True,
                          **{name: on}, **SIZE) as s:
            assert s.options[name] == on
            s.add_samples(2)
            images[on], stats[on] = s.image(), s.stats()
    assert np.array_equal(images[False], images[True])
    with dirt.Session(scene, engine="dirt", seed=2, bounces=2, **SIZE) as s:
        s.add_samples(2)
        s.set_options(**{name: True})
        assert s.samples == 0 and s.options[name]
        s.add_samples(2)
        assert np.array_equal(images[True], s.image())
        changed = s.stats()
    return stats[False], stats[True], changed


def test_large_grid_option(scene):
    """large_grid (dirt_session_opts): the same image bit for bit, the
    grid's bytes only with it, fewer triangle tests per ray; a change
    rebuilds the structure."""
    off, on, changed = _trace_option(scene, "large_grid")
    assert off["ads"]["bytes_large_grid"] == 0 < on["ads"]["bytes_large_grid"]
    work = [off["work"][0], on["work"][0]]  # primary rays
    assert work[0]["rays"] == work[1]["rays"] > 0
    assert work[1]["triangle_tests"] < work[0]["triangle_tests"]
    assert changed["ads"]["bytes_large_grid"] > 0


def test_sub_tiles_option(scene):
    """sub_tiles (dirt_session_opts): the same image bit for bit, fewer
    triangle tests per camera ray; a change rebuilds the structure."""
    off, on, _ = _trace_option(scene, "sub_tiles")
    work = [off["work"][0], on["work"][0]]  # primary rays
    assert work[0]["rays"] == work[1]["rays"] > 0
    assert work[0]["list_nodes"] == work[1]["list_nodes"]
    assert work[1]["triangle_tests"] < work[0]["triangle_tests"]


def test_bucket_masks_option(scene):
    """bucket_masks (dirt_session_opts): the same image bit for bit, no ray
    type walking more tiles and fewer in all, 4 B per tile of masks only
    with it; a change rebuilds the structure."""
    off, on, changed = _trace_option(scene, "bucket_masks")
    assert off["ads"]["bytes_bucket_masks"] == 0
    assert on["ads"]["bytes_bucket_masks"] > 0
    for a, b in zip(off["work"], on["work"]):
        assert a["rays"] == b["rays"] and b["tiles"] <= a["tiles"]
    assert sum(w["tiles"] for w in on["work"]) < sum(w["tiles"] for w in off["work"])
    assert changed["ads"]["bytes_bucket_masks"] > 0


def test_node_depths_option(scene):
    """node_depths (dirt_session_opts): the same image bit for bit, the
    build says it stored them, no bytes of their own, the same list nodes
    read and fewer triangle tests per secondary ray; a change rebuilds the
    structure."""
    off, on, changed = _trace_option(scene, "node_depths")
    assert not off["ads"]["node_depths"] and on["ads"]["node_depths"]
    assert off["ads"]["bytes_total_used"] == on["ads"]["bytes_total_used"]
    work = [off["work"][2], on["work"][2]]  # specular rays
    assert work[0]["rays"] == work[1]["rays"] > 0
    assert work[0]["list_nodes"] == work[1]["list_nodes"]
    assert work[1]["triangle_tests"] < work[0]["triangle_tests"]
    assert changed["ads"]["node_depths"]


def test_adaptive_depth_buckets_by_name(scene):
    """depth_buckets mirrors the session option: adaptive buckets (by name)
    give the uniform ones' image bit for bit, and their memory is counted."""
    images = {}
    for mode in ("uniform", "adaptive"):
        with dirt.Session(scene, engine="dirt", seed=2, bounces=2, buckets=8,
                          depth_buckets=mode, **SIZE) as s:
            s.add_samples(1)
            assert s.options["depth_buckets"] == mode
            images[mode] = s.image()
            st = s.stats()["ads"]
            assert (st["bytes_bucket_edges"] > 0) == (mode == "adaptive")
    assert np.array_equal(images["uniform"], images["adaptive"])
    with pytest.raises(Exception):
        dirt.Session(scene, engine="dirt", depth_buckets="quantile", **SIZE)


def test_bad_scenes_raise_with_the_loaders_id(tmp_path):
    with pytest.raises(dirt.Error) as e:
        dirt.Scene(tmp_path / "missing.glb")
    assert e.value.kind == "scene" and e.value.id == "IO"
    deep = tmp_path / "deep.gltf"
    deep.write_text('{"asset": {"version": "2.0"}, "x": ' + "[" * 40 + "]" * 40 + "}")
    with pytest.raises(dirt.Error) as e:
        dirt.Scene(deep, max_depth=16)
    assert e.value.id == "TOO_DEEP"
    assert e.value.code == dirt.lib.DIRT_SCENE_ERR_TOO_DEEP
    trunc = tmp_path / "t.glb"
    trunc.write_bytes(b"glTF\x02\x00\x00\x00\xff\x00\x00\x00")
    with pytest.raises(dirt.Error) as e:
        dirt.Scene(trunc)
    assert e.value.id == "TRUNCATED"


def test_scenes_stay_in_their_folder_and_strict_fails_on_warnings(tmp_path):
    (tmp_path / "s").mkdir()
    (tmp_path / "tri.bin").write_bytes(struct.pack("<9f3H2x", 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 2))
    gltf = {"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
            "buffers": [{"byteLength": 44, "uri": "../tri.bin"}],
            "bufferViews": [{"buffer": 0, "byteLength": 36},
                            {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                           "min": [0, 0, 0], "max": [1, 1, 0]},
                          {"bufferView": 1, "componentType": 5123, "count": 3,
                           "type": "SCALAR"}]}
    up = tmp_path / "s" / "up.gltf"
    up.write_text(json.dumps(gltf))
    with pytest.raises(dirt.Error) as e:
        dirt.Scene(up)
    assert e.value.id == "OUTSIDE"
    assert dirt.Scene(up, allow_outside=True).triangles == 1
    gltf["buffers"][0]["uri"] = "tri.bin"
    gltf["extensionsUsed"] = ["KHR_materials_clearcoat"]
    (tmp_path / "ext.gltf").write_text(json.dumps(gltf))
    assert dirt.Scene(tmp_path / "ext.gltf").triangles == 1
    with pytest.raises(dirt.Error) as e:
        dirt.Scene(tmp_path / "ext.gltf", strict=True)
    assert e.value.id == "STRICT"


def test_session_errors_are_ids(scene, tmp_path):
    with pytest.raises(TypeError):
        dirt.Session(scene, widht=64)
    with pytest.raises(ValueError):
        dirt.Session(scene, engine="cycles")
    with pytest.raises(ValueError):
        dirt.Session(scene, width="64")
    with pytest.raises(dirt.Error) as e:
        dirt.Session(scene, tile_size=3, **SIZE)
    assert e.value.kind == "session" and e.value.id == "OPTION"
    with pytest.raises(dirt.Error) as e:
        dirt.Session(scene, engine="mmrt", fetch="raster", **SIZE)
    assert e.value.id == "OPTION"
    with dirt.Session(scene, engine="embree", **SIZE) as s:
        with pytest.raises(dirt.Error) as e:
            s.image()
        assert e.value.id == "NOT_READY"
        with pytest.raises(dirt.Error) as e:
            s.set_camera(7)
        assert e.value.id == "CAMERA" and "camera 7" in e.value.reason
        with pytest.raises(dirt.Error) as e:
            s.set_options(bounces=-1)
        assert e.value.id == "OPTION"
        s.add_samples(1)
        with pytest.raises(dirt.Error) as e:
            s.write(tmp_path / "no" / "such" / "dir.exr")
        assert e.value.id == "IO"
        s.set_camera(eye=(0, 1, 3), target=(0, 1, 0), fov=50)
        s.set_time(0.0)
        s.add_samples(1)
        assert math.isfinite(float(s.image()[..., :3].sum()))
