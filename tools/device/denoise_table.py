"""Scores tools/device/denoise-study.sh's images: rel MSE against the reference (the metric of
geocold-imgdiff: squared difference over reference squared plus 1e-2, averaged over pixels and
channels) of the raw 16- and 256-spp images and of the 16-spp image denoised with the filter
settings of --denoise (host/image/denoise.cpp: RT filter, hdr, albedo and normal guides,
cleanAux, default quality). Needs pyoidn (/opt/geocold-cl/oidn-venv, tools/install-deps.sh).

Usage: python denoise_table.py denoise-256.npz [denoise-512.npz ...]
"""
import sys

import numpy as np
import pyoidn


def rel_mse(image, reference):
    return float(np.mean((image - reference) ** 2 / (reference ** 2 + 1e-2)))


def main(paths):
    print('| size | reference | 16 spp | 16 spp denoised | 256 spp | denoised 16 / raw 256 |')
    print('|---|---|---|---|---|---|')
    for path in paths:
        packed = np.load(path)
        image = {k: np.ascontiguousarray(packed[k], dtype=np.float32)
                 for k in ('reference', 'spp16', 'spp256', 'albedo', 'normal')}
        ref = image['reference']
        denoised = pyoidn.denoise(image['spp16'], image['albedo'], image['normal'], hdr=True, clean_aux=True)
        raw16, raw256, den16 = (rel_mse(x, ref) for x in (image['spp16'], image['spp256'], denoised))
        size = f'{ref.shape[1]}x{ref.shape[0]}'
        print(f'| {size} | {int(packed["ref_spp"])} spp | {raw16:.6f} | {den16:.6f} | {raw256:.6f} | {den16 / raw256:.1f}x |')


if __name__ == '__main__':
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
