"""Material and camera edits: seen at the next render, without reload, BVH or program build."""

import time

import numpy as np
import pytest

from conftest import CORNELL, RES


def test_material_edit_changes_exactly_the_pixels_that_see_it(gc, device):
    scene = gc.load(CORNELL)
    bvh_before = scene.timings
    # max_depth 2 (direct light): a pixel's value depends on the material it sees first and
    # on the lights, never on the other walls' reflectance.
    r = gc.Renderer(scene, device=device, res=RES, max_depth=2, seed=2)
    # The albedo AOV at the same seed and spp traces the same camera rays: the pixels where it
    # changes are those with a sample whose first hit is the edited material.
    primid = gc.Renderer(scene, device=device, aov="albedo", res=RES, seed=2, spp=4)
    t0 = time.perf_counter()
    before = r.render(spp=4)
    first = time.perf_counter() - t0
    albedo_before = primid.render()
    info = r.info
    setup = info["load_seconds"] + info["bvh_seconds"] + info["upload_seconds"] + info["compile_seconds"]

    scene.materials["leftWall"].base_color = (0.1, 0.2, 0.7)
    assert scene.materials["leftWall"].base_color == pytest.approx((0.1, 0.2, 0.7))
    assert r.sample_count == 0  # the film restarts at the next render
    t0 = time.perf_counter()
    after = r.render(spp=4)
    rerender = time.perf_counter() - t0
    albedo_after = primid.render()
    sees = (albedo_before != albedo_after).any(axis=2)
    changed = (before != after).any(axis=2)
    print(f"\nset-up {setup:.3f} s (load {info['load_seconds']:.4f}, BVH {info['bvh_seconds']:.4f}, upload "
          f"{info['upload_seconds']:.4f}, compile {info['compile_seconds']:.3f}); first render {first:.3f} s; "
          f"re-render after the edit {rerender:.3f} s; program builds since: {r.info['program_builds']}")
    assert sees.any() and not sees.all()
    # Every pixel that changed sees the material; those that see it only in the dark (shadowed
    # wall, no light sampled) keep their zero.
    assert not (changed & ~sees).any()
    assert changed.sum() >= 0.8 * sees.sum()
    assert np.array_equal(before[~sees].view(np.uint32), after[~sees].view(np.uint32))
    assert r.info["program_builds"] == 0 and primid.info["program_builds"] == 0
    assert scene.timings == bvh_before  # no reload, no BVH build

    # The edited scene renders as a fresh renderer of it does.
    fresh = gc.Renderer(scene, device=device, res=RES, max_depth=2, seed=2).render(spp=4)
    assert np.array_equal(after, fresh)


def test_emission_and_params_edits(gc, device):
    scene = gc.load(CORNELL)
    p = scene.params
    assert "materials/light/emission" in p and "camera/fov" in p
    assert p["materials/leftWall/base_color"] == scene.materials["leftWall"].base_color
    r = gc.Renderer(scene, device=device, res=RES)
    bright = r.render(spp=2)
    p["materials/light/emission"] = tuple(2 * v for v in p["materials/light/emission"])
    brighter = r.render(spp=2)
    assert brighter[..., :3].mean() > 1.5 * bright[..., :3].mean()
    p.update({"materials/floor/roughness": 0.5, "materials/floor/metallic": 0.25})
    assert scene.materials["floor"].roughness == 0.5 and scene.materials["floor"].metallic == 0.25
    with pytest.raises(KeyError):
        p["materials/nope/base_color"]
    with pytest.raises(KeyError):
        scene.materials["nope"]
    assert set(scene.materials) == {"leftWall", "rightWall", "floor", "ceiling", "backWall", "shortBox",
                                    "tallBox", "light"}
    assert set(scene.materials["floor"].fields()) >= {"base_color", "emission", "roughness", "metallic",
                                                       "specular", "ior"}


def test_camera_edit_equals_the_cli_overrides(gc, device):
    scene = gc.load(CORNELL)
    r = gc.Renderer(scene, device=device, res=RES)
    a = r.render(spp=2)
    cam = scene.camera
    cam.look_from = (0, 1, 3.9)
    cam.look_at = (0, 1, 0)
    cam.up = (0, 1, 0)
    cam.fov = 30
    assert scene.params["camera/fov"] == 30
    b = r.render(spp=2)
    assert r.sample_count == 2 and not np.array_equal(a, b)
    other = gc.load(CORNELL, look_from=(0, 1, 3.9), look_at=(0, 1, 0), up=(0, 1, 0), fov=30)
    assert np.array_equal(b, gc.Renderer(other, device=device, res=RES).render(spp=2))
    with pytest.raises(gc.ArgumentError):
        cam.fov = 180
    with pytest.raises(ValueError):
        cam.look_at = cam.look_from


def test_thin_lens_equals_the_cli_flags(gc, device, cli, tmp_path):
    import subprocess
    from test_render import read_pfm
    out = tmp_path / "cli.pfm"
    subprocess.run([cli, "--quiet", "--device", device, "--res", f"{RES[0]}x{RES[1]}", "--spp", "4",
                    "--aperture", "0.05", "--focus-distance", "2.5", str(CORNELL), "-o", str(out)], check=True)
    scene = gc.load(CORNELL)
    r = gc.Renderer(scene, device=device, res=RES)
    pinhole = r.render(spp=4)
    scene.camera.set(aperture=0.05, focus_distance=2.5)
    assert scene.params["camera/aperture"] == pytest.approx(0.05)
    lens = r.render(spp=4)
    assert not np.array_equal(pinhole, lens)
    assert np.array_equal(lens[..., :3].view(np.uint32), read_pfm(out).view(np.uint32))
    loaded = gc.load(CORNELL, aperture=0.05, focus_distance=2.5)
    assert np.array_equal(lens, gc.Renderer(loaded, device=device, res=RES).render(spp=4))
    scene.camera.aperture = 0  # back to the pinhole, bit for bit
    assert np.array_equal(r.render(spp=4), pinhole)
    with pytest.raises(gc.ArgumentError):
        scene.camera.aperture = -1
    with pytest.raises(gc.ArgumentError):
        scene.camera.focus_distance = "far"
