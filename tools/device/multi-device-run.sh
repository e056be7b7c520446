#!/usr/bin/env bash
# On the GPU node (through the device tool, carrying .deps/): builds the bare configuration,
# runs the chunk and multi-device tests there (GPU + PoCL), then times --device gpu, cpu and all
# on the Cornell box and the dragon at 1024^2, with chunk sizes 32, 128 and one chunk (the
# per-chunk cost), and prints each device's chunks, busy time and last-chunk time (-v) and
# the image hashes. Not yet run: no GPU node was lent when it was written (issue 41).
# Usage: OUT=<folder> tools/device/multi-device-run.sh
set -uo pipefail
log=$OUT/run.log
tools/device/build-and-test.sh -j 16 -R 'chunks_test|multi_device_test|MultiDevice|ChunkPlan|FrameAcc|PartialImage|MeanFilm|AskSize' > "$OUT/build.log" 2>&1
echo "build+tests rc=$?" | tee -a "$log"
grep -E "tests passed|Failed|FAILED" "$OUT/build.log" | tail -8 >> "$log"
cli=build/bare/geocold-cl
$cli --list-devices | tee -a "$log"
export GEOCOLD_CACHE_DIR=$OUT/../kcache
cornell=scenes/cornell-box/CornellBox-Original.obj
dragon=.deps/shared/scenes/stanford-dragon-100k/dragon.obj
run() {  # label, args...
  local label=$1; shift
  $cli "$@" -v -o /tmp/o.pfm > /tmp/r.log 2>&1; rc=$?
  echo "$label rc=$rc: $(grep 'wrote' /tmp/r.log)" | tee -a "$log"
  grep "device .*chunks" /tmp/r.log | sed 's/^/    /' | tee -a "$log"
  sha256sum /tmp/o.pfm | cut -c1-16 | sed "s/^/    hash /" | tee -a "$log"
}
for scene in cornell dragon; do
  s=$cornell; [[ $scene == dragon ]] && s=$dragon
  spp=2048; [[ $scene == dragon ]] && spp=4096
  # warm-up (kernel caches)
  $cli $s --device all --res 256x256 --spp 64 -q -o /tmp/w.pfm
  for round in 1 2; do
    run "$scene gpu   r$round" $s --device gpu --res 1024x1024 --spp $spp --chunk-samples 32
    run "$scene cpu   r$round" $s --device cpu --threads 15 --res 1024x1024 --spp 32 --chunk-samples 32
    run "$scene all   r$round" $s --device all --res 1024x1024 --spp $spp --chunk-samples 32
    run "$scene gpu1chunk r$round" $s --device gpu --res 1024x1024 --spp $spp --chunk-samples $spp
    run "$scene gpu c128 r$round" $s --device gpu --res 1024x1024 --spp $spp --chunk-samples 128
    run "$scene all c128 r$round" $s --device all --res 1024x1024 --spp $spp --chunk-samples 128
  done
done
