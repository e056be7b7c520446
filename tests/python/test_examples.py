"""Every script in examples/ runs, and does what it says."""

import subprocess
import sys

import numpy as np
import pytest

from conftest import ROOT

EXAMPLES = ROOT / "examples"


def run(script, *args, cwd):
    done = subprocess.run([sys.executable, str(EXAMPLES / script), *args], cwd=cwd, capture_output=True,
                          text=True, timeout=600)
    print(done.stdout, done.stderr)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_render_to_numpy(gc, device, tmp_path):
    out = run("render_to_numpy.py", "--device", device, "--spp", "4", "--res", "64", "48", "-o", "r.exr",
              cwd=tmp_path)
    assert "4 spp on" in out
    assert gc.read(tmp_path / "r.exr").shape == (48, 64, 4)
    assert (tmp_path / "r.albedo.png").exists()


def test_material_sweep_contact_sheet(device, tmp_path):
    from PIL import Image

    run("material_sweep.py", "--device", device, "--size", "48", "--spp", "2", "-o", "sheet.png", cwd=tmp_path)
    sheet = np.asarray(Image.open(tmp_path / "sheet.png"))
    assert sheet.shape == (2 * (48 + 14), 5 * 48, 3)
    tiles = [sheet[14:62, 48 * i:48 * (i + 1)] for i in range(5)]
    assert all(not np.array_equal(tiles[0], t) for t in tiles[1:])  # the sweep changes the image


def test_edit_rerender_within_ten_percent_of_the_set_up(device, tmp_path):
    # A first run's set-up: the kernels compiled, as on a fresh machine.
    out = run("edit_rerender.py", "--device", device, "--res", "128", "--cold", "--max-ratio", "0.10",
              cwd=tmp_path)
    assert "programs rebuilt: 0" in out


def test_optimize_wall_colour_recovers_the_red_wall(device, tmp_path):
    out = run("optimize_wall_colour.py", "--device", device, "--res", "64", "--target-spp", "64", "-o", "wall",
              cwd=tmp_path)
    error = float(out.split("colour error")[1].split()[0])
    print(f"  colour error {error:.6f} (sum over RGB of squared differences; limit 0.005)")
    assert error <= 0.005
    assert (tmp_path / "wall-loss.png").exists() and (tmp_path / "wall-images.png").exists()


def test_optimize_texture_brings_the_renders_to_the_target(device, tmp_path):
    out = run("optimize_texture.py", "--device", device, "--res", "64", "--iterations", "40", "-o", "tex",
              cwd=tmp_path)
    before, after = (float(v) for v in out.split("image error (RMS): before")[1].replace(", after", "").split()[:2])
    print(f"  image error (RMS over three views) before {before:.5f}, after {after:.5f} (limit: after <= 0.3 x before)")
    assert after <= 0.3 * before
    assert (tmp_path / "tex-loss.png").exists() and (tmp_path / "tex-images.png").exists()
