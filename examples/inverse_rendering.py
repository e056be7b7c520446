"""What the inverse-rendering examples share: Adam, and PNGs of images and of a loss curve."""

import numpy as np
from PIL import Image, ImageDraw


class Adam:
    """Adam (Kingma & Ba 2015) on one array."""

    def __init__(self, lr, beta1=0.9, beta2=0.999, eps=1e-8):
        self.lr, self.beta1, self.beta2, self.eps = lr, beta1, beta2, eps
        self.m = self.v = None
        self.t = 0

    def step(self, x, grad):
        if self.m is None:
            self.m, self.v = np.zeros_like(x), np.zeros_like(x)
        self.t += 1
        self.m = self.beta1 * self.m + (1 - self.beta1) * grad
        self.v = self.beta2 * self.v + (1 - self.beta2) * grad * grad
        m_hat = self.m / (1 - self.beta1 ** self.t)
        v_hat = self.v / (1 - self.beta2 ** self.t)
        return x - self.lr * m_hat / (np.sqrt(v_hat) + self.eps)


def write_images(path, images):
    """Linear RGB images side by side, sRGB-encoded, clipped at 1."""
    row = np.concatenate([np.asarray(i)[..., :3] for i in images], axis=1)
    Image.fromarray((np.clip(row, 0, 1) ** (1 / 2.2) * 255).astype(np.uint8)).save(path)


def write_loss_curve(path, losses, size=(320, 200)):
    """log10 of the losses against the iteration."""
    im = Image.new("RGB", size, "white")
    draw = ImageDraw.Draw(im)
    logs = np.log10(np.maximum(np.asarray(losses, dtype=np.float64), 1e-12))
    lo, hi = logs.min(), max(logs.max(), logs.min() + 1e-6)
    points = [(10 + i * (size[0] - 20) / max(len(logs) - 1, 1), size[1] - 10 - (v - lo) / (hi - lo) * (size[1] - 20))
              for i, v in enumerate(logs)]
    draw.line(points, fill="black", width=2)
    draw.text((12, 4), f"log10 loss {hi:.2f} .. {lo:.2f}", fill="black")
    im.save(path)
