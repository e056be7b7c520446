#!/usr/bin/env python3
"""Renders an independent Mitsuba 3 reference of a scene for geocold-cl's image tests.

    make_reference.py SCENE.obj|.gltf|.glb --config view.json -o out/NAME.exr
    make_reference.py SCENE.obj --look-from 0,1,3.9 --look-at 0,1,0 --fov 39.3077 --res 128x128 \
        --spp 16384 --max-depth 8 [--env 1,1,1] -o NAME.exr

--config takes a JSON like /work/shared/refs/*.json (its camera, spp, max_depth and env; its
"scene", resolved against the JSON's directory, when no SCENE is given); command-line values
override it. Writes NAME.exr (float RGB, zip), NAME-variance.exr (the per-sample variance, half
float) and NAME.json beside it with the same fields as the shared references plus the
variance file, the exact command and the render time. See README.md.
"""

from __future__ import annotations

import argparse
import math
import json
import os
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)


def _triple(text: str):
    values = [float(x) for x in text.split(",")]
    if len(values) != 3:
        raise argparse.ArgumentTypeError(f"expected x,y,z, got '{text}'")
    return values


def _res(text: str):
    try:
        w, h = (int(x) for x in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected WIDTHxHEIGHT, got '{text}'") from None
    return [w, h]


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scene", nargs="?", help=".obj, .gltf or .glb (default: the config's scene)")
    p.add_argument("--config", help="JSON with camera/spp/max_depth/env, like the shared refs'")
    p.add_argument("--look-from", type=_triple)
    p.add_argument("--look-at", type=_triple)
    p.add_argument("--up", type=_triple)
    p.add_argument("--fov", type=float, help="full vertical field of view, degrees")
    p.add_argument("--aperture", type=float, help="thin lens: aperture radius (Mitsuba's thinlens)")
    p.add_argument("--focus-distance", type=float, help="thin lens: distance of the plane in focus")
    p.add_argument("--res", type=_res, help="WIDTHxHEIGHT")
    p.add_argument("--spp", type=int)
    p.add_argument("--max-depth", type=int)
    p.add_argument("--env", type=_triple, help="constant environment radiance r,g,b (default: black)")
    p.add_argument("--pbr", action="store_true",
                   help="glTF materials as Mitsuba's principled BSDF (metallic, roughness, normal map) "
                        "instead of Lambert base colour; see README.md")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--pass-spp", type=int, default=256, help="samples per pixel per Mitsuba render call")
    p.add_argument("--variant", default="scalar_rgb",
                   help="Mitsuba variant (scalar_rgb works everywhere; llvm_ad_rgb needs LLVM >= 16)")
    p.add_argument("--threads", type=int, default=0, help="Mitsuba worker threads (0 = all cores)")
    p.add_argument("-o", "--output", required=True, help="output .exr (the .json goes beside it)")
    return p.parse_args(argv)


def resolve_settings(args):
    cfg = {}
    if args.config:
        with open(args.config) as f:
            cfg = json.load(f)
    cam = dict(cfg.get("camera", {}))
    for key, value in (("look_from", args.look_from), ("look_at", args.look_at), ("up", args.up),
                       ("fov", args.fov), ("res", args.res), ("aperture_radius", args.aperture),
                       ("focus_distance", args.focus_distance)):
        if value is not None:
            cam[key] = value
    cam.setdefault("up", [0.0, 1.0, 0.0])
    if cam.get("aperture_radius", 0) > 0 and "focus_distance" not in cam and "look_at" in cam:
        # geocold-cl's default: in focus at the look-at point (the view axis runs through it).
        cam["focus_distance"] = math.dist(cam["look_from"], cam["look_at"])
    missing = [k for k in ("look_from", "look_at", "fov", "res") if k not in cam]
    if missing:
        raise SystemExit(f"error: camera incomplete, missing {', '.join(missing)} (give --config or the flags)")
    scene = args.scene
    if scene is None:
        if "scene" not in cfg:
            raise SystemExit("error: no scene given and the config names none")
        scene = os.path.join(os.path.dirname(os.path.abspath(args.config)), cfg["scene"])
    spp = args.spp if args.spp is not None else cfg.get("spp")
    max_depth = args.max_depth if args.max_depth is not None else cfg.get("max_depth", 8)
    env = args.env if args.env is not None else cfg.get("env")
    if spp is None or spp <= 0:
        raise SystemExit("error: --spp must be given and positive")
    if spp % args.pass_spp != 0 or spp // args.pass_spp < 2:
        raise SystemExit(f"error: --spp {spp} must be a multiple (>= 2x) of --pass-spp {args.pass_spp}")
    return os.path.abspath(scene), cam, int(spp), int(max_depth), env


def load_groups(scene_path: str, tmp_dir: str, pbr: bool = False):
    from gltf_to_obj import convert
    from obj_scene import read_obj

    ext = os.path.splitext(scene_path)[1].lower()
    if ext in (".gltf", ".glb"):
        scene_path = convert(scene_path, tmp_dir, pbr)
    elif ext != ".obj":
        raise SystemExit(f"error: {scene_path}: unsupported scene type (want .obj, .gltf or .glb)")
    return read_obj(scene_path)


def write_exr(path: str, image: np.ndarray, half: bool = False):
    import mitsuba as mi

    # Mitsuba writes float32 EXR with lossless PIZ; OpenImageIO's oiiotool, where installed,
    # rewrites it with lossless zip (smaller for these images), pixel for pixel the same.
    bitmap = mi.Bitmap(image.astype(np.float32), mi.Bitmap.PixelFormat.RGB)
    tmp = path + ".tmp.exr"
    bitmap.write(tmp)
    oiiotool = shutil.which("oiiotool")
    if oiiotool:
        zipped = path + ".zip.exr"
        subprocess.run([oiiotool, tmp, "-d", "half" if half else "float", "--compression", "zip", "-o", zipped],
                       check=True)
        os.replace(zipped, tmp)
    os.replace(tmp, path)


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    scene_path, cam, spp, max_depth, env = resolve_settings(args)

    import mitsuba as mi

    mi.set_variant(args.variant)
    if args.threads > 0:
        import drjit as dr

        dr.set_thread_count(args.threads)
    from mitsuba_scene import build_scene, integrator_for

    with tempfile.TemporaryDirectory() as tmp:
        groups = load_groups(scene_path, tmp, args.pbr)
        scene = build_scene(groups, cam, max_depth, env, args.seed)
        integrator = integrator_for(groups)
        width, height = cam["res"]
        total = np.zeros((height, width, 3), dtype=np.float64)
        total_sq = np.zeros_like(total)
        done, passes, attempts, replaced = 0, 0, 0, 0
        start = time.time()
        while done < spp:
            # A fresh seed per pass: independent samples; equal passes, so the mean of the pass
            # means is the spp-sample mean. A pass with a non-finite pixel (Mitsuba's rough
            # dielectrics now and then give a NaN sample) is rendered again with the next seed,
            # and the JSON counts those.
            n = args.pass_spp
            image = np.array(mi.render(scene, spp=n, seed=args.seed * 1_000_003 + attempts), dtype=np.float64)
            attempts += 1
            if not np.isfinite(image[:, :, :3]).all():
                replaced += 1
                continue
            total += image[:, :, :3]
            total_sq += image[:, :, :3] ** 2
            done += n
            passes += 1
            elapsed = time.time() - start
            print(f"\r{done}/{spp} spp, {elapsed:.0f} s", end="", file=sys.stderr, flush=True)
        seconds = time.time() - start
        print(file=sys.stderr)
    mean = total / passes
    # Per-sample variance from the scatter of the pass means: Var(pass mean) = sigma^2 / n, so
    # sigma^2 ~ n * sum((m_i - mean)^2) / (P - 1). The Z-tests need the reference's own noise
    # where Mitsuba's estimator is noisier than the renderer under test.
    variance = args.pass_spp * np.maximum(total_sq - passes * mean**2, 0.0) / max(passes - 1, 1)

    out = os.path.abspath(args.output)
    os.makedirs(os.path.dirname(out), exist_ok=True)
    write_exr(out, mean)
    variance_path = os.path.splitext(out)[0] + "-variance.exr"
    write_exr(variance_path, variance, half=True)
    meta = {
        "image": os.path.basename(out),
        "scene": os.path.relpath(scene_path, os.path.dirname(out)),
        "camera": {k: cam[k] for k in ("look_from", "look_at", "up", "fov", "res", "aperture_radius",
                                        "focus_distance") if k in cam},
        "spp": spp,
        "max_depth": max_depth,
        "env": env,
        "renderer": f"Mitsuba {mi.__version__}, {args.variant} variant, "
                    f"{integrator} integrator (NEE + MIS), "
                    "box filter, independent sampler" + (", glTF materials as principled" if args.pbr else ""),
        "variance": os.path.basename(variance_path),
        "variance_estimator": f"per-sample variance from {passes} passes of {args.pass_spp} spp",
        **({"nonfinite_passes_replaced": replaced} if replaced else {}),
        "seed": args.seed,
        "seconds": round(seconds, 1),
        "command": "tools/reference/make_reference.py " + " ".join(shlex.quote(a) for a in
                                                                   (sys.argv[1:] if argv is None else argv)),
    }
    with open(os.path.splitext(out)[0] + ".json", "w") as f:
        json.dump(meta, f, indent=1)
        f.write("\n")
    print(f"wrote {out} ({spp} spp, {seconds:.1f} s, mean {mean.mean():.6f})")


if __name__ == "__main__":
    main()
