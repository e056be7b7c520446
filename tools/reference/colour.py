"""Colour arithmetic shared by the reference and benchmark scripts. It imports nothing, so
the scripts and tests that must run without Mitsuba (tools/bench/mitsuba_yardstick.py's
ctest) can use it too."""
from __future__ import annotations

# Rec. 709 / sRGB primaries, the renderer's working space.
REC709_LUMINANCE = (0.2126, 0.7152, 0.0722)


def luminance(c) -> float:
    """Luminance of one RGB triple."""
    wr, wg, wb = REC709_LUMINANCE
    return wr * c[0] + wg * c[1] + wb * c[2]
