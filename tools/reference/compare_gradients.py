"""Compares two gradients printed by prb_gradient.py / geocold_gradient.py, component by
component, in units of their combined standard error.

    build/release/python-venv/bin/python tools/reference/compare_gradients.py geocold.json mitsuba.json

(any Python with NumPy). For each component z = (a - b) / sqrt(se_a^2 + se_b^2). Prints the
count, mean, std and largest |z|, the fraction with |z| < 3, and the relative difference of the
totals (sum over components). Exits 1 when more than 1% of the |z| exceed 4, or on a shift
that every component shares (a systematic bias), too small to show in any one of them:

- where both files carry "total_std_error" (the pass-to-pass error of the sum over
  components), when the totals differ by more than 4 of their combined errors;
- otherwise (older files), when the mean z lies beyond 4 / sqrt(count).

The second test takes the components for independent; they seldom are. A texel's R, G and B
under a constant environment are one number times the environment's colour, and neighbouring
texels share the samples of their bilinear footprints: on the textured plane (192 components)
the mean z scatters ~0.2 from run to run, against a threshold of 0.29 meant as 4 sigma. The
sum's own error holds those correlations.
"""

from __future__ import annotations

import argparse
import json
import sys

import numpy as np


def pass_statistics(g: np.ndarray) -> dict:
    """The fields both gradient scripts print for passes x components `g`: each component's
    mean and standard error, and the sum over components with its pass-to-pass error (which,
    unlike one from the components' errors, holds their correlations: the bias test below)."""
    total = g.sum(axis=1)
    root_n = np.sqrt(len(g))
    return {"gradient": g.mean(axis=0).tolist(), "std_error": (g.std(axis=0, ddof=1) / root_n).tolist(),
            "total": float(total.mean()), "total_std_error": float(total.std(ddof=1) / root_n)}


def load(path: str):
    with open(path) as f:
        d = json.load(f)
    return d, np.asarray(d["gradient"], dtype=np.float64), np.asarray(d["std_error"], dtype=np.float64)


def z_scores(a, se_a, b, se_b) -> np.ndarray:
    se = np.sqrt(se_a ** 2 + se_b ** 2)
    if np.any(se == 0):
        # Zero error on both sides (a texel no camera ray reaches): equal values are no evidence
        # either way, unequal ones are a real difference.
        bad = (se == 0) & (a != b)
        if np.any(bad):
            raise SystemExit(f"error: {bad.sum()} components differ with zero standard error on both sides")
    with np.errstate(invalid="ignore", divide="ignore"):
        z = (a - b) / se
    return z[se > 0]


def summary(z: np.ndarray, a: np.ndarray, b: np.ndarray) -> dict:
    total_a, total_b = a.sum(), b.sum()
    return {"count": int(z.size), "mean": float(z.mean()), "std": float(z.std(ddof=1)) if z.size > 1 else 0.0,
            "max_abs": float(np.abs(z).max()), "within_3": float(np.mean(np.abs(z) < 3)),
            "over_4": float(np.mean(np.abs(z) > 4)), "total_a": float(total_a), "total_b": float(total_b),
            "total_rel_diff": float(abs(total_a - total_b) / max(abs(total_a), abs(total_b), 1e-300))}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("a", help="a gradient JSON (e.g. geocold's)")
    ap.add_argument("b", help="another, of the same parameter (e.g. Mitsuba's)")
    args = ap.parse_args(argv)

    da, a, se_a = load(args.a)
    db, b, se_b = load(args.b)
    if a.shape != b.shape or da.get("shape") != db.get("shape"):
        raise SystemExit(f"error: shapes differ: {da.get('shape', list(a.shape))} vs {db.get('shape', list(b.shape))}")
    z = z_scores(a, se_a, b, se_b)
    s = summary(z, a, b)
    print(f"a: {da.get('renderer')} ({args.a})\nb: {db.get('renderer')} ({args.b})")
    print(f"z = (a - b) / combined std. error over {s['count']} components: mean {s['mean']:+.3f}, "
          f"std {s['std']:.3f}, max |z| {s['max_abs']:.2f}, |z| < 3: {100 * s['within_3']:.1f}%, "
          f"|z| > 4: {100 * s['over_4']:.1f}%")
    print(f"totals: a {s['total_a']:.7g}, b {s['total_b']:.7g}, relative difference {s['total_rel_diff']:.2e}", end="")
    failures = []
    if s["over_4"] > 0.01:
        failures.append(f"{100 * s['over_4']:.1f}% of |z| exceed 4")
    if "total_std_error" in da and "total_std_error" in db:
        z_total = (s["total_a"] - s["total_b"]) / np.hypot(da["total_std_error"], db["total_std_error"])
        print(f", z {z_total:+.2f}")
        if abs(z_total) > 4:
            failures.append(f"the totals differ by {z_total:+.2f} combined std. errors")
    else:
        print(" (no total_std_error: bias test on the mean z)")
        if abs(s["mean"]) > 4 / np.sqrt(s["count"]):
            failures.append(f"mean z {s['mean']:+.3f} beyond 4/sqrt({s['count']}) = {4 / np.sqrt(s['count']):.3f}")
    print("disagree: " + "; ".join(failures) if failures else "agree within the noise")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
