"""Interactive-style editing: the first render pays for loading, the BVH, the upload and the
kernels; a re-render after a material edit pays for none of them (no reload, no BVH build,
no program build). Prints both, and the ratio.

    python examples/edit_rerender.py [scene.obj] [--device any] [--res 256] [--cold]

--cold compiles the kernels as a first run on a fresh machine does (no kernel cache, ours or
PoCL's); without it a warm cache makes the set-up of a small scene a few tens of ms.
"""

import argparse
import os
import pathlib
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent
DEFAULT_SCENE = HERE.parent / "scenes" / "cornell-box" / "CornellBox-Original.obj"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", nargs="?", default=str(DEFAULT_SCENE))
    ap.add_argument("--device", default="any")
    ap.add_argument("--res", type=int, default=256)
    ap.add_argument("--material", default=None, help="the material to edit (default: the first)")
    ap.add_argument("--max-ratio", type=float, default=None, help="exit 1 when the ratio is above this")
    ap.add_argument("--cold", action="store_true", help="no kernel cache: the set-up of a first run")
    args = ap.parse_args()
    if args.cold:
        # Before geocold loads OpenCL: PoCL reads its variables once.
        os.environ["GEOCOLD_NO_CACHE"] = "1"
        os.environ["POCL_KERNEL_CACHE"] = "0"
    import geocold as gc

    t0 = time.perf_counter()
    scene = gc.load(args.scene)
    r = gc.Renderer(scene, device=args.device, res=(args.res, args.res))
    setup = time.perf_counter() - t0
    r.render(spp=1)
    first = time.perf_counter() - t0
    info = r.info
    print(f"first render: {first:.3f} s, of which set-up {setup:.3f} s (load {info['load_seconds']:.3f}, "
          f"BVH {info['bvh_seconds']:.3f}, upload {info['upload_seconds']:.3f}, kernels "
          f"{info['compile_seconds']:.3f}{' from the cache' if info['program_from_cache'] else ''})")

    name = args.material or next(iter(scene.materials))
    m = scene.materials[name]
    times = []
    for colour in ((0.8, 0.1, 0.1), (0.1, 0.8, 0.1), (0.1, 0.1, 0.8)):
        t0 = time.perf_counter()
        m.base_color = colour
        r.render(spp=1)
        times.append(time.perf_counter() - t0)
    rerender = min(times)
    plain = []
    for _ in range(3):
        t0 = time.perf_counter()
        r.render(spp=1)
        plain.append(time.perf_counter() - t0)
    ratio = rerender / setup
    print(f"re-render after editing materials/{name}/base_color: {rerender * 1000:.1f} ms "
          f"= {100 * ratio:.1f} % of the set-up (a 1-spp pass without an edit: {min(plain) * 1000:.1f} ms); "
          f"programs rebuilt: {r.info['program_builds']}")
    sys.stdout.flush()
    if args.max_ratio is not None and ratio > args.max_ratio:
        raise SystemExit(f"the re-render took {100 * ratio:.1f} % of the set-up (limit {100 * args.max_ratio:.0f} %)")


if __name__ == "__main__":
    main()
