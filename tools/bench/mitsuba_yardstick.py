"""Mitsuba 3 as a yardstick in the same run: geocold-bench's path-traced samples per second
against Mitsuba 3's on the same view, the same machine and the same threads, in interleaved
rounds (ours, then Mitsuba's), reported as the median of the per-round ratios.

Why: issue 6 states its Mitsuba anchors as fixed figures measured elsewhere (0.96 M samples/s
per thread for llvm_ad_rgb on the Cornell box, 221 M for cuda_ad_rgb on an H200). A shared
machine's speed moves by 2x from one hour to the next, so a ratio to a fixed figure says more
about the machine's load than about the renderer. Embree already runs in the same process as
our rays; this does the same for the path figures.

    python3 -m venv .venv && .venv/bin/pip install -r tools/reference/requirements.txt
    apt-get install libllvm19          # Dr.Jit's LLVM back end needs LLVM >= 17
    .venv/bin/python tools/bench/mitsuba_yardstick.py --bench build/release/geocold-bench \\
        --threads 1 --scene cornell,dragon --rounds 5
    .venv/bin/python tools/bench/mitsuba_yardstick.py --bench ... --device gpu   # cuda_ad_rgb

The view (scene file, camera, resolution, environment, max depth 8 and no Russian roulette)
comes from geocold-bench's own --json output, and the Mitsuba scene from the reference tools'
OBJ conversion (tools/reference), so both renderers see the same scene by construction. A
check that they do: geocold-cl renders the view too, and the two images' mean luminance must
agree within --same-picture percent, or the comparison is refused (exit 1).

Timing: Mitsuba renders with a fixed sample count chosen so that one render takes about
--seconds (after a render that compiles its kernels, which Dr.Jit then caches), and the time
covers mi.render up to dr.sync_thread(). Ours is geocold-bench's own figure: the median time
of its timed samples, kernels compiled beforehand.

Exit status: 0 done, 1 the pictures differ, 2 bad usage or a failed child.
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
from colour import REC709_LUMINANCE  # noqa: E402  (tools/reference, Mitsuba-free)


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--bench", required=True, help="the geocold-bench executable")
    p.add_argument("--geocold", help="the geocold-cl executable (default: beside --bench)")
    p.add_argument("--scene", default="cornell,dragon", help="geocold-bench scene names (with a file)")
    p.add_argument("--device", choices=["cpu", "gpu"], default="cpu",
                   help="cpu: PoCL against llvm_ad_rgb; gpu: the GPU against cuda_ad_rgb")
    p.add_argument("--threads", type=int, default=0, help="CPU threads for both (0: every core)")
    p.add_argument("--rounds", type=int, default=5, help="interleaved rounds per scene")
    p.add_argument("--seconds", type=float, default=1.0, help="target length of one Mitsuba render")
    p.add_argument("--same-picture", type=float, default=2.0,
                   help="largest difference of the mean luminance, percent")
    p.add_argument("--mitsuba-lanes", choices=["native", "8"], default="native",
                   help="llvm only: Dr.Jit's SIMD width; 8 pins it to AVX2 code where the CPU has AVX-512 "
                        "(Dr.Jit then runs 16 paths per instruction), to tell the ISA's share of a ratio")
    p.add_argument("--json", help="also write the figures here")
    args = p.parse_args(argv)
    if args.rounds < 1 or args.threads < 0 or not args.seconds > 0:
        p.error("--rounds must be >= 1, --threads >= 0 and --seconds > 0")
    if args.mitsuba_lanes != "native" and args.device != "cpu":
        p.error("--mitsuba-lanes sets llvm_ad_rgb's SIMD width: --device cpu only")
    if not os.access(args.bench, os.X_OK):
        p.error(f"--bench {args.bench}: not an executable")
    args.geocold = args.geocold or os.path.join(os.path.dirname(os.path.abspath(args.bench)), "geocold-cl")
    return args


def fail(message: str, status: int = 2):
    print(f"mitsuba_yardstick: {message}", file=sys.stderr)
    raise SystemExit(status)


def thread_args(threads: int) -> list:
    return ["--threads", str(threads)] if threads > 0 else []


def ours(args, scene: str):
    """geocold-bench's path figure and view for one scene: (samples/s, view, device label, host CPU)."""
    command = [args.bench, "--json", "--device", args.device, "--scene", scene, "--no-rays", "--no-first-image",
               "--no-packet-probe", *thread_args(args.threads)]
    run = subprocess.run(command, capture_output=True, text=True)
    if run.returncode != 0:
        fail(f"{' '.join(command)} exited {run.returncode}:\n{run.stderr}")
    doc = json.loads(run.stdout)
    entry = doc["scenes"].get(scene)
    if not entry or not entry.get("path"):
        fail(f"geocold-bench measured no path figure for scene '{scene}' on {args.device}")
    label, figures = next(iter(entry["path"].items()))
    return figures["samples_per_s"], entry["view"], label, doc.get("host_cpu", {}).get("summary", "not recorded")


def llvm_target(set_avx2: bool = False):
    """Dr.Jit's LLVM target as (cpu, lanes), or None where this Dr.Jit does not say. With
    set_avx2, first pins the target to eight-lane AVX2 code (None if that is not possible).

    Why: Dr.Jit renders one path per SIMD lane, 16 per instruction where the CPU has AVX-512
    and 8 with AVX2, while our kernels trace one path per work-item whatever the width, so
    a CPU ratio comes with the ISA it was measured on. (Held to 8 lanes on the H200 host's
    AVX-512 Xeon, Mitsuba rendered the Cornell box 0.90x as fast: the width is a part of its
    per-CPU speed, not most of it.) Dr.Jit 1.5 has no Python call for its target; its C++ API
    (jit_llvm_target_cpu, jit_llvm_vector_width, jit_llvm_set_target in drjit-core's jit.h) is
    reached by name."""
    import ctypes

    import drjit as dr

    try:
        core = ctypes.CDLL(os.path.join(os.path.dirname(dr.__file__), "libdrjit-core.so"))
        cpu = core._Z19jit_llvm_target_cpuv
        lanes = core._Z21jit_llvm_vector_widthv
        set_target = core._Z19jit_llvm_set_targetPKcS0_j
    except (OSError, AttributeError):
        return None
    cpu.restype, lanes.restype = ctypes.c_char_p, ctypes.c_uint32
    if set_avx2:
        # The CPU's own scheduling model, without AVX-512 (LLVM drops the extensions that
        # depend on avx512f with it).
        set_target.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_uint32]
        set_target(cpu(), b"+avx,+avx2,+fma,+f16c,+bmi,+bmi2,+popcnt,+sse4.2,-avx512f", 8)
    return cpu().decode(), int(lanes())


def mitsuba_setup(view):
    """The Mitsuba scene and integrator for a geocold-bench view."""
    import mitsuba as mi
    from make_reference import load_groups
    from mitsuba_scene import build_scene

    if not view["source"]:
        fail("a generated scene has no file for Mitsuba to load; pick scenes with a file")
    camera = {"look_from": view["look_from"], "look_at": view["look_at"], "up": view["up"], "fov": view["fov"],
              "res": [view["width"], view["height"]]}
    with tempfile.TemporaryDirectory() as tmp:
        scene = build_scene(load_groups(view["source"], tmp), camera, view["max_depth"], view["env"])
    # rr_depth past max_depth: no Russian roulette, as in geocold-bench.
    integrator = mi.load_dict({"type": "path", "max_depth": int(view["max_depth"]),
                               "rr_depth": max(int(view["rr_depth"]), int(view["max_depth"]) + 1)})
    return scene, integrator


def mitsuba_render(scene, integrator, spp: int, seed: int):
    """(seconds, image) of one render, to the end of the device's work."""
    import drjit as dr
    import mitsuba as mi

    start = time.perf_counter()
    image = mi.render(scene, integrator=integrator, spp=spp, seed=seed)
    dr.eval(image)
    dr.sync_thread()
    return time.perf_counter() - start, image


def luminance_mean(rgb) -> float:
    """Mean Rec. 709 luminance of a flat R, G, B, R, G, B... sequence (a list, an array or a
    NumPy vector)."""
    pixels = len(rgb) // 3
    if pixels == 0:
        fail("an empty image")
    wr, wg, wb = REC709_LUMINANCE
    return (wr * sum(rgb[0::3]) + wg * sum(rgb[1::3]) + wb * sum(rgb[2::3])) / pixels


def read_pfm(path: str):
    """(width, height, rgb) of a colour PFM, rgb flat as in luminance_mean (standard library
    only, so that the checks run where NumPy is not installed)."""
    import array

    with open(path, "rb") as f:
        if f.readline().strip() != b"PF":
            fail(f"{path}: not a colour PFM")
        width, height = (int(x) for x in f.readline().split())
        scale = float(f.readline())
        rgb = array.array("f")
        rgb.frombytes(f.read())
    if (scale < 0) != (sys.byteorder == "little"):  # a negative scale means little-endian
        rgb.byteswap()
    if len(rgb) != width * height * 3:
        fail(f"{path}: {len(rgb)} floats for {width}x{height}x3")
    return width, height, rgb


def geocold_command(geocold: str, view, device: str, spp: int, out: str, extra=()) -> list:
    """The geocold-cl command line that renders a geocold-bench view to `out`."""
    triple = lambda v: ",".join(repr(float(x)) for x in v)
    return [geocold, view["source"], "--quiet", "--device", device, "--spp", str(spp),
            "--res", f"{view['width']}x{view['height']}", "--max-depth", str(view["max_depth"]),
            "--rr-depth", str(view["rr_depth"]), f"--look-from={triple(view['look_from'])}",
            f"--look-at={triple(view['look_at'])}", f"--up={triple(view['up'])}", "--fov",
            repr(float(view["fov"])), "--env", triple(view["env"]), *extra, "-o", out]


def geocold_picture(args, view, spp: int):
    """geocold-cl's rendering of the view (for the same-picture check)."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "ours.pfm")
        command = geocold_command(args.geocold, view, args.device, spp, out, thread_args(args.threads))
        run = subprocess.run(command, capture_output=True, text=True)
        if run.returncode != 0:
            fail(f"{' '.join(command)} exited {run.returncode}:\n{run.stderr}")
        width, height, rgb = read_pfm(out)
        if (width, height) != (view["width"], view["height"]):
            fail(f"geocold-cl drew {width}x{height}, not the view's {view['width']}x{view['height']}")
        return rgb


def measure_scene(args, scene_name: str) -> dict:
    ours_sps, view, label, host_cpu = ours(args, scene_name)
    scene, integrator = mitsuba_setup(view)
    pixels = view["width"] * view["height"]
    # The sample count for one render of about --seconds: grown 8x at a time until a render
    # takes a quarter of that, so that a fast device is not timed on a launch or two (1 spp of
    # the dragon takes the H200 well under a millisecond). Each new count is rendered once
    # untimed first: it may compile kernels of its own.
    spp = 1
    mitsuba_render(scene, integrator, spp, 0)
    while True:
        seconds, _ = mitsuba_render(scene, integrator, spp, 1)
        if seconds >= args.seconds / 4 or spp >= 1 << 20:
            break
        spp *= 8
        mitsuba_render(scene, integrator, spp, 0)
    spp = max(1, round(spp * args.seconds / seconds))
    _, image = mitsuba_render(scene, integrator, spp, 2)

    import numpy as np

    ours_mean = luminance_mean(geocold_picture(args, view, max(spp, 16)))
    theirs_mean = luminance_mean(np.asarray(image, dtype=np.float64)[..., :3].reshape(-1))
    diff = 100.0 * abs(ours_mean - theirs_mean) / max(theirs_mean, 1e-12)
    print(f"== {scene_name}: {view['width']}x{view['height']}, depth {view['max_depth']}, no Russian roulette; "
          f"mean luminance ours {ours_mean:.5f}, Mitsuba {theirs_mean:.5f} ({diff:.2f} % apart, bound "
          f"{args.same_picture} %)")
    print(f"  host CPU: {host_cpu}")
    if not diff <= args.same_picture:
        fail(f"{scene_name}: the two renderers do not draw the same picture; no ratio", 1)

    rounds = []
    for r in range(args.rounds):
        if r > 0:
            ours_sps, _, _, _ = ours(args, scene_name)
        seconds, _ = mitsuba_render(scene, integrator, spp, 3 + r)
        theirs_sps = pixels * spp / seconds
        rounds.append({"ours": ours_sps, "mitsuba": theirs_sps, "ratio": ours_sps / theirs_sps})
        print(f"  round {r + 1}: ours {ours_sps / 1e6:.4f} M, Mitsuba {theirs_sps / 1e6:.4f} M "
              f"({spp} spp in {seconds:.3f} s) = {ours_sps / theirs_sps:.3f}x")
    ratios = [x["ratio"] for x in rounds]
    summary = {"device": label, "host_cpu": host_cpu, "ours_median": statistics.median(x["ours"] for x in rounds),
               "mitsuba_median": statistics.median(x["mitsuba"] for x in rounds), "ratio_median": statistics.median(ratios),
               "ratio_min": min(ratios), "ratio_max": max(ratios), "mitsuba_spp": spp, "rounds": rounds,
               "mean_luminance": {"ours": ours_mean, "mitsuba": theirs_mean}}
    print(f"  {scene_name} {label}: ours {summary['ours_median'] / 1e6:.4f} M / Mitsuba "
          f"{summary['mitsuba_median'] / 1e6:.4f} M samples/s = {summary['ratio_median']:.3f}x (median of "
          f"{len(ratios)} per-round ratios, {summary['ratio_min']:.3f}-{summary['ratio_max']:.3f})")
    return summary


def main(argv=None) -> int:
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        import drjit as dr
        import mitsuba as mi
    except ImportError as e:
        fail(f"Mitsuba 3 is not importable ({e}); pip install -r tools/reference/requirements.txt")
    variant = "cuda_ad_rgb" if args.device == "gpu" else "llvm_ad_rgb"
    try:
        mi.set_variant(variant)
    except Exception as e:  # Dr.Jit raises its own types when LLVM or CUDA is missing
        fail(f"Mitsuba's {variant} does not start here ({e}); llvm needs libLLVM >= 17 "
             "(DRJIT_LIBLLVM_PATH), cuda an NVIDIA driver")
    if args.threads > 0:
        dr.set_thread_count(args.threads)
    target = None
    if args.device == "cpu":
        target = llvm_target(set_avx2=args.mitsuba_lanes == "8")
        if args.mitsuba_lanes == "8" and (target is None or target[1] != 8):
            fail("--mitsuba-lanes 8: this Dr.Jit's target cannot be set")
    threads = "every core" if args.threads == 0 else f"{args.threads} thread(s)"
    isa = f" ({target[0]}, {target[1]} lanes)" if target else ""
    print(f"Mitsuba {mi.__version__} {variant}{isa} against geocold-bench --device {args.device}, {threads}, "
          f"{args.rounds} interleaved rounds")
    results = {name: measure_scene(args, name) for name in args.scene.split(",") if name}
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"variant": variant, "mitsuba": mi.__version__, "threads": args.threads,
                       "llvm_target": {"cpu": target[0], "lanes": target[1]} if target else None,
                       "scenes": results}, f, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
