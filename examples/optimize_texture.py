"""Recover a glTF model's base-colour texture from renders under an environment (Renderer.backward).

    python examples/optimize_texture.py [--device any] [--res 96] [--iterations 60] [-o out]

The Khronos BoxTextured model under a constant white environment, seen from three sides.
The texture starts flat grey; each iteration renders one view at 4 spp, takes the image
MSE's gradient with respect to the texels (textures/0/texels) and steps them with Adam.
Writes <out>-loss.png and <out>-images.png (before, target, after, of the first view) and
prints the image error (RMS over the views at the targets' sample count) before and after.
The texels themselves are not all recoverable: the texture repeats up to six times across a
face, so a pixel sees several texels and the images constrain their blend.
"""

import argparse
import pathlib

import numpy as np

import geocold as gc
from inverse_rendering import Adam, write_images, write_loss_curve

HERE = pathlib.Path(__file__).resolve().parent
SCENE = HERE.parent / "tests" / "data" / "scenes" / "box-textured" / "BoxTextured.gltf"
VIEWS = [(1.6, 1.2, 2.0), (-2.0, 1.2, 1.6), (0.4, -1.8, -2.0)]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--device", default="any")
    ap.add_argument("--res", type=int, default=96)
    ap.add_argument("--iterations", type=int, default=60)
    ap.add_argument("--lr", type=float, default=0.05)
    ap.add_argument("--spp", type=int, default=4)
    ap.add_argument("--target-spp", type=int, default=64)
    ap.add_argument("-o", "--output", default="texture")
    args = ap.parse_args()

    scene = gc.load(SCENE, look_at=(0, 0, 0), up=(0, 1, 0), fov=40)
    key = next(k for k in scene.params.differentiable() if k.startswith("textures/"))
    r = gc.Renderer(scene, device=args.device, res=(args.res, args.res), env=1.0, max_depth=3, seed=0)

    def view(i):
        scene.camera.look_from = VIEWS[i % len(VIEWS)]

    truth = np.array(scene.params[key], dtype=np.float32)

    def renders():
        out = []
        for i in range(len(VIEWS)):
            view(i)
            out.append(r.render(spp=args.target_spp)[..., :3].copy())
        return out

    def image_error(images):
        return float(np.sqrt(np.mean([(a - t) ** 2 for a, t in zip(images, targets)])))

    targets = renders()
    texels = np.full_like(truth, 0.5)
    texels[..., 3] = truth[..., 3]
    scene.params[key] = texels
    before = renders()

    adam = Adam(args.lr)
    losses = []
    for it in range(args.iterations):
        view(it)
        scene.params[key] = texels
        img = r.render(spp=args.spp)[..., :3]
        target = targets[it % len(VIEWS)]
        losses.append(float(np.mean((img - target) ** 2)))
        grad = r.backward(2 * (img - target) / img.size, [key], spp=args.spp, seed=1000 + it)[key]
        texels = np.clip(adam.step(texels, grad), 0.0, 1.0).astype(np.float32)
        if it % 10 == 0 or it == args.iterations - 1:
            print(f"iteration {it:3d}: loss {losses[-1]:.6f}")
    scene.params[key] = texels
    after = renders()

    print(f"image error (RMS): before {image_error(before):.5f}, after {image_error(after):.5f}")
    write_loss_curve(f"{args.output}-loss.png", losses)
    write_images(f"{args.output}-images.png", [before[0], targets[0], after[0]])


if __name__ == "__main__":
    main()
