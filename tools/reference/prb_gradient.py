"""Mitsuba 3's `prb` gradient of an image's mean with respect to one material's diffuse
reflectance: the independent yardstick for geocold-cl's Renderer.backward (docs/differentiable.md).

    .venv/bin/python tools/reference/prb_gradient.py --config tests/data/refs/cornell-original.json \\
        --material leftWall --res 64x64 --spp 64 --passes 8 --max-depth 6
    .venv/bin/python tools/reference/prb_gradient.py --config tests/data/scenes/textured-plane/gradient.json \\
        --material plane --texels --res 64x64 --spp 64 --passes 16 --max-depth 4

Prints one JSON object: the gradient of mean(image) (over pixels and RGB) with respect to
the material's RGB reflectance, averaged over --passes independent seeds, with its standard
error. Lambert materials only (illum 0-2): the reflectance is a diffuse BSDF's.

With --texels, the gradient with respect to the linear texels of the material's map_Kd (Kd
must be 1, so that the texture is the reflectance): "gradient" and "std_error" are then
flattened (h, w, 3) arrays, rows top to bottom as in the image file, and "shape" is [h, w, 3].
compare_gradients.py compares two such files.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile

import numpy as np

from compare_gradients import pass_statistics
from make_reference import _res, load_groups, resolve_settings


def parameter_keys(params, groups, material: str, texels: bool) -> list:
    """The Mitsuba parameters of the material's reflectance (or its texels), one per group:
    build_scene names the meshes mesh_<i> and gives each its own BSDF, so their gradients add."""
    leaf = "data" if texels else "value"
    mine = [(i, g) for i, g in enumerate(groups) if g.material.name == material]
    keys = [f"mesh_{i:03d}.bsdf.brdf_0.reflectance.{leaf}" for i, _ in mine]
    # With Kd != 1 the bitmap holds Kd times the texture (mitsuba_scene.py bakes it), not the texels.
    baked = texels and any(not np.allclose(g.material.kd, 1.0) for _, g in mine)
    if not keys or baked or any(k not in params.keys() for k in keys):
        what = "diffuse texture with Kd 1" if texels else "constant diffuse reflectance"
        raise SystemExit(f"error: material {material!r} has no {what} (Lambert materials only)")
    return keys


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--config", required=True, help="a reference JSON (scene, camera, max_depth)")
    ap.add_argument("--material", required=True)
    ap.add_argument("--res", type=_res, default=None)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--passes", type=int, default=8)
    ap.add_argument("--max-depth", type=int, default=None)
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--texels", action="store_true", help="differentiate the material's map_Kd texels instead")
    args = ap.parse_args(argv)

    import drjit as dr
    import mitsuba as mi

    mi.set_variant(args.variant)
    from mitsuba_scene import build_scene

    settings = argparse.Namespace(scene=None, config=args.config, look_from=None, look_at=None, up=None, fov=None,
                                  res=args.res, spp=args.spp * 2, max_depth=args.max_depth, env=None, pass_spp=args.spp,
                                  aperture=None, focus_distance=None)
    scene_path, cam, _, max_depth, env = resolve_settings(settings)
    with tempfile.TemporaryDirectory() as tmp:
        groups = load_groups(scene_path, tmp)
        scene = build_scene(groups, cam, max_depth, env, 0, integrator="prb", float_textures=args.texels)
    params = mi.traverse(scene)
    keys = parameter_keys(params, groups, args.material, args.texels)
    shape = list(params[keys[0]].shape) if args.texels else None
    grads = []
    for p in range(args.passes):
        for k in keys:
            dr.enable_grad(params[k])
        params.update()
        image = mi.render(scene, params, spp=args.spp, seed=p, seed_grad=10_000 + p)
        dr.backward(dr.mean(image))
        grads.append(sum(np.array(dr.grad(params[k]), dtype=np.float64).ravel() for k in keys))
        for k in keys:
            dr.set_grad(params[k], 0)
        print(f"\rpass {p + 1}/{args.passes}", end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)
    g = np.array(grads)
    out = {"renderer": f"Mitsuba {mi.__version__} {args.variant} prb", "parameters": keys, **pass_statistics(g),
           "res": cam["res"], "spp": args.spp, "passes": args.passes, "max_depth": max_depth}
    if shape is not None:
        out["shape"] = shape
    print(json.dumps(out))


if __name__ == "__main__":
    main()
