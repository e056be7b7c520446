"""gc.write's display transforms: 8-bit outputs go through the named curve, float ones stay linear."""

import numpy as np
import pytest


def test_tonemap_applies_to_eight_bit_outputs_only(gc, tmp_path):
    img = np.ones((2, 3, 3), np.float32)
    gc.write(tmp_path / "clamp.ppm", img, tonemap="clamp")
    gc.write(tmp_path / "neutral.ppm", img)  # the CLI's default for a rendered image
    gc.write(tmp_path / "neutral.pfm", img, tonemap="pbr-neutral", exposure=1.0)
    assert np.allclose(gc.read(tmp_path / "clamp.ppm")[..., :3], 1.0)
    # Khronos PBR Neutral maps 1.0 to 0.8690909 (KhronosGroup/ToneMapping, PBR_Neutral).
    assert np.allclose(gc.read(tmp_path / "neutral.ppm")[..., :3], 0.8690909, atol=0.01)
    assert np.array_equal(gc.read(tmp_path / "neutral.pfm")[..., :3], img)
    with pytest.raises(gc.ArgumentError, match="tonemap"):
        gc.write(tmp_path / "x.ppm", img, tonemap="filmic")
