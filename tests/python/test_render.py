"""Rendering through geocold: the CLI's bits, continuation, sums, AOVs, lifetimes, threads."""

import gc as pygc
import os
import signal
import subprocess
import sys
import threading

import numpy as np
import pytest

from conftest import CORNELL, RES


def read_pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        w, h = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(h, w, 3)[::-1]  # PFM rows run bottom to top


@pytest.mark.parametrize("integrator,extra,kwargs", [("path", [], {}), ("whitted", [], {}),
                                                     ("aov", ["--aov", "albedo"], {"aov": "albedo"}),
                                                     ("path", ["--sampler", "independent"], {"sampler": "independent"})])
def test_render_equals_cli_bit_for_bit(gc, cornell, device, cli, tmp_path, integrator, extra, kwargs):
    spp = 1 if integrator == "aov" else 8
    out = tmp_path / "cli.pfm"
    subprocess.run([cli, "--quiet", "--device", device, "--res", f"{RES[0]}x{RES[1]}", "--spp", str(spp),
                    "--seed", "3", "--integrator", integrator, *extra, str(CORNELL), "-o", str(out)], check=True)
    img = gc.Renderer(cornell, device=device, integrator=integrator, res=RES, seed=3, **kwargs).render(spp=spp)
    assert img.dtype == np.float32 and img.shape == (RES[1], RES[0], 4)
    assert np.array_equal(img[..., :3].view(np.uint32), read_pfm(out).view(np.uint32))


def test_python_m_geocold_behaves_like_the_cli(device, cli, tmp_path):
    args = ["--quiet", "--device", device, "--res", "32x24", "--spp", "4", str(CORNELL)]
    subprocess.run([cli, *args, "-o", str(tmp_path / "cli.pfm")], check=True)
    subprocess.run([sys.executable, "-m", "geocold", *args, "-o", str(tmp_path / "py.pfm")], check=True)
    assert (tmp_path / "cli.pfm").read_bytes() == (tmp_path / "py.pfm").read_bytes()
    bad = subprocess.run([sys.executable, "-m", "geocold", "--no-such-option"], capture_output=True, text=True)
    assert bad.returncode == 2 and "--no-such-option" in bad.stderr
    missing = subprocess.run([sys.executable, "-m", "geocold", "--quiet", str(tmp_path / "missing.obj")],
                             capture_output=True, text=True)
    assert missing.returncode == 3 and "missing.obj" in missing.stderr


@pytest.mark.parametrize("integrator", ["path", "whitted"])
def test_two_renders_equal_one(gc, cornell, device, integrator):
    a = gc.Renderer(cornell, device=device, integrator=integrator, res=RES, seed=1)
    a.render(spp=3)
    first = a.sums()
    two = a.render(spp=5)
    assert a.sample_count == 8
    b = gc.Renderer(cornell, device=device, integrator=integrator, res=RES, seed=1)
    one = b.render(spp=8)
    assert b.sample_count == 8
    assert np.array_equal(two.view(np.uint32), one.view(np.uint32))
    assert np.array_equal(a.film(), one)
    s = b.sums()
    assert s.sums.shape == (RES[1], RES[0], 4) and s.sample_counts.shape == (RES[1], RES[0])
    assert (s.sample_counts == 8).all() and (first.sample_counts == 3).all()
    assert np.allclose(s.sums[..., :3] / 8, one[..., :3], rtol=1e-6, atol=0)


def test_every_aov(gc, cornell, device):
    for aov in gc.AOVS:
        r = gc.Renderer(cornell, device=device, integrator="aov", aov=aov, res=RES)
        img = r.render()
        assert r.sample_count == 1 and np.isfinite(img).all(), aov
    albedo = gc.Renderer(cornell, device=device, aov="albedo", res=RES).render()
    assert albedo[..., :3].max() <= 1.0 and albedo[..., :3].max() > 0.1


def test_time_limit_and_progress(gc, cornell, device):
    r = gc.Renderer(cornell, device=device, res=RES)
    seen = []
    r.render(spp=6, progress=lambda done, target: seen.append((done, target)))
    assert seen and seen[-1] == (6, 6) and all(t == 6 for _, t in seen)
    r.render(spp=1_000_000, time_limit=0.3)
    assert 6 < r.sample_count < 1_000_006


def test_progress_error_stops_the_render_with_the_film_intact(gc, cornell, device):
    r = gc.Renderer(cornell, device=device, res=RES, samples_per_pass=1)

    def stop(done, target):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        r.render(spp=50, progress=stop)
    assert r.sample_count == 1 and np.isfinite(r.film()).all()


def test_ctrl_c_raises_keyboard_interrupt_at_a_pass_boundary(gc, cornell, device):
    r = gc.Renderer(cornell, device=device, res=RES, samples_per_pass=1)
    r.render(spp=1)  # the program is built: the interrupt lands in the render loop
    timer = threading.Timer(0.2, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            r.render(spp=10_000_000)
    finally:
        timer.cancel()
    done = r.sample_count
    assert 1 < done < 10_000_001
    film = r.film()
    assert np.isfinite(film).all()
    # The film is intact: rendering on gives the bits of one uninterrupted render.
    more = r.render(spp=2)
    again = gc.Renderer(cornell, device=device, res=RES, samples_per_pass=1).render(spp=done + 2)
    assert np.array_equal(more, again)


def test_arrays_outlive_their_renderer_and_scene(gc, device):
    scene = gc.load(CORNELL)
    r = gc.Renderer(scene, device=device, res=RES)
    img = r.render(spp=2)
    sums = r.sums()
    copy = img.copy()
    del r, scene
    pygc.collect()
    filler = [np.full((RES[1], RES[0], 4), 7.0, np.float32) for _ in range(20)]  # reuse freed memory
    assert np.array_equal(img, copy)
    assert (sums.sample_counts == 2).all() and np.isfinite(sums.squares).all()
    assert img.flags.owndata is False and img.base is not None  # the film, not a copy
    del filler


def test_two_renderers_on_two_threads_equal_alone(gc, cornell, device):
    settings = [dict(integrator="path", seed=5), dict(integrator="whitted", seed=0)]
    alone = [gc.Renderer(cornell, device=device, res=RES, **s).render(spp=4) for s in settings]
    results = [None, None]
    errors = []

    def work(i):
        try:
            results[i] = gc.Renderer(cornell, device=device, res=RES, **settings[i]).render(spp=4)
        except Exception as e:  # reported below
            errors.append(e)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    for a, b in zip(alone, results):
        assert np.array_equal(a.view(np.uint32), b.view(np.uint32))


def test_devices(gc):
    devs = gc.devices()
    assert devs and all(d.kind in ("gpu", "cpu", "other") for d in devs)
    assert [d.index for d in devs] == list(range(len(devs)))


def test_write_and_read(gc, cornell, device, tmp_path):
    r = gc.Renderer(cornell, device=device, res=RES)
    img = r.render(spp=2)
    gc.write(tmp_path / "a.pfm", img)
    assert np.array_equal(gc.read(tmp_path / "a.pfm")[..., :3], img[..., :3])
    gc.write(tmp_path / "a.exr", img, metadata=r.metadata())
    gc.write(tmp_path / "b.exr", img, metadata={"spp": 2})
    back = gc.read(tmp_path / "a.exr")
    assert back.shape == img.shape and np.array_equal(back, img)
    gc.write(tmp_path / "a.png", img[..., :3], tonemap="clamp")
    png = gc.read(tmp_path / "a.png")
    assert png.shape == img.shape and np.abs(png[..., :3] - np.clip(img[..., :3], 0, 1)).max() < 0.02


def test_gltf_render_equals_cli_and_shares_the_vocabulary(gc, device, cli, tmp_path):
    gltf = CORNELL.parents[2] / "tests" / "data" / "scenes" / "box-textured" / "BoxTextured-PointLight.gltf"
    out = tmp_path / "cli.pfm"
    subprocess.run([cli, "--quiet", "--device", device, "--res", f"{RES[0]}x{RES[1]}", "--spp", "4",
                    "--env", "0.5,0.5,0.5", str(gltf), "-o", str(out)], check=True)
    scene = gc.load(gltf)
    img = gc.Renderer(scene, device=device, res=RES, env=0.5).render(spp=4)
    assert np.array_equal(img[..., :3].view(np.uint32), read_pfm(out).view(np.uint32))
    # One vocabulary for both formats: glTF's baseColorFactor is base_color, as .mtl's Kd.
    names = {k.rsplit("/", 1)[1] for k in scene.params if k.startswith("materials/")}
    obj_names = {k.rsplit("/", 1)[1] for k in gc.load(CORNELL).params if k.startswith("materials/")}
    assert names == obj_names >= {"base_color", "emission", "roughness", "metallic"}
