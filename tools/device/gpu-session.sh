#!/usr/bin/env bash
# Every GPU recipe in one device call (the tool's limit is 10 minutes a call, 8 files back):
# the bare build with the bench tools and the Python module (multi-device-run.sh build), the
# Python/CLI parity (python-parity.sh), one round of the multi-device runs, the 10^6-dragon
# instancing preview and path trace, the Sobol sampler's cost, the gradients against Mitsuba (gradients.sh, with Mitsuba where
# `GEOCOLD_PACK_MITSUBA=1 tools/device/prepare-deps.sh` carried it) and, with the time left, a
# second round of the multi-device runs. Each step has its own time limit; the logs end up in
# one archive, $OUT/all.tgz, and steps.log in it says how each step ended and when.
# Usage (through the device tool, carrying .deps): OUT=<folder> tools/device/gpu-session.sh
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
budget=${GEOCOLD_SESSION_SECONDS:-560}
began=$(date +%s)
elapsed() { echo $(( $(date +%s) - began )); }
left() { echo $(( budget - $(elapsed) )); }
step() { echo "[$(elapsed)s] $*" | tee -a "$OUT/steps.log"; }

tools/device/multi-device-run.sh build
step "build: $(head -2 "$OUT/run.log" | tr '\n' ' ')"
PY_BUILD_DIR=build/bare timeout 150 tools/device/python-parity.sh > "$OUT/py.log" 2>&1
step "python parity rc=$? ($(tail -1 "$OUT/py.log"))"
ROUNDS=1 timeout 170 tools/device/multi-device-run.sh runs > "$OUT/runs.out" 2>&1
step "multi-device runs rc=$?"
timeout 40 build/bare/geocold-instances --mesh .deps/shared/scenes/stanford-dragon-100k/dragon.obj \
    --instances 1000000 --device gpu --size 640x480 --out "$OUT/dragons.pfm" > "$OUT/instances.log" 2>&1
step "instances rc=$?"
timeout 60 build/bare/geocold-instances --mesh .deps/shared/scenes/stanford-dragon-100k/dragon.obj \
    --instances 1000000 --device gpu --size 640x480 --spp 16 --out "$OUT/dragons-path.pfm" \
    > "$OUT/instances-path.log" 2>&1
step "instances, path traced rc=$?"
# The Sobol sampler's cost on the GPU: the Cornell box and the dragon, independent and sobol
# alternated, three rounds (docs/performance.md reads the samples/s lines).
for round in 1 2 3; do
    for sampler in independent sobol; do
        for s in scenes/cornell-box/CornellBox-Original.obj .deps/shared/scenes/stanford-dragon-100k/dragon.obj; do
            echo "r$round $sampler $(basename "$s"): $(timeout 30 build/bare/geocold-cl "$s" --device gpu --res 1024x1024 \
                --spp 1024 --sampler $sampler -v -o /tmp/sampler.pfm 2>&1 | grep -E 'samples/s|error')" >> "$OUT/sampler.log"
        done
    done
done
step "sampler cost rc=$?"
# Issue 43's textured-adjoint fault: is it the adjoint, or any one-kernel path (the adjoint's
# form) with textures on NVIDIA? The megakernel forced on the GPU, textured and not.
for s in tests/data/scenes/box-textured/BoxTextured.gltf scenes/cornell-box/CornellBox-Original.obj; do
    GEOCOLD_PATH_KERNEL=megakernel timeout 30 build/bare/geocold-cl "$s" --device gpu --res 64x64 --spp 4 \
        --env 1,1,1 -o /tmp/mk.pfm > /tmp/mk.log 2>&1
    echo "megakernel on the GPU, $(basename "$s"): rc=$? $(tail -1 /tmp/mk.log)" >> "$OUT/megakernel-gpu.log"
done
step "megakernel on the GPU: $(tr '\n' ' ' < "$OUT/megakernel-gpu.log")"
if [ "$(left)" -gt 30 ]; then
    GEOCOLD_GRAD_REPEATS=3 timeout "$(left)" tools/device/gradients.sh > /dev/null 2>&1
    step "gradients rc=$?"
fi
if [ "$(left)" -gt 25 ]; then
    ROUNDS=1 timeout $(( $(left) - 15 )) tools/device/multi-device-run.sh runs > "$OUT/runs2.out" 2>&1
    step "multi-device runs, second round rc=$?"
fi
archive=$(mktemp -d)/all.tgz
(cd "$OUT" && tar czf "$archive" . && rm -rf ./* && mv "$archive" .)
ls -la "$OUT"
