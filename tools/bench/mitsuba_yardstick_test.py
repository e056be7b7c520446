"""Checks of tools/bench/mitsuba_yardstick.py that need no Mitsuba (ctest: bench_yardstick_py).

The yardstick itself runs by hand (Mitsuba and LLVM >= 17 are not build dependencies), so
what can break silently is its side of the contract with our own tools: that geocold-bench
--json still gives it a view and a figure, that geocold-cl still takes the options it passes
and writes the PFM it reads, and that bad usage stops it with exit 2. GEOCOLD_BENCH and
GEOCOLD_CL name the executables.
"""

from __future__ import annotations

import os
import struct
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import mitsuba_yardstick as yardstick  # noqa: E402

SCRIPT = os.path.join(HERE, "mitsuba_yardstick.py")
BENCH = os.environ.get("GEOCOLD_BENCH", "")
GEOCOLD = os.environ.get("GEOCOLD_CL", "")


def run_script(*args):
    return subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True)


class Usage(unittest.TestCase):
    def test_a_missing_bench_is_a_usage_error(self):
        run = run_script("--bench", "/nonexistent/geocold-bench")
        print(f"[ yardstick ] --bench /nonexistent: exit {run.returncode}: {run.stderr.strip().splitlines()[-1]}")
        self.assertEqual(run.returncode, 2)
        self.assertIn("not an executable", run.stderr)

    def test_zero_rounds_is_a_usage_error(self):
        run = run_script("--bench", BENCH, "--rounds", "0")
        self.assertEqual(run.returncode, 2)
        self.assertIn("--rounds must be >= 1", run.stderr)

    def test_lanes_on_the_gpu_are_a_usage_error(self):
        run = run_script("--bench", BENCH, "--device", "gpu", "--mitsuba-lanes", "8")
        self.assertEqual(run.returncode, 2)
        self.assertIn("--device cpu only", run.stderr)


class Pfm(unittest.TestCase):
    def write(self, header: bytes, floats, order: str) -> str:
        f = tempfile.NamedTemporaryFile(suffix=".pfm", delete=False)
        f.write(header + struct.pack(order + "f" * len(floats), *floats))
        f.close()
        self.addCleanup(os.unlink, f.name)
        return f.name

    def test_reads_both_byte_orders(self):
        pixels = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0]  # 2x1: red, green
        for header, order in ((b"PF\n2 1\n-1\n", "<"), (b"PF\n2 1\n1\n", ">")):
            width, height, rgb = yardstick.read_pfm(self.write(header, pixels, order))
            mean = yardstick.luminance_mean(rgb)
            print(f"[ yardstick ] {header.split()[-1].decode()} scale: {width}x{height}, mean luminance {mean:.4f}")
            self.assertEqual((width, height), (2, 1))
            self.assertAlmostEqual(mean, (0.2126 + 0.7152) / 2, places=6)

    def test_rejects_grey_and_short_files(self):
        for header, floats in ((b"Pf\n1 1\n-1\n", [0.5]), (b"PF\n2 2\n-1\n", [0.5] * 3)):
            with self.assertRaises(SystemExit) as stop:
                yardstick.read_pfm(self.write(header, floats, "<"))
            self.assertEqual(stop.exception.code, 2)


@unittest.skipUnless(BENCH and GEOCOLD, "GEOCOLD_BENCH and GEOCOLD_CL name the executables")
class OwnTools(unittest.TestCase):
    def args(self):
        return yardstick.parse_args(["--bench", BENCH, "--geocold", GEOCOLD, "--threads", "1", "--device", "cpu"])

    def test_bench_json_gives_a_view_and_a_figure_and_geocold_cl_draws_it(self):
        args = self.args()
        samples_per_s, view, label, host_cpu = yardstick.ours(args, "tiny")
        print(f"[ yardstick ] geocold-bench tiny on {label} ({host_cpu}): {samples_per_s / 1e6:.3f} M samples/s, "
              f"view {view}")
        self.assertNotEqual(host_cpu, "not recorded")
        self.assertGreater(samples_per_s, 0.0)
        self.assertTrue(view["source"].endswith("CornellBox-Original.obj"))
        self.assertEqual((view["width"], view["height"], view["max_depth"]), (64, 64, 8))
        self.assertGreater(view["rr_depth"], view["max_depth"])  # no Russian roulette
        rgb = yardstick.geocold_picture(args, view, 4)
        mean = yardstick.luminance_mean(rgb)
        print(f"[ yardstick ] geocold-cl drew {len(rgb) // 3} pixels, mean luminance {mean:.5f}")
        self.assertEqual(len(rgb), 64 * 64 * 3)
        # The Cornell box's light: a lit picture, and not a blown-out one.
        self.assertGreater(mean, 0.01)
        self.assertLess(mean, 1.0)


if __name__ == "__main__":
    unittest.main(verbosity=2)
