#!/usr/bin/env bash
# On the GPU device machine, after tools/device/build-and-test.sh has built the `bare` preset:
# adds geocold-bench to that build (GEOCOLD_BUILD_BENCH is OFF in the preset; the bench needs
# neither Embree nor OpenImageIO) and runs it on every OpenCL device there (NVIDIA OpenCL and
# PoCL), text to $OUT/bench.txt, the JSON document to $OUT/bench.json.
# Usage: tools/bench/gpu.sh [extra geocold-bench args, e.g. --scene cornell,dragon]
# The bunny and the dragon are read from $GEOCOLD_SHARED_DIR, ./shared or ../shared (skipped
# with a note when absent); the Cornell box and the generated 5M-triangle scene always run.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
out=${OUT:-$root/out}
mkdir -p "$out"
[ -f build/bare/CMakeCache.txt ] || { echo "build/bare is not configured: run tools/device/build-and-test.sh first" >&2; exit 2; }

# A bench built with the carried Embree (tools/device/build-and-test.sh) loads it from there.
# Unpacked before the configure too: a later call's carry replaces .deps/ and with it the
# unpacked library, which Embree's CMake files then reject.
# shellcheck source=tools/device/embree-env.sh
source "$root/tools/device/embree-env.sh"
cmake -S . -B build/bare -DGEOCOLD_BUILD_BENCH=ON > "$out/bench-configure.log"
cmake --build build/bare --target geocold-bench -j "$(nproc)" > "$out/bench-build.log" 2>&1 ||
    { tail -50 "$out/bench-build.log" >&2; exit 3; }

if [ -z "${GEOCOLD_SHARED_DIR:-}" ]; then
    for d in "$root/shared" "$root/../shared"; do
        if [ -d "$d/scenes" ]; then export GEOCOLD_SHARED_DIR="$d"; break; fi
    done
fi
{
    echo "# geocold-bench on $(hostname), $(date -u +%FT%TZ), $(nproc) CPU threads"
    command -v nvidia-smi > /dev/null && nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv,noheader
    ./build/bare/geocold-cl --list-devices
} > "$out/bench.txt" 2>&1 || true
# Leave room under the device tool's 10-minute command limit for the A/B runs and transfers.
status=0
timeout "${GEOCOLD_BENCH_TIMEOUT:-420}" ./build/bare/geocold-bench --json "$@" > "$out/bench.json" 2>> "$out/bench.txt" || status=$?
# A/B of the wavefront's scheduling knobs, path tracing only, on every device, so the defaults
# can be chosen per device from data: the counter read-back (on by default on CPUs, off on
# GPUs) and the launch widths after the first bounce (GPUs size them from the last batch;
# GEOCOLD_WAVEFRONT_GRID=N fixes N work-items per compute unit instead, 0 one per slot).
if [ "${GEOCOLD_BENCH_AB:-1}" = 1 ]; then
    for setting in GEOCOLD_WAVEFRONT_SYNC=0 GEOCOLD_WAVEFRONT_SYNC=1 GEOCOLD_WAVEFRONT_GRID=0 \
        GEOCOLD_WAVEFRONT_GRID=4096; do
        echo "== A/B: $setting (path tracing only)" >> "$out/bench.txt"
        env "$setting" timeout 90 ./build/bare/geocold-bench --scene cornell,dragon,large --no-rays \
            --no-first-image --repeats 3 2>&1 | grep -E "path|error" >> "$out/bench.txt" || true
    done
fi
cat "$out/bench.txt"
exit $status
