"""Mitsuba 3's `prb` as the yardstick of geocold-grad-bench in the same run: one optimisation
iteration (render with the parameters, then the backward pass of the loss mean(image)) of the
Cornell box at each size, the first iteration (which compiles Dr.Jit's kernels) apart from
the median of --repeats after it, and the ratio ours / Mitsuba of the medians (issue 43
item 5 asks for <= 0.5 on an H200).

    /work/refvenv/bin/python tools/bench/mitsuba_prb_yardstick.py \\
        --grad-bench build/release/geocold-grad-bench --device cpu --variant llvm_ad_rgb
    python3 tools/bench/mitsuba_prb_yardstick.py --grad-bench build/bare/geocold-grad-bench \\
        --device gpu --variant cuda_ad_rgb          # the H200 (tools/device/gradients.sh)

The view (scene file, camera, environment, depth, no Russian roulette, the parameters) is
geocold-grad-bench --view's, and the Mitsuba scene the reference tools' OBJ conversion
(tools/reference/mitsuba_scene.py), as tools/bench/mitsuba_yardstick.py does. The two
iterations do the same work: spp samples for the image and spp for the gradient, the image's
mean as the loss, the gradient of every parameter evaluated (Dr.Jit: up to dr.sync_thread()).
Ours also reads its image back to the host to compute the loss. Dr.Jit caches compiled
kernels on disk, so a second run's first iteration is shorter than a cold one.

Exit status: 0 done, 2 bad usage, a failed child or no Mitsuba.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "reference"))


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--grad-bench", required=True, help="the geocold-grad-bench executable")
    p.add_argument("--device", default="cpu", help="geocold-grad-bench --device (cpu: PoCL, gpu)")
    p.add_argument("--variant", default="llvm_ad_rgb", choices=["llvm_ad_rgb", "cuda_ad_rgb"])
    p.add_argument("--sizes", default="128:4,512:16", help="SIDE:SPP per size (spp for render and backward each)")
    p.add_argument("--depth", type=int, default=6)
    p.add_argument("--repeats", type=int, default=5, help="timed iterations per size after the first")
    p.add_argument("--params", default="leftWall", choices=["leftWall", "walls"])
    p.add_argument("--threads", type=int, default=0, help="CPU threads for both (0: every core)")
    p.add_argument("--no-ours", action="store_true", help="time Mitsuba alone")
    p.add_argument("--json", help="also write the figures here")
    args = p.parse_args(argv)
    try:
        args.size_list = [tuple(int(x) for x in s.split(":")) for s in args.sizes.split(",") if s]
    except ValueError:
        p.error(f"--sizes {args.sizes!r}: not SIDE:SPP[,SIDE:SPP]")
    if not args.size_list or any(len(s) != 2 or min(s) < 1 for s in args.size_list):
        p.error(f"--sizes {args.sizes!r}: not SIDE:SPP[,SIDE:SPP]")
    if args.repeats < 1 or args.depth < 1 or args.threads < 0:
        p.error("--repeats and --depth must be >= 1, --threads >= 0")
    if not os.access(args.grad_bench, os.X_OK):
        p.error(f"--grad-bench {args.grad_bench}: not an executable")
    return args


def fail(message: str, status: int = 2):
    print(f"mitsuba_prb_yardstick: {message}", file=sys.stderr)
    raise SystemExit(status)


def grad_bench(args, *extra) -> str:
    command = [args.grad_bench, "--depth", str(args.depth), "--params", args.params, *extra]
    if args.threads:
        command += ["--threads", str(args.threads)]
    run = subprocess.run(command, capture_output=True, text=True)
    if run.returncode != 0:
        fail(f"{' '.join(command)} exited {run.returncode}:\n{run.stderr}")
    return run.stdout


def ours(args):
    """geocold-grad-bench's figures: (device name, [per-size dict])."""
    out = grad_bench(args, "--device", args.device, "--sizes", args.sizes, "--repeats", str(args.repeats),
                     "--no-memory")
    lines = out.strip().splitlines()
    for line in lines[:-1]:
        print("  ours " + line.strip())
    doc = json.loads(lines[-1])
    name, figures = next(iter(doc["devices"].items()))
    return name, figures["sizes"]


def mitsuba_setup(view, side: int):
    import mitsuba as mi
    from make_reference import load_groups
    from mitsuba_scene import build_scene

    camera = {"look_from": view["look_from"], "look_at": view["look_at"], "up": view["up"], "fov": view["fov"],
              "res": [side, side]}
    with tempfile.TemporaryDirectory() as tmp:
        groups = load_groups(view["source"], tmp)
        scene = build_scene(groups, camera, view["depth"], view["env"], 0, integrator="prb")
    integrator = mi.load_dict({"type": "prb", "max_depth": int(view["depth"]), "rr_depth": int(view["rr_depth"])})
    params = mi.traverse(scene)
    # The named materials' diffuse reflectances (build_scene names the meshes mesh_<i>; one
    # of our materials may be several Mitsuba BSDFs).
    names = {p.split("/")[1] for p in view["params"]}
    keys = [f"mesh_{i:03d}.bsdf.brdf_0.reflectance.value" for i, g in enumerate(groups) if g.material.name in names]
    missing = [k for k in keys if k not in params.keys()]
    if not keys or missing:
        fail(f"no diffuse reflectance in Mitsuba's scene for {sorted(names)} ({missing or 'no mesh'})")
    params.keep(keys)
    first = view["params"][0].split("/")[1]
    # The first parameter's BSDFs first, so that its gradient is the sum over keys[:first_keys].
    keys.sort(key=lambda k: groups[int(k[5:8])].material.name != first)
    first_keys = sum(groups[int(k[5:8])].material.name == first for k in keys)
    return scene, integrator, params, keys, first_keys


def mitsuba_iteration(scene, integrator, params, keys, first_keys: int, spp: int, seed: int):
    """(seconds of one render + backward, to the end of the device's work; the gradient of the
    first parameter, summed over its Mitsuba BSDFs, as a list of RGB)."""
    import drjit as dr
    import mitsuba as mi

    start = time.perf_counter()
    for k in keys:
        dr.enable_grad(params[k])
    params.update()
    image = mi.render(scene, params, integrator=integrator, spp=spp, seed=seed, seed_grad=100_000 + seed)
    loss = dr.mean(image, axis=None)
    dr.backward(loss)
    grads = [dr.grad(params[k]) for k in keys]
    dr.eval(*grads)
    dr.sync_thread()
    seconds = time.perf_counter() - start
    first = [sum(float(dr.grad(params[k])[c][0]) for k in keys[:first_keys]) for c in range(3)]
    for k in keys:
        dr.set_grad(params[k], 0)
    return seconds, first


def main(argv=None) -> int:
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        import drjit as dr
        import mitsuba as mi
    except ImportError as e:
        fail(f"Mitsuba 3 is not importable ({e}); pip install -r tools/reference/requirements.txt")
    try:
        mi.set_variant(args.variant)
    except Exception as e:  # Dr.Jit raises its own types when LLVM or CUDA is missing
        fail(f"Mitsuba's {args.variant} does not start here ({e})")
    if args.threads:
        dr.set_thread_count(args.threads)
    view = json.loads(grad_bench(args, "--view").strip().splitlines()[-1])
    threads = "every core" if args.threads == 0 else f"{args.threads} thread(s)"
    print(f"Mitsuba {mi.__version__} {args.variant} prb against geocold-grad-bench --device {args.device}, {threads}; "
          f"Cornell box depth {args.depth}, no Russian roulette, {len(view['params'])} parameter(s) ({args.params})")
    device, our_sizes = (None, []) if args.no_ours else ours(args)
    results = []
    for i, (side, spp) in enumerate(args.size_list):
        scene, integrator, params, keys, first_keys = mitsuba_setup(view, side)
        first, _ = mitsuba_iteration(scene, integrator, params, keys, first_keys, spp, 0)
        runs = [mitsuba_iteration(scene, integrator, params, keys, first_keys, spp, 1 + r) for r in range(args.repeats)]
        times = [t for t, _ in runs]
        grad = runs[-1][1]
        theirs = statistics.median(times)
        row = {"side": side, "spp": spp, "mitsuba_first_s": first, "mitsuba_median_s": theirs, "mitsuba_s": times,
               "mitsuba_gradient_first": [view["params"][0], grad]}
        line = (f"  {side}x{side} spp {spp}+{spp}: Mitsuba first iteration {first:.3f} s, iteration {theirs:.4f} s "
                f"(median of {len(times)}, {min(times):.4f}-{max(times):.4f}), d/d {view['params'][0]} = "
                f"({grad[0]:.4g}, {grad[1]:.4g}, {grad[2]:.4g})")
        if our_sizes:
            mine = our_sizes[i]["iteration_median_s"]
            row.update({"ours_median_s": mine, "ours_programs_s": our_sizes[i]["programs_s"],
                        "ours_first_s": our_sizes[i]["first_iteration_s"], "ratio": mine / theirs})
            line += f"; ours {mine:.4f} s = {mine / theirs:.3f}x Mitsuba's"
        print(line, flush=True)
        results.append(row)
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"variant": args.variant, "mitsuba": mi.__version__, "device": device, "threads": args.threads,
                       "depth": args.depth, "params": view["params"], "sizes": results}, f, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
