#!/usr/bin/env python3
"""Instructions per path sample, ours against Mitsuba 3 llvm_ad_rgb, counted by Valgrind.

Why: on the H200 host's Xeon the guest's CPUs look like hardware threads whose core's other
thread is usually busy (experiments README, session 25). There the core's issue ports are
shared, and a program's speed follows how many instructions it needs per sample more than
how long its dependent chains are. The VM has no hardware counters, so this counts them in
software: each program renders the same view twice, with few and with many samples per
pixel, under `valgrind --tool=cachegrind --cache-sim=no`; the difference of the two totals
over the difference of the samples is the instructions per sample, start-up and kernel
loading cancelled. Kernel caches are warmed first by the same runs, with and without
Valgrind, so no compiler runs in a counted run. Each program gets one thread (PoCL: one
worker; Dr.Jit: one thread), and Valgrind runs a process's threads one at a time, so a
thread that spins while it waits would count too: the two totals' difference keeps what
grows with the samples.

Valgrind 3.19 does not decode AVX-512, so this runs on AVX2 machines (Dr.Jit at 8 lanes).

    tools/bench/experiments/instructions_per_sample.py --bench build/release/geocold-bench \
        [--scene cornell] [--res 64] [--spp 8,72]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
sys.path.insert(0, os.path.join(HERE, "..", "..", "reference"))
from mitsuba_yardstick import geocold_command  # noqa: E402  (imports no Mitsuba itself)

# One Mitsuba render in its own process, one thread. argv: the view (JSON), spp, a file to
# write Dr.Jit's LLVM target to, and the folders mitsuba_yardstick.py imports from (JSON).
MITSUBA_CHILD = r"""
import json, sys
import drjit as dr, mitsuba as mi
mi.set_variant("llvm_ad_rgb")
dr.set_thread_count(1)
sys.path[:0] = json.loads(sys.argv[4])
from mitsuba_yardstick import llvm_target, mitsuba_setup, mitsuba_render
view = json.loads(sys.argv[1])
scene, integrator = mitsuba_setup(view)
seconds, image = mitsuba_render(scene, integrator, int(sys.argv[2]), 0)
open(sys.argv[3], "w").write(json.dumps(llvm_target()))
"""


def fail(message: str):
    print(f"instructions_per_sample: {message}", file=sys.stderr)
    sys.exit(1)


def run(command, valgrind: bool) -> int:
    """Runs command; under Valgrind, returns its instruction total (else 0)."""
    prefix = ["valgrind", "--tool=cachegrind", "--cache-sim=no", "--cachegrind-out-file=/dev/null"] if valgrind else []
    done = subprocess.run(prefix + command, capture_output=True, text=True)
    if done.returncode != 0:
        fail(f"{' '.join(prefix + command)} exited {done.returncode}:\n{done.stderr[-3000:]}")
    if not valgrind:
        return 0
    found = re.search(r"I\s+refs:\s+([\d,]+)", done.stderr)
    if not found:
        fail(f"no 'I refs' line from Valgrind:\n{done.stderr[-2000:]}")
    return int(found.group(1).replace(",", ""))


def ours_command(geocold: str, view, spp: int, out: str):
    # Fixed passes of 8 samples: the camera packets of eight samples the renderer's own
    # planner uses on a CPU, whatever the (here much slower) pass times.
    return geocold_command(geocold, view, "cpu", spp, out, ["--threads", "1", "--samples-per-pass", "8"])


def mitsuba_command(view, spp: int, out: str):
    paths = [os.path.join(HERE, ".."), os.path.join(HERE, "..", "..", "reference")]
    return [sys.executable, "-c", MITSUBA_CHILD, json.dumps(view), str(spp), out, json.dumps(paths)]


def per_sample(name: str, make, res: int, spps, note=lambda: "") -> float:
    low, high = spps
    # Warm the kernel caches, outside Valgrind and under it: the CPU that Valgrind shows a
    # program may differ from the real one, and so may the kernel a cache keys on it.
    # Dr.Jit keys its kernels on the sample count too, so both counts are warmed.
    for spp in (low, high):
        run(make(spp), valgrind=False)
        run(make(spp), valgrind=True)
    counts = [run(make(spp), valgrind=True) for spp in (low, high)]
    value = (counts[1] - counts[0]) / (res * res * (high - low))
    print(f"  {name}: {counts[0]:,} instructions at {low} spp, {counts[1]:,} at {high} spp: "
          f"{value:,.0f} per sample{note()}")
    return value


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--bench", required=True, help="geocold-bench (for the scene's view)")
    p.add_argument("--geocold", help="geocold-cl (default: beside --bench)")
    p.add_argument("--scene", default="cornell")
    p.add_argument("--res", type=int, default=64, help="square image side")
    p.add_argument("--spp", default="8,72",
                   help="the two sample counts, low,high (far apart: Mitsuba's totals move by tens of millions "
                        "between runs)")
    args = p.parse_args()
    geocold = args.geocold or os.path.join(os.path.dirname(args.bench), "geocold-cl")
    spps = [int(x) for x in args.spp.split(",")]
    if len(spps) != 2 or not 0 < spps[0] < spps[1] or args.res < 1:
        fail("--spp takes two counts, low < high, and --res a positive side")
    doc = subprocess.run([args.bench, "--json", "--device", "cpu", "--scene", args.scene, "--no-rays",
                          "--no-first-image", "--no-path", "--no-packet-probe"], capture_output=True, text=True)
    if doc.returncode != 0:
        fail(f"geocold-bench exited {doc.returncode}:\n{doc.stderr}")
    view = dict(json.loads(doc.stdout)["scenes"][args.scene]["view"], width=args.res, height=args.res)
    print(f"{args.scene} at {args.res}x{args.res}, depth {view['max_depth']}, one thread each, "
          f"Valgrind instruction counts at {spps[0]} and {spps[1]} spp")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        ours = per_sample("geocold-cl (PoCL)", lambda spp: ours_command(geocold, view, spp, out + ".pfm"),
                          args.res, spps)
        # The child writes Dr.Jit's LLVM target (as seen under Valgrind in the counted runs).
        target = lambda: f" (Dr.Jit target under Valgrind: {open(out + '.txt').read()})"
        theirs = per_sample("Mitsuba llvm_ad_rgb", lambda spp: mitsuba_command(view, spp, out + ".txt"),
                            args.res, spps, target)
    print(f"ours / Mitsuba: {ours / theirs:.2f}x the instructions per sample")
    return 0


if __name__ == "__main__":
    sys.exit(main())
