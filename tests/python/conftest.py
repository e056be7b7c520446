"""Fixtures of the geocold pytest suite: the bundled Cornell box, the device under test
(GEOCOLD_TEST_DEVICE, default "any") and the geocold-cl binary to compare with (GEOCOLD_CLI,
else build/*/geocold-cl)."""

import os
import pathlib
import shutil

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
CORNELL = ROOT / "scenes" / "cornell-box" / "CornellBox-Original.obj"
DEVICE = os.environ.get("GEOCOLD_TEST_DEVICE", "any")
RES = (48, 40)  # small and not square: catches a swapped width and height


@pytest.fixture(scope="session")
def gc():
    import geocold
    return geocold


@pytest.fixture()
def cornell(gc):
    return gc.load(CORNELL)


@pytest.fixture(scope="session")
def device():
    return DEVICE


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("GEOCOLD_CLI")
    if not path:
        candidates = sorted(ROOT.glob("build/*/geocold-cl"), key=lambda p: p.stat().st_mtime, reverse=True)
        path = str(candidates[0]) if candidates else shutil.which("geocold-cl")
    if not path or not os.path.exists(path):
        pytest.skip("no geocold-cl binary (set GEOCOLD_CLI)")
    return path
