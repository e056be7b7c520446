#!/usr/bin/env bash
# Issue 42's run, on a node with one or more GPUs (through the device tool, carrying .deps/):
# builds the bare configuration with the bench tools, then renders one frame on the first N
# GPUs for N = 1, 2, 4, 8 (as many as the node has), the GPUs alone and with PoCL beside them,
# on the Cornell box at 1024x1024, the dragon and the generated 5.2M-triangle scene, ROUNDS
# times each; then prints the table of tools/device/scaling_table.py (samples per second,
# scaling efficiency T(1) / (N T(N)), the end-of-frame idle time, the frame's hash against the
# one-GPU frame's).
# Usage: OUT=<folder> tools/device/multi-gpu-scaling.sh [build|runs|all (default)] [scenes,
# default: cornell dragon large]; ROUNDS (default 3).
set -uo pipefail
log=$OUT/scaling.log
what=${1:-all}
[ $# -eq 0 ] || shift
if [ "$what" != runs ]; then
  GEOCOLD_CMAKE_ARGS="-DGEOCOLD_BUILD_BENCH=ON" tools/device/build-and-test.sh -R 'multi_device_test|chunks_test' \
    > "$OUT/build.log" 2>&1
  echo "build+tests rc=$?" | tee -a "$log"
  grep -E "tests passed|Failed|FAILED" "$OUT/build.log" | tail -4 >> "$log"
fi
[ "$what" != build ] || exit 0

cli=build/bare/geocold-cl
export GEOCOLD_CACHE_DIR=/tmp/kcache
source tools/device/frame-scenes.sh
$cli --list-devices | tee -a "$log"
# `--list-devices` rows: index, type, name...; GPUs in index order, and PoCL's CPU device.
gpus=($($cli --list-devices | awk '$2 == "gpu" {print $1}'))
pocl=$($cli --list-devices | awk '$2 == "cpu" && /Portable Computing Language/ {print $1; exit}')
[ ${#gpus[@]} -gt 0 ] || { echo "no GPU listed" | tee -a "$log"; exit 3; }

runs=$OUT/runs
mkdir -p "$runs"
for scene in ${*:-cornell dragon large}; do
  frame_scene $scene >> "$log" || continue
  case $scene in cornell) spp=2048 ;; dragon|large) spp=4096 ;; esac
  $cli "${scene_args[@]}" --device all --res 256x256 --spp 64 -q -o /tmp/warm.pfm  # kernel caches
  for n in 1 2 4 8; do
    [ $n -le ${#gpus[@]} ] || break
    set_gpus=$(IFS=,; echo "${gpus[*]:0:$n}")
    for round in $(seq "${ROUNDS:-3}"); do
      for with in gpus gpus-pocl; do
        devices=$set_gpus
        if [ $with = gpus-pocl ]; then [ -n "$pocl" ] || continue; devices=$set_gpus,$pocl; fi
        name=$scene.$with.$n.r$round
        $cli "${scene_args[@]}" --device "$devices" --res 1024x1024 --spp $spp -v -o /tmp/frame.pfm > "$runs/$name.log" 2>&1
        echo "rc=$?" >> "$runs/$name.log"
        echo "hash $(sha256sum /tmp/frame.pfm | cut -c1-16)" >> "$runs/$name.log"
        echo "$name: $(grep -E 'Msamples/s|error' "$runs/$name.log")" | tee -a "$log"
      done
    done
  done
done
python3 tools/device/scaling_table.py "$runs" | tee -a "$log"
