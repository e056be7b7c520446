"""Renderer.backward and the differentiable parameters: finite differences, determinism, texels, errors."""

import numpy as np
import pytest

from conftest import CORNELL, ROOT

WALL = "materials/leftWall/base_color"
BOX = ROOT / "tests" / "data" / "scenes" / "box-textured" / "BoxTextured-PointLight.gltf"


def linear_loss_grad(shape, rng):
    """d loss / d image of loss = sum(weights * image): positive random weights."""
    return rng.uniform(0.5, 1.5, size=shape).astype(np.float32) / np.prod(shape)


def test_base_colour_gradient_equals_central_differences(gc, device):
    # Same seed for the images and the gradient: the difference quotient sees the same paths,
    # so the two agree far below the Monte Carlo noise (the C++ tests use the same set-up).
    res, spp, seed, eps = (32, 32), 16, 5, 1e-3
    scene = gc.load(CORNELL)
    r = gc.Renderer(scene, device=device, res=res, max_depth=4, seed=seed)
    weights = linear_loss_grad((res[1], res[0], 3), np.random.default_rng(0))
    base = np.array(scene.params[WALL], dtype=np.float64)
    grad = r.backward(weights, [WALL], spp=spp, seed=seed)[WALL]
    assert grad.shape == (3,) and grad.dtype == np.float32
    fd = np.zeros(3)
    for c in range(3):
        losses = []
        for sign in (1, -1):
            v = base.copy()
            v[c] += sign * eps
            scene.params[WALL] = tuple(v)
            losses.append(np.sum(weights.astype(np.float64) * r.render(spp=spp)[..., :3]))
            r.clear()
        fd[c] = (losses[0] - losses[1]) / (2 * eps)
    scene.params[WALL] = tuple(base)
    rel = np.abs(grad - fd) / np.abs(fd)
    print(f"\n  {WALL}: backward {grad}, central differences {fd}, relative error {rel.max():.2e} (limit 5e-4)")
    assert np.all(fd > 0) and rel.max() <= 5e-4


def test_backward_is_the_same_bits_every_time(gc, cornell, device):
    r = gc.Renderer(cornell, device=device, res=(24, 20), max_depth=5, seed=0)
    img = r.render(spp=2)
    loss_grad = 2 * (img[..., :3] - 0.5) / img[..., :3].size
    names = [WALL, "materials/light/emission"]
    a = r.backward(loss_grad, names, spp=2, seed=1)
    b = r.backward(loss_grad, names, spp=2, seed=1)
    c = r.backward(loss_grad, names, spp=2, seed=2)
    for n in names:
        assert np.array_equal(a[n].view(np.uint32), b[n].view(np.uint32)), n
    assert not np.array_equal(a[WALL], c[WALL])  # the seed picks the paths


def test_differentiable_lists_names_with_shapes(gc, cornell):
    d = cornell.params.differentiable()
    assert d[WALL] == (3,) and d["materials/light/emission"] == (3,) and d["environment/radiance"] == (3,)
    assert not any(k.startswith("camera/") or k.endswith("/ior") for k in d)


def test_texels_round_trip_and_gradient_shape(gc, device):
    scene = gc.load(BOX)
    keys = [k for k in scene.params.differentiable() if k.startswith("textures/")]
    assert keys, "BoxTextured has a base-colour texture"
    key = keys[0]
    texels = scene.params[key]
    h, w, _ = texels.shape
    assert scene.params.differentiable()[key] == (h, w, 4)
    r = gc.Renderer(scene, device=device, res=(24, 24), max_depth=3, seed=0)
    before = r.render(spp=2)
    scene.params[key] = texels  # now stored as linear floats: the same image, bit for bit
    assert r.sample_count == 0
    after = r.render(spp=2)
    assert np.array_equal(before, after)
    grad = r.backward(np.ones((24, 24, 3), np.float32), [key], spp=2, seed=1)[key]
    assert grad.shape == (h, w, 4) and np.count_nonzero(grad[..., :3]) > 0 and not np.any(grad[..., 3])
    scene.params[key] = np.zeros_like(texels)
    assert not np.array_equal(r.render(spp=2), before)
    with pytest.raises(gc.ArgumentError, match="texels"):
        scene.params[key] = np.zeros((h + 1, w, 4), np.float32)


def test_what_cannot_be_differentiated_says_why(gc, cornell, device):
    r = gc.Renderer(cornell, device=device, res=(8, 8), seed=0)
    g = np.ones((8, 8, 3), np.float32)
    for name in ("camera/fov", "materials/leftWall/ior", "materials/nosuch/base_color"):
        with pytest.raises(gc.ArgumentError) as e:
            r.backward(g, [name], spp=1, seed=1)
        print(f"\n  {name}: {e.value}")
    with pytest.raises(gc.ArgumentError, match="loss_grad"):
        r.backward(np.ones((4, 4, 3), np.float32), [WALL], spp=1, seed=1)
    whitted = gc.Renderer(cornell, device=device, integrator="whitted", res=(8, 8))
    with pytest.raises(gc.ArgumentError):
        whitted.backward(g, [WALL], spp=1, seed=1)
