#!/usr/bin/env python3
"""Writes plane.obj, plane.mtl and texture.png: a 2x2 quad in the y = 0 plane (normal +y), uv
0..1 over it, a Lambert material (Kd 1) whose map_Kd is an 8x8 8-bit sRGB PNG with a
different colour in every texel. Deterministic; needs NumPy and Mitsuba 3 (for the PNG).

    python3 make_textured_plane.py   (in this folder, in tools/reference's venv)
"""
import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")

N = 8
y, x = np.mgrid[0:N, 0:N]
# R grows left to right, G top to bottom, B a scramble of both: every texel differs, and a
# flip of rows or columns changes the image. Stored values 24..231, away from 0 and 255.
rgb = np.stack([x, y, (3 * x + 5 * y) % N], axis=-1).astype(np.float64)
texels = np.round(24 + rgb * (207 / (N - 1))).astype(np.uint8)
assert len({tuple(t) for t in texels.reshape(-1, 3)}) == N * N
mi.Bitmap(texels, mi.Bitmap.PixelFormat.RGB).write("texture.png")

with open("plane.mtl", "w") as f:
    f.write("newmtl plane\nillum 1\nKd 1 1 1\nKa 0 0 0\nmap_Kd texture.png\n")
with open("plane.obj", "w") as f:
    # vt v is up: the image's top row (v = 1) lies at z = -1, away from a camera on +z.
    f.write("mtllib plane.mtl\n"
            "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\n"
            "vt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\n"
            "vn 0 1 0\n"
            "usemtl plane\n"
            # counter-clockwise seen from +y
            "f 4/4/1 3/3/1 2/2/1\nf 4/4/1 2/2/1 1/1/1\n")
