"""Render a scene into a numpy array, look at it, and write it.

    python examples/render_to_numpy.py [scene.obj] [--device any] [--spp 64] [-o out.exr]
"""

import argparse
import pathlib

import numpy as np

import geocold as gc

HERE = pathlib.Path(__file__).resolve().parent
DEFAULT_SCENE = HERE.parent / "scenes" / "cornell-box" / "CornellBox-Original.obj"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", nargs="?", default=str(DEFAULT_SCENE))
    ap.add_argument("--device", default="any")
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--res", type=int, nargs=2, default=(256, 256), metavar=("W", "H"))
    ap.add_argument("-o", "--output", default="render.exr")
    args = ap.parse_args()

    for d in gc.devices():
        print(f"device {d.index}: {d.kind} {d.name} ({d.platform})")
    scene = gc.load(args.scene)
    print(scene, scene.camera)
    r = gc.Renderer(scene, device=args.device, integrator="path", res=tuple(args.res), max_depth=8, seed=0)

    # Half the samples, then the other half: the film continues (same bits as one call).
    img = r.render(spp=args.spp // 2, progress=lambda done, target: print(f"  {done}/{target} spp", end="\r"))
    img = r.render(spp=args.spp - args.spp // 2)
    print()
    assert isinstance(img, np.ndarray) and img.dtype == np.float32 and img.shape == (args.res[1], args.res[0], 4)
    luminance = img[..., :3] @ np.array([0.2126, 0.7152, 0.0722], np.float32)
    print(f"{r.sample_count} spp on {r.info['device']}: mean luminance {luminance.mean():.4f}, "
          f"max {luminance.max():.3f}, brightest pixel (row, col) {np.unravel_index(luminance.argmax(), luminance.shape)}")

    sums = r.sums()  # raw per-pixel sums: what a partial render hands on for merging
    print(f"sample counts {sums.sample_counts.min()}..{sums.sample_counts.max()}")

    albedo = gc.Renderer(scene, device=args.device, aov="albedo", res=tuple(args.res)).render()
    gc.write(args.output, img, metadata=r.metadata())
    gc.write(pathlib.Path(args.output).with_suffix(".albedo.png"), albedo, tonemap="clamp")
    print(f"wrote {args.output} and its albedo; read back: {gc.read(args.output).shape}")


if __name__ == "__main__":
    main()
