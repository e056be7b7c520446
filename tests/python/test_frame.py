"""gc.render_frame: one frame on several devices, with the bits of one device and of the CLI."""

import subprocess

import numpy as np

from conftest import CORNELL, RES
from test_render import read_pfm


def bits(img):
    return img[..., :3].view(np.uint32)


def test_one_chunk_is_the_plain_render(gc, cornell, device):
    img, spp = gc.render_frame(cornell, [device], spp=8, res=RES, seed=2)
    assert spp == 8
    plain = gc.Renderer(cornell, device=device, res=RES, seed=2).render(spp=8)
    assert np.array_equal(bits(img), bits(plain))


def test_two_devices_give_the_bits_of_one_and_of_the_cli(gc, cornell, device, cli, tmp_path):
    # The same device twice: two contexts and two threads pulling chunks.
    one, spp = gc.render_frame(cornell, [device], spp=20, chunk_samples=4, res=RES, max_depth=4)
    two, spp2 = gc.render_frame(cornell, [device, device], spp=20, chunk_samples=4, res=RES, max_depth=4)
    assert spp == spp2 == 20
    assert np.array_equal(bits(one), bits(two))
    out = tmp_path / "cli.pfm"
    subprocess.run([cli, "--quiet", "--device", device, "--res", f"{RES[0]}x{RES[1]}", "--spp", "20",
                    "--chunk-samples", "4", "--max-depth", "4", str(CORNELL), "-o", str(out)], check=True)
    assert np.array_equal(bits(one), read_pfm(out).view(np.uint32))


def test_a_sample_range(gc, cornell, device):
    img, spp = gc.render_frame(cornell, [device], samples=(8, 12), chunk_samples=4, res=RES)
    assert spp == 4 and img.shape == (RES[1], RES[0], 4)
    try:
        gc.render_frame(cornell, [device], samples=(2, 12), chunk_samples=4, res=RES)
    except gc.ArgumentError as e:
        assert "multiple of the chunk size" in str(e)
    else:
        raise AssertionError("a range that does not start a chunk was accepted")


def test_adaptive_frame_repeats_its_bits_and_matches_the_cli(gc, device, cli, tmp_path):
    sphere = gc.load(CORNELL.parent / "CornellBox-Sphere.obj")
    args = dict(spp=64, chunk_samples=16, res=RES, noise_threshold=0.2)
    one, spp = gc.render_frame(sphere, [device], **args)
    two, _ = gc.render_frame(sphere, [device, device], **args)
    assert spp == 64
    assert np.array_equal(bits(one), bits(two))
    out = tmp_path / "adaptive.pfm"
    subprocess.run([cli, "--quiet", "--device", device, "--res", f"{RES[0]}x{RES[1]}", "--spp", "64",
                    "--chunk-samples", "16", "--noise-threshold", "0.2", str(CORNELL.parent / "CornellBox-Sphere.obj"),
                    "-o", str(out)], check=True)
    assert np.array_equal(bits(one), read_pfm(out).view(np.uint32))
    # Not the uniform frame: some tiles stopped early.
    uniform, _ = gc.render_frame(sphere, [device], spp=64, chunk_samples=16, res=RES)
    assert not np.array_equal(bits(one), bits(uniform))
    for bad, kwargs in ((-0.1, {}), (0.1, {"integrator": "whitted"}), (0.1, {"samples": (16, 64)})):
        try:
            gc.render_frame(sphere, [device], chunk_samples=16, res=RES, noise_threshold=bad, **kwargs)
        except gc.ArgumentError as e:
            assert "noise_threshold" in str(e)
        else:
            raise AssertionError(f"noise_threshold={bad} with {kwargs} was accepted")
