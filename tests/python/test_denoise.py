"""gc.denoise through pyoidn: a denoised low-spp render is closer to a high-spp reference than
the noisy one; without pyoidn it is a DeviceError that says how to install it."""

import sys

import numpy as np
import pytest

from conftest import RES


def rel_mse(test, ref):
    t, r = test[..., :3].astype(np.float64), ref[..., :3].astype(np.float64)
    return float(np.mean((t - r) ** 2 / (r * r + 1e-2)))


def test_denoised_is_closer_to_the_reference(gc, cornell, device):
    pytest.importorskip("pyoidn")
    render = lambda spp, **kw: gc.Renderer(cornell, device=device, res=RES, max_depth=6, **kw).render(spp=spp)
    ref = render(1024)
    noisy = render(8)
    albedo = render(64, aov="albedo")
    normal = render(1, aov="normal")
    denoised = gc.denoise(noisy, albedo, normal, clean_aux=True)
    assert denoised.shape == noisy.shape and denoised.dtype == np.float32
    assert np.array_equal(denoised[..., 3], noisy[..., 3])
    e_noisy, e_denoised = rel_mse(noisy, ref), rel_mse(denoised, ref)
    print(f"\ngc.denoise, {RES[0]}x{RES[1]}: rel MSE 8 spp {e_noisy:.5f}, denoised {e_denoised:.5f}")
    assert e_denoised < e_noisy
    assert gc.denoise(noisy[..., :3]).shape == noisy[..., :3].shape  # colour alone, RGB in and out


def test_bad_guides_are_argument_errors(gc):
    pytest.importorskip("pyoidn")
    img = np.zeros((4, 4, 4), np.float32)
    with pytest.raises(gc.ArgumentError):
        gc.denoise(img, np.zeros((2, 2, 3), np.float32))
    with pytest.raises(gc.ArgumentError):
        gc.denoise(img, None, img)


def test_without_pyoidn_it_says_how_to_install_it(gc, monkeypatch):
    monkeypatch.setitem(sys.modules, "pyoidn", None)  # makes `import pyoidn` raise ImportError
    with pytest.raises(gc.DeviceError, match="pip install pyoidn"):
        gc.denoise(np.zeros((4, 4, 3), np.float32))


def test_guide_aovs_equal_the_plain_ones_without_mirrors_or_glass(gc, cornell, device):
    # The Original Cornell box has no delta surfaces: the guide is the jittered albedo, plus
    # the lamp's emission (clamped to 1) where the lamp is.
    render = lambda aov: gc.Renderer(cornell, device=device, res=RES, aov=aov).render(spp=4)
    guide, albedo = render("guide-albedo"), render("albedo")
    differs = np.any(guide != albedo, axis=2)
    assert 0 < differs.mean() < 0.05  # the lamp
    assert np.all(guide[differs][:, :3] >= albedo[differs][:, :3])
    assert render("guide-normal").shape == (RES[1], RES[0], 4)
    assert "guide-albedo" in gc.AOVS and "guide-normal" in gc.AOVS
