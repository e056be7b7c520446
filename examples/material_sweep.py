"""Sweep one material's factor and lay the renders out as a contact sheet (PNG, Pillow).

Every frame re-renders the same device scene after an edit: no reload, no BVH build, no
program build.

    python examples/material_sweep.py [scene.obj] [--material tallBox] [--device any] [-o sheet.png]
"""

import argparse
import pathlib

import numpy as np
from PIL import Image, ImageDraw

import geocold as gc

HERE = pathlib.Path(__file__).resolve().parent
DEFAULT_SCENE = HERE.parent / "scenes" / "cornell-box" / "CornellBox-Original.obj"


def to_srgb8(img):
    """Linear RGB to 8-bit sRGB (the OETF, no tone mapping), as gc.write does for PNG."""
    x = np.clip(img[..., :3], 0.0, 1.0)
    x = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    return (x * 255 + 0.5).astype(np.uint8)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", nargs="?", default=str(DEFAULT_SCENE))
    ap.add_argument("--material", default="tallBox")
    ap.add_argument("--device", default="any")
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("-o", "--output", default="sweep.png")
    args = ap.parse_args()

    scene = gc.load(args.scene)
    m = scene.materials[args.material]
    r = gc.Renderer(scene, device=args.device, res=(args.size, args.size), seed=0)
    rows = {
        "base_color": [(v, 0.2, 1.0 - v) for v in np.linspace(0.05, 0.95, 5)],
        "emission": [(v, v, v) for v in (0.0, 0.5, 1.0, 2.0, 4.0)],
    }
    original = m.fields()
    sheet = Image.new("RGB", (5 * args.size, len(rows) * (args.size + 14)), "white")
    draw = ImageDraw.Draw(sheet)
    for row, (field, values) in enumerate(rows.items()):
        for col, value in enumerate(values):
            setattr(m, field, value)
            img = r.render(spp=args.spp)
            x, y = col * args.size, row * (args.size + 14)
            sheet.paste(Image.fromarray(to_srgb8(img)), (x, y + 14))
            draw.text((x + 2, y + 1), f"{field} {value[0]:.2f}", fill="black")
        setattr(m, field, original[field])
    sheet.save(args.output)
    print(f"wrote {args.output}: {len(rows)} x 5 renders of materials/{args.material}, "
          f"{r.info['program_builds']} programs rebuilt")


if __name__ == "__main__":
    main()
