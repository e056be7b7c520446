"""Recover the Cornell box's red wall from a target image by gradient descent (Renderer.backward).

    python examples/optimize_wall_colour.py [--device any] [--res 128] [--iterations 50] [-o out]

Mitsuba 3's inverse-rendering tutorial set-up: the left wall's base colour starts blue, the
loss is the image MSE against a render with the true colour, and Adam (lr 0.05) steps the
colour from the gradients of a 4-spp render with 4 samples of its own seed. Writes
<out>-loss.png (the loss curve) and <out>-images.png (before, target, after) and prints the
colour error, sum over RGB of the squared difference.
"""

import argparse
import pathlib

import numpy as np

import geocold as gc
from inverse_rendering import Adam, write_images, write_loss_curve

HERE = pathlib.Path(__file__).resolve().parent
SCENE = HERE.parent / "scenes" / "cornell-box" / "CornellBox-Original.obj"
WALL = "materials/leftWall/base_color"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--device", default="any")
    ap.add_argument("--res", type=int, default=128)
    ap.add_argument("--iterations", type=int, default=50)
    ap.add_argument("--lr", type=float, default=0.05)
    ap.add_argument("--spp", type=int, default=4)
    ap.add_argument("--target-spp", type=int, default=256)
    ap.add_argument("-o", "--output", default="wall")
    args = ap.parse_args()

    scene = gc.load(SCENE)
    res = (args.res, args.res)
    r = gc.Renderer(scene, device=args.device, res=res, max_depth=6, seed=0)
    truth = np.array(scene.params[WALL], dtype=np.float32)
    target = r.render(spp=args.target_spp)[..., :3].copy()

    colour = np.array([0.01, 0.2, 0.9], dtype=np.float32)
    scene.params[WALL] = tuple(colour)
    before = r.render(spp=args.target_spp)[..., :3].copy()
    adam = Adam(args.lr)
    losses = []
    for it in range(args.iterations):
        scene.params[WALL] = tuple(colour)
        r.clear()
        img = r.render(spp=args.spp)[..., :3]
        losses.append(float(np.mean((img - target) ** 2)))
        loss_grad = 2 * (img - target) / img.size
        # The gradient's own seed, new each step: an unbiased estimate of d loss / d colour.
        grad = r.backward(loss_grad, [WALL], spp=args.spp, seed=1000 + it)[WALL]
        colour = np.clip(adam.step(colour, grad), 0.0, 1.0).astype(np.float32)
        if it % 10 == 0 or it == args.iterations - 1:
            print(f"iteration {it:3d}: loss {losses[-1]:.6f}, colour {np.round(colour, 4)}")
    scene.params[WALL] = tuple(colour)
    r.clear()
    after = r.render(spp=args.target_spp)[..., :3]

    error = float(np.sum((colour - truth) ** 2))
    print(f"true colour {np.round(truth, 4)}, recovered {np.round(colour, 4)}, colour error {error:.6f}")
    write_loss_curve(f"{args.output}-loss.png", losses)
    write_images(f"{args.output}-images.png", [before, target, after])


if __name__ == "__main__":
    main()
