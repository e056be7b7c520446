#!/usr/bin/env bash
# Every GPU recipe in one device call (the tool's limit is 10 minutes a call, 8 files back), in
# the order of what the open issues still need when the call's time runs short:
#   1. the bare build with the bench tools and the Python module (multi-device-run.sh build,
#      which also runs the chunk, multi-device and instanced-render tests on the GPU);
#   2. the 10^6-dragon instancing preview and path trace (issue 45);
#   3. the megakernel forced on the GPU with and without textures (issue 43's textured-adjoint
#      fault: the adjoint's own, or any one-kernel path's with textures?);
#      GEOCOLD_SKIP_ANSWERED=1 leaves 2 and 3 out, their questions being answered;
#   4. the gradients against Mitsuba (gradients.sh, with Mitsuba where
#      `GEOCOLD_PACK_MITSUBA=1 tools/device/prepare-deps.sh` carried it; issue 43);
#   5. one round of the multi-device runs (issue 41);
#   6. the Sobol sampler's cost against the independent one (GEOCOLD_SKIP_SAMPLER_COST=1 leaves it out);
#   7. the Python/CLI parity (python-parity.sh; GEOCOLD_SKIP_PYTHON=1 leaves it out) and, with
#      the time left, a second round of the multi-device runs.
# Each step has its own time limit within GEOCOLD_SESSION_SECONDS (default 560); the logs end
# up in one archive, $OUT/all.tgz, and steps.log in it says how each step ended and when.
# Usage (through the device tool, carrying .deps): OUT=<folder> tools/device/gpu-session.sh
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
budget=${GEOCOLD_SESSION_SECONDS:-560}
began=$(date +%s)
elapsed() { echo $(( $(date +%s) - began )); }
left() { echo $(( budget - $(elapsed) )); }
step() { echo "[$(elapsed)s] $*" | tee -a "$OUT/steps.log"; }
source tools/device/frame-scenes.sh
frame_scene dragon
dragon=${scene_args[0]}

tools/device/multi-device-run.sh build
step "build: $(head -2 "$OUT/run.log" | tr '\n' ' ')"

if [ "${GEOCOLD_SKIP_ANSWERED:-0}" != 1 ]; then
    timeout 40 build/bare/geocold-instances --mesh $dragon --instances 1000000 --device gpu --size 640x480 \
        --out "$OUT/dragons.pfm" > "$OUT/instances.log" 2>&1
    step "instances rc=$?"
    timeout 60 build/bare/geocold-instances --mesh $dragon --instances 1000000 --device gpu --size 640x480 --spp 16 \
        --out "$OUT/dragons-path.pfm" > "$OUT/instances-path.log" 2>&1
    step "instances, path traced rc=$?"

    for s in tests/data/scenes/box-textured/BoxTextured.gltf scenes/cornell-box/CornellBox-Original.obj; do
        GEOCOLD_PATH_KERNEL=megakernel timeout 30 build/bare/geocold-cl "$s" --device gpu --res 64x64 --spp 4 \
            --env 1,1,1 -o /tmp/mk.pfm > /tmp/mk.log 2>&1
        echo "megakernel on the GPU, $(basename "$s"): rc=$? $(tail -1 /tmp/mk.log)" >> "$OUT/megakernel-gpu.log"
    done
    step "megakernel on the GPU: $(tr '\n' ' ' < "$OUT/megakernel-gpu.log")"
fi

if [ "$(left)" -gt 60 ]; then
    grad_time=$(( $(left) > 400 ? $(left) - 180 : $(left) * 11 / 20 ))
    GEOCOLD_GRAD_REPEATS=3 timeout "$grad_time" tools/device/gradients.sh > /dev/null 2>&1
    step "gradients rc=$? (limit ${grad_time}s)"
fi
if [ "$(left)" -gt 40 ]; then
    ROUNDS=1 timeout $(( $(left) > 190 ? 170 : $(left) - 20 )) tools/device/multi-device-run.sh runs > "$OUT/runs.out" 2>&1
    step "multi-device runs rc=$?"
fi
# The Sobol sampler's cost on the GPU: the Cornell box and the dragon, independent and sobol
# alternated, three rounds (docs/performance.md reads the samples/s lines).
for round in 1 2 3; do
    [ "${GEOCOLD_SKIP_SAMPLER_COST:-0}" != 1 ] && [ "$(left)" -gt 25 ] || break
    for sampler in independent sobol; do
        for name in cornell dragon; do
            frame_scene $name
            echo "r$round $sampler $name: $(timeout 30 build/bare/geocold-cl "${scene_args[@]}" --device gpu --res 1024x1024 \
                --spp 1024 --sampler $sampler -v -o /tmp/sampler.pfm 2>&1 | grep -E 'samples/s|error')" >> "$OUT/sampler.log"
        done
    done
done
step "sampler cost"
if [ "${GEOCOLD_SKIP_PYTHON:-0}" != 1 ] && [ "$(left)" -gt 60 ]; then
    PY_BUILD_DIR=build/bare timeout 150 tools/device/python-parity.sh > "$OUT/py.log" 2>&1
    step "python parity rc=$? ($(tail -1 "$OUT/py.log"))"
fi
if [ "$(left)" -gt 25 ]; then
    ROUNDS=1 timeout $(( $(left) - 15 )) tools/device/multi-device-run.sh runs > "$OUT/runs2.out" 2>&1
    step "multi-device runs, second round rc=$?"
fi
archive=$(mktemp -d)/all.tgz
(cd "$OUT" && tar czf "$archive" . && rm -rf ./* && mv "$archive" .)
ls -la "$OUT"
