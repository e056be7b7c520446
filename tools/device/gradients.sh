#!/usr/bin/env bash
# On the GPU node (issue 43 items 3 and 5): builds geocold-grad-bench and gradient_test with
# the `bare` preset and the carried .deps/ (tools/device/prepare-deps.sh), then
#   1. times one iteration (render + backward) of the Cornell box at 128x128 4+4 spp and
#      512x512 16+16 spp, depth 6, on the GPU and on PoCL, against Mitsuba 3 cuda_ad_rgb prb
#      in the same run where .deps/mitsuba is carried (GEOCOLD_PACK_MITSUBA=1; prb is one of
#      Mitsuba's Python integrators, so the plugin cut of prepare-deps.sh keeps it), else
#      geocold-grad-bench alone; then ours with other cuts of the adjoint's work (samples per
#      work-item, work-group sums); GEOCOLD_GRAD_SPEED_ONLY=1 stops there;
#   2. the peak OpenCL buffer bytes at depth 6 and depth 64 (our count; both in one process,
#      then each depth in a process of its own under nvidia-smi sampling the GPU's used memory (the driver's
#      figure, contexts and program binaries included);
#   3. gradient_test with GEOCOLD_TEST_DEVICE=gpu, then =cpu;
#   4. determinism: per device, two iterations' gradient bits (exit 1 where they differ),
#      and the largest relative difference between the GPU's and PoCL's (acceptance: 1e-5);
#   5. on NVIDIA, ptxas -v of the adjoint programs (registers, stack frame, spills).
# Everything goes to $OUT/gradients.txt (geocold-grad-bench's JSON lines among it), the
# build's output to $OUT/gradients-build.log, the Mitsuba comparisons' JSON to
# $OUT/gradients-prb-*.json. The bare preset leaves the bench tools out: GEOCOLD_BUILD_BENCH=ON
# adds them (as tools/bench/gpu.sh does); Embree is not needed by geocold-grad-bench.
# Usage: tools/device/gradients.sh [extra geocold-grad-bench args, e.g. --threads 8]
# BUILD_DIR overrides build/bare. To rehearse it off the node: GEOCOLD_GRAD_NO_BUILD=1 (use
# BUILD_DIR's geocold-grad-bench and gradient_test as they are), GEOCOLD_GRAD_GPU=cpu (the
# device spec that stands for the GPU; Mitsuba then runs llvm_ad_rgb), PYTHON (a Python with
# Mitsuba, where .deps/mitsuba is not carried), GEOCOLD_GRAD_SIZES and
# GEOCOLD_GRAD_MEMORY_SIZE (smaller sizes than 128:4,512:16 and 512:16). GEOCOLD_GRAD_REPEATS
# (default 5) is both sides' timed iterations; extra arguments go to geocold-grad-bench's own
# speed steps.
# Exit status: the first failing step's, after every step.
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
out=${OUT:-$root/out}
mkdir -p "$out"
log="$out/gradients.txt"
build=${BUILD_DIR:-build/bare}
gpu=${GEOCOLD_GRAD_GPU:-gpu}
py=${PYTHON:-python3}
sizes=${GEOCOLD_GRAD_SIZES:-128:4,512:16}
repeats=${GEOCOLD_GRAD_REPEATS:-5}
memory_size=${GEOCOLD_GRAD_MEMORY_SIZE:-512:16}
variant=cuda_ad_rgb
[ "$gpu" = gpu ] || variant=llvm_ad_rgb
no_build=${GEOCOLD_GRAD_NO_BUILD:-0}
[ "$no_build" = 1 ] || [ -d .deps/include ] || { echo "missing .deps/: run tools/device/prepare-deps.sh on a Debian machine and carry it" >&2; exit 2; }
# shellcheck source=tools/device/configure-bare.sh
source "$root/tools/device/configure-bare.sh"
node_opencl_loader > /dev/null || exit 4
status=0
step() { # name, command...: runs it with its output appended to the log, keeps the first failure
    local name=$1
    shift
    echo "== $name: $*" >> "$log"
    "$@" >> "$log" 2>&1
    local s=$?
    [ "$s" = 0 ] || { echo "  ($name: exit $s)" >> "$log"; [ "$status" != 0 ] || status=$s; }
    return "$s"
}
echo "# gradients on $(hostname), $(date -u +%FT%TZ), $(nproc) CPU threads" > "$log"
have_smi=0
command -v nvidia-smi > /dev/null && have_smi=1
[ "$have_smi" = 0 ] || nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader >> "$log" 2>&1

# The build: GoogleTest from the carried sources, as tools/device/build-and-test.sh does.
mkdir -p "$build"
build_abs=$(cd "$build" && pwd)
gtest_prefix="$build_abs/_gtest/install"
if [ "$no_build" = 1 ]; then
    echo "== no build (GEOCOLD_GRAD_NO_BUILD=1): $build_abs as it is" >> "$log"
elif [ ! -f "$gtest_prefix/lib/cmake/GTest/GTestConfig.cmake" ]; then
    cmake -S "$root/.deps/googletest" -B "$build_abs/_gtest/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
          -DCMAKE_INSTALL_PREFIX="$gtest_prefix" -DCMAKE_INSTALL_LIBDIR=lib -DBUILD_GMOCK=OFF -DINSTALL_GTEST=ON >/dev/null &&
        cmake --build "$build_abs/_gtest/build" -j "$(nproc)" >/dev/null &&
        cmake --install "$build_abs/_gtest/build" >/dev/null
fi
if [ "$no_build" != 1 ] && ! { configure_bare "$build" -DCMAKE_PREFIX_PATH="$gtest_prefix" -DGEOCOLD_GTEST_SOURCE_DIR="$root/.deps/googletest" -DGEOCOLD_BUILD_BENCH=ON &&
       cmake --build "$build" -j "$(nproc)" --target geocold-grad-bench gradient_test; } > "$out/gradients-build.log" 2>&1; then
    tail -30 "$out/gradients-build.log"
    exit 8
fi
bench="$build_abs/geocold-grad-bench"
"$bench" --help > /dev/null || exit 8

# 1. Speed: ours against Mitsuba's prb where it is carried (or PYTHON imports it).
if [ -f .deps/mitsuba/site.tar.xz ]; then
    site=${TMPDIR:-/tmp}/geocold-mitsuba-site
    [ -d "$site/mitsuba" ] || { mkdir -p "$site" && xz -dc .deps/mitsuba/site.tar.xz | tar -C "$site" -xf -; }
    export PYTHONPATH="$site${PYTHONPATH:+:$PYTHONPATH}"
fi
if "$py" -c "import mitsuba" 2> /dev/null; then
    for which in leftWall walls; do
        step "speed-$which-$gpu-vs-prb" "$py" tools/bench/mitsuba_prb_yardstick.py --grad-bench "$bench" --device "$gpu" \
            --variant "$variant" --sizes "$sizes" --repeats "$repeats" --params "$which" --json "$out/gradients-prb-$which.json"
    done
else
    echo "== no Mitsuba (GEOCOLD_PACK_MITSUBA=1 tools/device/prepare-deps.sh carries it): ours alone" >> "$log"
    step "speed-$gpu" "$bench" --device "$gpu" --sizes "$sizes" --repeats "$repeats" --no-memory "$@"
fi
# Where the adjoint learns each sample's radiance: a wavefront pass (the GPU's default, timed
# against Mitsuba above) against the path traced once more in the adjoint kernel, one process
# each, alternated, for one parameter and for the seven walls.
for way in leftWall:kernel leftWall:wavefront walls:kernel walls:wavefront; do
    IFS=: read -r which primal <<< "$way"
    step "speed-$gpu-$which-primal-$primal" "$bench" --device "$gpu" --sizes "$sizes" \
        --repeats "$repeats" --no-memory --params "$which" --primal "$primal" "$@"
done
[ "${GEOCOLD_GRAD_SPEED_ONLY:-0}" != 1 ] || { cat "$log"; exit "$status"; }
step speed-pocl "$bench" --device cpu --sizes "$sizes" --repeats "$repeats" --no-memory "$@"

# 2. Memory: our count, and nvidia-smi's used memory (the peak of 50 ms samples less the
# used memory before the process starts) per depth.
smi_peak() { # depth
    if [ "$have_smi" = 0 ]; then
        step "memory-depth-$1" "$bench" --device "$gpu" --no-time --memory-size "$memory_size" --memory-depths "$1"
        return
    fi
    local samples="$out/.smi-$1.csv"
    local before
    before=$(nvidia-smi --query-gpu=memory.used --format=csv,noheader,nounits | head -1)
    nvidia-smi --query-gpu=memory.used --format=csv,noheader,nounits -lms 50 > "$samples" 2>/dev/null &
    local smi=$!
    step "memory-depth-$1" "$bench" --device "$gpu" --no-time --memory-size "$memory_size" --memory-depths "$1"
    kill "$smi" 2>/dev/null
    wait "$smi" 2>/dev/null
    local peak
    peak=$(sort -n "$samples" | tail -1)
    echo "  nvidia-smi: depth $1: peak used ${peak:-?} MiB, ${before:-?} MiB before the process, $(( ${peak:-0} - ${before:-0} )) MiB its own" >> "$log"
    rm -f "$samples"
}
step memory "$bench" --device "$gpu" --no-time --memory-size "$memory_size" --memory-depths 6,64
smi_peak 6
smi_peak 64

# 3. The gradient tests on each device.
for d in $gpu cpu; do
    step "gradient_test-$d" env GEOCOLD_TEST_DEVICE=$d "$build_abs/tests/render/gradient_test" --gtest_brief=1
done

# 4. Determinism and the two devices' difference, at both sizes.
for size in ${sizes//,/ }; do
    step "determinism-$size" "$bench" --device "$gpu,cpu" --no-time --no-memory --determinism --sizes "$size"
done
# 5. What NVIDIA's compiler made of the adjoint (issue 43: its textured programs fault on the
# GPU, the untextured ones do not): the programs of an untextured and of a textured gradient
# test, dumped by the options shim, through ptxas -v (registers, stack frame, spills).
if command -v ptxas > /dev/null || [ -x /usr/local/cuda/bin/ptxas ]; then
    ptxas_bin=$(command -v ptxas || echo /usr/local/cuda/bin/ptxas)
    g++ -std=c++20 -shared -fPIC -O2 -I .deps/include tools/device/cl_options_shim.cpp -o "$build_abs/shim.so" -ldl
    for t in FiniteDifferencesAgree TexelGradientsAddUpToTheFactors; do
        dump="$build_abs/ptx-$t"
        rm -rf "$dump" && mkdir -p "$dump"
        LD_PRELOAD="$build_abs/shim.so" GEOCOLD_SHIM_DUMP="$dump" GEOCOLD_TEST_DEVICE=$gpu \
            "$build_abs/tests/render/gradient_test" --gtest_brief=1 --gtest_filter="*.$t" > /dev/null 2>&1
        for f in "$dump"/*.bin; do
            [ -f "$f" ] || continue
            echo "== ptxas -v, $t, $(basename "$f") ($(grep -c '^\.entry\|\.entry ' "$f") entries)" >> "$log"
            "$ptxas_bin" -arch=sm_90 -v "$f" -o /dev/null 2>&1 | grep -E "Compiling entry|Function properties|stack frame|registers|error|fatal" >> "$log"
        done
    done
fi
cat "$log"
exit "$status"
