#!/usr/bin/env python3
"""How each side of two mitsuba_yardstick.py runs grows from few threads to many.

Reads the --json documents of a run on few threads (typically --threads 1) and of a run on
more (typically every core), and prints per scene both sides' samples per second and how
much each grew, then the ratio of the two growths. A ratio against Mitsuba that falls from
one thread to 16 cores is either the one-thread figures (which move most between rounds) or
a scaling loss; this separates them: a growth below the thread count that Mitsuba's does not
share is ours. Medians of each run's rounds: the two runs are not interleaved with each
other, so there are no per-round pairs.

Usage: yardstick_scaling.py FEW.json MANY.json
Exit status: 0, or 2 for unreadable or mismatched documents.
"""

from __future__ import annotations

import json
import sys
from typing import NoReturn


def fail(message: str) -> NoReturn:
    print(f"yardstick_scaling: {message}", file=sys.stderr)
    sys.exit(2)


def load(path: str) -> dict:
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, ValueError) as e:
        fail(f"{path}: {e}")
    if not isinstance(doc, dict) or not isinstance(doc.get("scenes"), dict) or "threads" not in doc:
        fail(f"{path}: not a mitsuba_yardstick.py --json document (no 'threads' and 'scenes')")
    return doc


def threads_label(threads: int) -> str:
    return "every core" if threads == 0 else f"{threads} thread{'s' if threads != 1 else ''}"


def median_pair(path: str, name: str, scene: dict) -> tuple[float, float]:
    try:
        ours, theirs = float(scene["ours_median"]), float(scene["mitsuba_median"])
    except (KeyError, TypeError, ValueError):
        fail(f"{path}: scene {name} has no ours_median / mitsuba_median")
    if not (ours > 0 and theirs > 0):
        fail(f"{path}: scene {name} has a figure that is not positive")
    return ours, theirs


def growth_lines(few_path: str, many_path: str, few: dict, many: dict) -> list[str]:
    if few["threads"] == many["threads"]:
        fail(f"both documents ran on {threads_label(few['threads'])}")
    if few.get("variant") != many.get("variant"):
        fail(f"different Mitsuba variants: {few.get('variant')} and {many.get('variant')}")
    shared = [name for name in few["scenes"] if name in many["scenes"]]
    if not shared:
        fail(f"{few_path} and {many_path} have no scene in common")
    lines = [f"growth from {threads_label(few['threads'])} ({few_path}) to {threads_label(many['threads'])} "
             f"({many_path}), medians of each run's rounds:"]
    for name in shared:
        ours_few, theirs_few = median_pair(few_path, name, few["scenes"][name])
        ours_many, theirs_many = median_pair(many_path, name, many["scenes"][name])
        ours_growth = ours_many / ours_few
        theirs_growth = theirs_many / theirs_few
        lines.append(f"  {name}: ours {ours_few / 1e6:.3f} -> {ours_many / 1e6:.2f} M = {ours_growth:.1f}x, "
                     f"Mitsuba {theirs_few / 1e6:.3f} -> {theirs_many / 1e6:.2f} M = {theirs_growth:.1f}x; "
                     f"ours / Mitsuba's growth {ours_growth / theirs_growth:.3f}x")
    return lines


def main(argv: list[str]) -> int:
    if argv[:1] in (["-h"], ["--help"]):
        print(__doc__.strip())
        return 0
    if len(argv) != 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    few, many = load(argv[0]), load(argv[1])
    print("\n".join(growth_lines(argv[0], argv[1], few, many)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
