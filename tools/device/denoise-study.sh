#!/usr/bin/env bash
# The denoising figure (docs/performance.md, "Denoising") at sizes whose references would take
# the 2-core VM hours. On the GPU node, DamagedHelmet under a white sky at each size in SIZES
# (default 256 512 1024): a reference of REF_SPP samples (default 16384), the 16- and 256-spp
# images and --denoise's guides (albedo and normal AOVs of 64 samples, as
# host/render/denoise_guides.h renders them), packed as float16 into $OUT/denoise-<size>.npz.
# Open Image Denoise is not on the node (its library is over the transfer limit), so
# tools/device/denoise_table.py denoises and scores them on the VM with --denoise's settings.
#   Here:     tools/device/prepare-deps.sh     (packs the helmet into .deps)
#   The node: tools/device/denoise-study.sh    (carry .deps; about 60 s on an H100)
#   Here:     /opt/geocold-cl/oidn-venv/bin/python tools/device/denoise_table.py FILES_AT/denoise-*.npz
set -euo pipefail
cd "$(dirname "$0")/../.."
scene=.deps/shared/scenes/damaged-helmet/DamagedHelmet.glb
[ -f "$scene" ] || { echo "missing $scene: run tools/device/prepare-deps.sh here and carry .deps" >&2; exit 2; }
out=${OUT:?OUT must name the folder the results go to}
nvidia-smi --query-gpu=name --format=csv,noheader | tee "$out/gpu.txt"
# shellcheck source=tools/device/configure-bare.sh
source tools/device/configure-bare.sh
configure_bare build/bare -DGEOCOLD_BUILD_TESTS=OFF > "$out/build.log" 2>&1
cmake --build build/bare --target geocold-cl -j "$(nproc)" >> "$out/build.log" 2>&1
cli=build/bare/geocold-cl
export GEOCOLD_CACHE_DIR=/tmp/kcache
images=$(mktemp -d)
for size in ${SIZES:-256 512 1024}; do
  common=(-q --device gpu --res "${size}x$size" --env 1,1,1 "$scene")
  for spp in "${REF_SPP:-16384}" 16 256; do
    "$cli" "${common[@]}" --spp "$spp" -o "$images/spp$spp.pfm"
  done
  "$cli" "${common[@]}" --spp 64 --aov guide-albedo -o "$images/albedo.pfm"
  "$cli" "${common[@]}" --spp 64 --aov guide-normal -o "$images/normal.pfm"
  python3 - "$images" "$out/denoise-$size.npz" "${REF_SPP:-16384}" <<'PY'
import sys
import numpy as np
folder, packed, ref_spp = sys.argv[1], sys.argv[2], sys.argv[3]
def read_pfm(path):
    with open(path, 'rb') as f:
        f.readline()
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype='<f4' if scale < 0 else '>f4').reshape(height, width, 3)
    return data[::-1].astype(np.float16)  # PFM rows run bottom to top
names = {'reference': f'spp{ref_spp}', 'spp16': 'spp16', 'spp256': 'spp256', 'albedo': 'albedo', 'normal': 'normal'}
np.savez_compressed(packed, ref_spp=int(ref_spp), **{k: read_pfm(f'{folder}/{v}.pfm') for k, v in names.items()})
PY
  echo "packed $size x $size"
done
rm -rf "$images"
