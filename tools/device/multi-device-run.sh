#!/usr/bin/env bash
# On the GPU node (through the device tool, carrying .deps/): builds the bare configuration with
# the bench tools, runs the chunk, multi-device and instanced-path tests there (GPU + PoCL), then times
# --device gpu, cpu and all at 1024^2 (the default 64-sample chunks) on the Cornell box, the dragon and the generated
# 5.2M-triangle scene (geocold-large-mesh), two rounds each; on the first two also chunk sizes
# of 128 and one chunk (the per-chunk cost). Prints each run's samples/s line, each device's
# chunks, busy time and last-chunk time (-v) and the image hashes.
# Usage: OUT=<folder> tools/device/multi-device-run.sh [build|runs|all (default)] [scenes, default:
# cornell dragon large]; ROUNDS (default 2) rounds of each scene's runs; MULTI_DEVICE_QUICK=1 runs
# only gpu, cpu and all (no chunk-size variants).
set -uo pipefail
log=$OUT/run.log
what=${1:-all}
[ $# -eq 0 ] || shift
if [ "$what" != runs ]; then
# The Python module too, so that tools/device/python-parity.sh (PY_BUILD_DIR=build/bare) finds it built.
GEOCOLD_CMAKE_ARGS="-DGEOCOLD_BUILD_BENCH=ON -DGEOCOLD_PYTHON=ON -DPython_EXECUTABLE=$(command -v python3) -Dnanobind_DIR=$(python3 -m nanobind --cmake_dir)" \
  tools/device/build-and-test.sh \
  -R 'chunks_test|multi_device_test|MultiDevice|ChunkHandoff|AddsTooLittle|BackupGain|ChunkPlan|FrameAcc|PartialImage|MeanFilm|AskSize|InstancedRender' > "$OUT/build.log" 2>&1
echo "build+tests rc=$?" | tee -a "$log"
grep -E "tests passed|Failed|FAILED" "$OUT/build.log" | tail -8 >> "$log"
fi
[ "$what" != build ] || exit 0
cli=build/bare/geocold-cl
$cli --list-devices | tee -a "$log"
export GEOCOLD_CACHE_DIR=/tmp/kcache
source tools/device/frame-scenes.sh
run() {  # label, args...
  local label=$1; shift
  $cli "$@" -v -o /tmp/o.pfm > /tmp/r.log 2>&1; rc=$?
  echo "$label rc=$rc: $(grep -E 'wrote|error' /tmp/r.log)" | tee -a "$log"
  grep -E "device .*chunks|^geocold-cl: frame:" /tmp/r.log | sed 's/^/    /' | tee -a "$log"
  sha256sum /tmp/o.pfm | cut -c1-16 | sed "s/^/    hash /" | tee -a "$log"
}
scenes=${*:-cornell dragon large}
for scene in $scenes; do
  frame_scene $scene >> "$log" || continue
  case $scene in cornell) spp=2048 ;; dragon) spp=4096 ;; large) spp=1024 ;; esac
  # warm-up (kernel caches)
  $cli "${scene_args[@]}" --device all --res 256x256 --spp 64 -q -o /tmp/w.pfm
  for round in $(seq "${ROUNDS:-2}"); do
    run "$scene gpu   r$round" "${scene_args[@]}" --device gpu --res 1024x1024 --spp $spp
    run "$scene cpu   r$round" "${scene_args[@]}" --device cpu --threads 15 --res 1024x1024 --spp 64
    run "$scene all   r$round" "${scene_args[@]}" --device all --res 1024x1024 --spp $spp
    [[ $scene == large || ${MULTI_DEVICE_QUICK:-0} == 1 ]] && continue
    run "$scene gpu1chunk r$round" "${scene_args[@]}" --device gpu --res 1024x1024 --spp $spp --chunk-samples $spp
    run "$scene gpu c128 r$round" "${scene_args[@]}" --device gpu --res 1024x1024 --spp $spp --chunk-samples 128
    run "$scene all c128 r$round" "${scene_args[@]}" --device all --res 1024x1024 --spp $spp --chunk-samples 128
  done
done
