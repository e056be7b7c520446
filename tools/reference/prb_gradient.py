"""Mitsuba 3's `prb` gradient of an image's mean with respect to one material's diffuse
reflectance: the independent yardstick for geocold-cl's Renderer.backward (docs/differentiable.md).

    .venv/bin/python tools/reference/prb_gradient.py --config tests/data/refs/cornell-original.json \\
        --material leftWall --res 64x64 --spp 64 --passes 8 --max-depth 6

Prints one JSON object: the gradient of mean(image) (over pixels and RGB) with respect to
the material's RGB reflectance, averaged over --passes independent seeds, with its standard
error. Lambert materials only (illum 0-2): the reflectance is a diffuse BSDF's.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile

import numpy as np

from make_reference import _res, load_groups, resolve_settings


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--config", required=True, help="a reference JSON (scene, camera, max_depth)")
    ap.add_argument("--material", required=True)
    ap.add_argument("--res", type=_res, default=None)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--passes", type=int, default=8)
    ap.add_argument("--max-depth", type=int, default=None)
    ap.add_argument("--variant", default="llvm_ad_rgb")
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
        scene = build_scene(groups, cam, max_depth, env, 0, integrator="prb")
    params = mi.traverse(scene)
    # The material's groups (build_scene names their meshes mesh_<i>): one parameter for us,
    # one BSDF each for Mitsuba, so their gradients add.
    keys = [f"mesh_{i:03d}.bsdf.brdf_0.reflectance.value" for i, g in enumerate(groups) if g.material.name == args.material]
    if not keys or any(k not in params.keys() for k in keys):
        raise SystemExit(f"error: material {args.material!r} has no diffuse reflectance (Lambert materials only)")
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
    print(json.dumps({"renderer": f"Mitsuba {mi.__version__} {args.variant} prb", "parameters": keys,
                      "gradient": g.mean(axis=0).tolist(), "std_error": (g.std(axis=0, ddof=1) / np.sqrt(len(g))).tolist(),
                      "res": cam["res"], "spp": args.spp, "passes": args.passes, "max_depth": max_depth}))


if __name__ == "__main__":
    main()
