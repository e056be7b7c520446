"""Checks of tools/bench/yardstick_scaling.py on hand-made yardstick documents (ctest:
bench_yardstick_scaling_py): the growth figures it prints, and exit 2 with the file named for
documents it cannot compare."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "yardstick_scaling.py")


def document(threads, scenes, variant="llvm_ad_rgb"):
    return {"variant": variant, "mitsuba": "3.9.1", "threads": threads,
            "scenes": {name: {"ours_median": ours, "mitsuba_median": theirs} for name, (ours, theirs) in scenes.items()}}


class Scaling(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.dir.cleanup()

    def write(self, name, doc):
        path = os.path.join(self.dir.name, name)
        with open(path, "w", encoding="utf-8") as f:
            f.write(doc if isinstance(doc, str) else json.dumps(doc))
        return path

    def run_script(self, *args):
        run = subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True)
        print(f"[ scaling ] exit {run.returncode}: {(run.stdout + run.stderr).strip()}")
        return run

    def test_growth_of_each_side_and_their_ratio(self):
        # Ours 1.0 -> 12.0 M (12x), Mitsuba 1.0 -> 16.0 M (16x): 0.75x of Mitsuba's growth.
        few = self.write("one.json", document(1, {"cornell": (1.0e6, 1.0e6), "dragon": (4.0e6, 2.0e6)}))
        many = self.write("all.json", document(0, {"cornell": (12.0e6, 16.0e6), "dragon": (64.0e6, 32.0e6),
                                                   "bunny": (1.0, 1.0)}))
        run = self.run_script(few, many)
        self.assertEqual(run.returncode, 0)
        self.assertIn("from 1 thread", run.stdout)
        self.assertIn("to every core", run.stdout)
        self.assertIn("cornell: ours 1.000 -> 12.00 M = 12.0x, Mitsuba 1.000 -> 16.00 M = 16.0x; "
                      "ours / Mitsuba's growth 0.750x", run.stdout)
        self.assertIn("dragon: ours 4.000 -> 64.00 M = 16.0x, Mitsuba 2.000 -> 32.00 M = 16.0x; "
                      "ours / Mitsuba's growth 1.000x", run.stdout)
        self.assertNotIn("bunny", run.stdout, "a scene of one document only has no growth")

    def test_documents_it_cannot_compare_exit_2_naming_the_file(self):
        good = self.write("one.json", document(1, {"cornell": (1.0e6, 1.0e6)}))
        cases = {
            "same threads": (self.write("same.json", document(1, {"cornell": (2.0e6, 2.0e6)})), "both documents ran"),
            "other variant": (self.write("gpu.json", document(0, {"cornell": (2.0e6, 2.0e6)}, "cuda_ad_rgb")),
                              "different Mitsuba variants"),
            "no shared scene": (self.write("dragon.json", document(0, {"dragon": (2.0e6, 2.0e6)})), "no scene in common"),
            "not JSON": (self.write("broken.json", "{\"threads\": 0, "), "broken.json"),
            "no scenes": (self.write("empty.json", {"threads": 0}), "empty.json: not a mitsuba_yardstick.py"),
            "zero figure": (self.write("zero.json", document(0, {"cornell": (0.0, 2.0e6)})),
                            "zero.json: scene cornell has a figure that is not positive"),
            "missing file": (os.path.join(self.dir.name, "absent.json"), "absent.json"),
        }
        for what, (other, message) in cases.items():
            with self.subTest(what):
                run = self.run_script(good, other)
                self.assertEqual(run.returncode, 2)
                self.assertIn(message, run.stderr)
                self.assertEqual(run.stdout, "")

    def test_usage(self):
        self.assertEqual(self.run_script().returncode, 2)
        run = self.run_script("--help")
        self.assertEqual(run.returncode, 0)
        self.assertIn("Usage: yardstick_scaling.py FEW.json MANY.json", run.stdout)


if __name__ == "__main__":
    unittest.main(verbosity=2)
