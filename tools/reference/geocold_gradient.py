"""geocold's Renderer.backward on the set-up of prb_gradient.py: the gradient of mean(image)
(over pixels and RGB) with respect to a material's base colour, over independent seeds.

    python tools/reference/geocold_gradient.py --config tests/data/refs/cornell-original.json \\
        --material leftWall --res 64x64 --spp 256 --passes 8 --max-depth 6 [--device cpu]
    python tools/reference/geocold_gradient.py --config tests/data/scenes/textured-plane/gradient.json \\
        --material plane --texels --res 64x64 --spp 64 --passes 16 --max-depth 4 --device cpu

Runs in an environment with the geocold package installed (not Mitsuba's); prints one JSON
object with the same fields as prb_gradient.py. With --texels, the gradient with respect to
the texels of a texture, linear, without alpha (flattened (h, w, 3), rows top to bottom, and
"shape"): the scene's only texture, or --texture I (geocold's Python API does not say which
texture a material uses).
"""

import argparse
import json
import os

import numpy as np

import geocold as gc
from compare_gradients import pass_statistics


def texels_name(scene, index) -> str:
    """The parameter name of texture `index`, or of the scene's only differentiable texture."""
    names = [n for n in scene.params.differentiable() if n.startswith("textures/")]
    if index is not None:
        name = f"textures/{index}/texels"
        if name not in names:
            raise SystemExit(f"error: {name} is not differentiable (textures: {', '.join(names) or 'none'})")
        return name
    if len(names) != 1:
        raise SystemExit(f"error: the scene has {len(names)} differentiable textures ({', '.join(names)}); "
                         "give --texture")
    return names[0]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--config", required=True)
    ap.add_argument("--material", required=True)
    ap.add_argument("--res", default=None, help="WxH (default: the config's)")
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--passes", type=int, default=8)
    ap.add_argument("--max-depth", type=int, default=None)
    ap.add_argument("--device", default="any")
    ap.add_argument("--texels", action="store_true", help="differentiate a texture's texels instead of the base colour")
    ap.add_argument("--texture", type=int, default=None,
                    help="with --texels: the texture's index (default: the only one)")
    args = ap.parse_args()

    with open(args.config) as f:
        cfg = json.load(f)
    cam = cfg["camera"]
    width, height = (int(v) for v in args.res.split("x")) if args.res else cam["res"]
    max_depth = args.max_depth if args.max_depth is not None else cfg.get("max_depth", 8)
    scene = gc.load(os.path.join(os.path.dirname(os.path.abspath(args.config)), cfg["scene"]),
                    look_from=cam["look_from"], look_at=cam["look_at"], up=cam.get("up", (0, 1, 0)), fov=cam["fov"])
    r = gc.Renderer(scene, device=args.device, res=(width, height), max_depth=max_depth, seed=0,
                    env=tuple(cfg["env"]) if cfg.get("env") else 0.0)
    name = texels_name(scene, args.texture) if args.texels else f"materials/{args.material}/base_color"
    loss_grad = np.full((height, width, 3), 1.0 / (width * height * 3), np.float32)
    g = np.array([r.backward(loss_grad, [name], spp=args.spp, seed=10_000 + p)[name] for p in range(args.passes)],
                 dtype=np.float64)
    out = {"renderer": f"geocold {gc.__version__} ({r.info['device']})", "parameters": [name]}
    if args.texels:
        # (passes, h, w, 4) -> (passes, h*w*3): alpha's gradient is 0 and Mitsuba's texture has none.
        out["shape"] = [g.shape[1], g.shape[2], 3]
        g = g[..., :3].reshape(len(g), -1)
    out.update({**pass_statistics(g), "res": [width, height], "spp": args.spp, "passes": args.passes,
                "max_depth": max_depth})
    print(json.dumps(out))


if __name__ == "__main__":
    main()
