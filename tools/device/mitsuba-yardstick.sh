#!/usr/bin/env bash
# On the GPU node, after tools/bench/gpu.sh (or anything that built build/bare's geocold-bench
# and geocold-cl): Mitsuba 3 against geocold-bench in the same run
# (tools/bench/mitsuba_yardstick.py), with the Mitsuba that tools/device/prepare-deps.sh packed
# (GEOCOLD_PACK_MITSUBA=1) into .deps/mitsuba/site.tar.xz:
#   1. llvm_ad_rgb against PoCL on one thread (the issue's per-thread anchor's conditions);
#   2. llvm_ad_rgb against PoCL on every core;
#   3. cuda_ad_rgb against NVIDIA OpenCL on the GPU;
#   and on request (GEOCOLD_YARDSTICK_STEPS) the CPU steps with Mitsuba held to AVX2.
# Dr.Jit's LLVM back end needs a libLLVM >= 17: the first one found on the node, or
# DRJIT_LIBLLVM_PATH. Text to $OUT/yardstick.txt, JSON to $OUT/yardstick-*.json.
# Usage: tools/device/mitsuba-yardstick.sh [extra mitsuba_yardstick.py args, e.g. --rounds 3]
# Exit status: the first failing step's, after running every step.
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
out=${OUT:-$root/out}
mkdir -p "$out"
bench=${BUILD_DIR:-build/bare}/geocold-bench
[ -x "$bench" ] || { echo "$bench not built: run tools/bench/gpu.sh first" >&2; exit 2; }
[ -f .deps/mitsuba/site.tar.xz ] || { echo "no .deps/mitsuba: GEOCOLD_PACK_MITSUBA=1 tools/device/prepare-deps.sh" >&2; exit 2; }
site=${TMPDIR:-/tmp}/geocold-mitsuba-site
[ -d "$site/mitsuba" ] || { mkdir -p "$site" && xz -dc .deps/mitsuba/site.tar.xz | tar -C "$site" -xf -; }
export PYTHONPATH="$site${PYTHONPATH:+:$PYTHONPATH}"
[ -n "${GEOCOLD_SHARED_DIR:-}" ] || [ ! -d .deps/shared/scenes ] || export GEOCOLD_SHARED_DIR="$root/.deps/shared"
# A bench built with the carried Embree (tools/device/build-and-test.sh) loads it from there.
# shellcheck source=tools/device/embree-env.sh
source "$root/tools/device/embree-env.sh"

if [ -z "${DRJIT_LIBLLVM_PATH:-}" ]; then
    for lib in $(ldconfig -p | awk '/libLLVM/{print $NF}') /usr/lib/llvm-*/lib/libLLVM*.so*; do
        v=$(basename "$lib" | grep -oE '[0-9]+' | head -1)
        if [ -f "$lib" ] && [ "${v:-0}" -ge 17 ]; then export DRJIT_LIBLLVM_PATH="$lib"; break; fi
    done
fi
{
    echo "# Mitsuba yardstick on $(hostname), $(date -u +%FT%TZ), $(nproc) CPU threads, libLLVM: ${DRJIT_LIBLLVM_PATH:-none found}"
} > "$out/yardstick.txt"
status=0
run() { # name, args...
    local name=$1
    shift
    python3 tools/bench/mitsuba_yardstick.py --bench "$bench" --json "$out/yardstick-$name.json" "$@" 2>&1 |
        grep -v "WARN" >> "$out/yardstick.txt"
    local s=${PIPESTATUS[0]}
    [ "$s" = 0 ] || { echo "  ($name: exit $s)" >> "$out/yardstick.txt"; [ "$status" != 0 ] || status=$s; }
    [ "$s" != 0 ] || succeeded="$succeeded$name "
}
succeeded=" "  # the steps whose JSON this run wrote
# GEOCOLD_YARDSTICK_STEPS picks steps; the -avx2 ones pin Mitsuba to eight lanes
# (--mitsuba-lanes 8), which tells how much of a CPU ratio is Dr.Jit's 16 AVX-512 lanes.
for step in ${GEOCOLD_YARDSTICK_STEPS:-cpu-1 cpu-all gpu}; do
    case $step in
    cpu-1) run "$step" --device cpu --threads 1 "$@" ;;
    cpu-all) run "$step" --device cpu "$@" ;;
    cpu-1-avx2) run "$step" --device cpu --threads 1 --mitsuba-lanes 8 "$@" ;;
    cpu-all-avx2) run "$step" --device cpu --mitsuba-lanes 8 "$@" ;;
    gpu) run "$step" --device gpu "$@" ;;
    *) echo "unknown step '$step' in GEOCOLD_YARDSTICK_STEPS" >&2; exit 2 ;;
    esac
done
# Where both a one-thread and an every-core step ran: how much each side grew between them
# (a ratio that falls with the thread count is then a scaling loss, not a one-thread figure).
for lanes in "" -avx2; do
    if [[ $succeeded == *" cpu-1$lanes "* && $succeeded == *" cpu-all$lanes "* ]]; then
        python3 tools/bench/yardstick_scaling.py "$out/yardstick-cpu-1$lanes.json" "$out/yardstick-cpu-all$lanes.json" \
            >> "$out/yardstick.txt" 2>&1
    fi
done
cat "$out/yardstick.txt"
exit "$status"
