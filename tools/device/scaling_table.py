#!/usr/bin/env python3
"""The table of tools/device/multi-gpu-scaling.sh from its run logs.

Each log (SCENE.SET.N.rROUND.log) is one `geocold-cl -v` frame plus the script's "rc=" and
"hash" lines. Per scene, device set (gpus, gpus-pocl) and GPU count N, over the rounds:
median samples per second; scaling efficiency T(1) / (N T(N)) with T the median frame time
(rendering, every device set up) and T(1) the one-GPU frame's of the same set; the end-of-frame
idle time, from the first to the last device's last chunk (among devices that rendered any:
how long the first one done waited for the others), as a share of the frame; and whether every
round's image hash equals the one-GPU GPUs-alone frame's.
Usage: scaling_table.py RUNS_DIR
"""
import re
import statistics
import sys
from pathlib import Path

DEVICE = re.compile(r"device (?P<name>.*): (?P<chunks>\d+) chunks .* last chunk at (?P<last>[\d.]+) s")
FRAME = re.compile(r"frame: (?P<seconds>[\d.]+) s rendering")
RATE = re.compile(r"(?P<rate>[\d.]+) Msamples/s")
HASH = re.compile(r"^hash (?P<hash>\w+)", re.M)


def read_run(path):
    text = path.read_text(errors="replace")
    if "rc=0" not in text:
        return None
    frame = float(FRAME.search(text)["seconds"])
    ends = [float(m["last"]) for m in DEVICE.finditer(text) if int(m["chunks"]) > 0]
    return {
        "rate": float(RATE.search(text)["rate"]),
        "seconds": frame,
        "idle": (max(ends) - min(ends)) / frame if ends else 0.0,
        "hash": HASH.search(text)["hash"],
    }


def main(runs_dir):
    runs = {}
    failed = []
    for path in sorted(Path(runs_dir).glob("*.log")):
        scene, device_set, n, _round = path.stem.split(".")
        run = read_run(path)
        if run is None:
            failed.append(path.name)
            continue
        runs.setdefault((scene, device_set, int(n)), []).append(run)
    print("| scene | devices | GPUs | Msamples/s (median) | efficiency T(1)/(N T(N)) | end idle (max) | "
          "bits = 1 GPU |")
    print("|---|---|---|---|---|---|---|")
    for (scene, device_set, n), rounds in sorted(runs.items()):
        seconds = statistics.median(r["seconds"] for r in rounds)
        one = runs.get((scene, device_set, 1))
        efficiency = statistics.median(r["seconds"] for r in one) / (n * seconds) if one else float("nan")
        reference = runs.get((scene, "gpus", 1))
        same = reference is not None and all(r["hash"] == reference[0]["hash"] for r in rounds)
        print(f"| {scene} | {device_set} | {n} | {statistics.median(r['rate'] for r in rounds):.1f} | "
              f"{efficiency:.3f} | {100 * max(r['idle'] for r in rounds):.1f} % | "
              f"{'yes' if same else 'no'} ({len(rounds)} rounds) |")
    for name in failed:
        print(f"failed: {name}")
    return 1 if failed else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
