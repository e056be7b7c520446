#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) in their own build folder and runs
# each for SECONDS, one after the other, printing the executions count of each.
#
#   tools/fuzz/run.sh [SECONDS]          default 60
#
# Environment: GEOCOLD_FUZZ_BUILD_DIR (default build/fuzz), CXX (default clang++-15, else
# clang++), FUZZ_RSS_MB (default 2048), FUZZ_TARGETS (default "fuzz_obj fuzz_gltf"),
# FUZZ_JOBS (build parallelism, default 2).
# New inputs go to <build>/corpus/<format>; the committed seeds (tools/fuzz/corpus) and the
# bad-scene corpus (tests/data/bad) are read, never written. A crash leaves its reproducer
# in <build>/crashes/ and makes the script exit non-zero; rerun one with
#   <build>/fuzz_obj <build>/crashes/crash-...
set -euo pipefail

seconds=${1:-60}
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${GEOCOLD_FUZZ_BUILD_DIR:-$root/build/fuzz}
cxx=${CXX:-$(command -v clang++-15 || command -v clang++ || true)}
rss_mb=${FUZZ_RSS_MB:-2048}
targets=${FUZZ_TARGETS:-fuzz_obj fuzz_gltf}
if [ -z "$cxx" ]; then
    echo "run.sh: no clang++ found; install clang-15 and libclang-common-15-dev (tools/install-deps.sh)" >&2
    exit 2
fi

mkdir -p "$build"
cmake -S "$root/tools/fuzz" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_COMPILER="$cxx" > "$build/configure.log" 2>&1 || { cat "$build/configure.log" >&2; exit 2; }
# shellcheck disable=SC2086
cmake --build "$build" --target $targets -j "${FUZZ_JOBS:-2}"

status=0
for target in $targets; do
    format=${target#fuzz_}
    mkdir -p "$build/corpus/$format" "$build/crashes"
    log="$build/$target.log"
    echo "== $target: ${seconds}s"
    set +e
    # -close_fd_mask=2: the loaders' warnings go nowhere; libFuzzer and the sanitizers keep
    # their own copy of stderr for reports. stdin from /dev/null: nothing can block on it.
    "$build/$target" -max_total_time="$seconds" -rss_limit_mb="$rss_mb" -malloc_limit_mb="$rss_mb" \
        -timeout=20 -max_len=16384 -close_fd_mask=2 -print_final_stats=1 \
        -dict="$root/tools/fuzz/$format.dict" -artifact_prefix="$build/crashes/$target-" \
        "$build/corpus/$format" "$root/tools/fuzz/corpus/$format" "$root/tests/data/bad" \
        < /dev/null > "$log" 2>&1
    rc=$?
    set -e
    runs=$(sed -n 's/^Done \([0-9]*\) runs in \([0-9]*\) second.*/\1 executions in \2 s/p' "$log" | tail -1)
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 || true)
    if [ "$rc" -ne 0 ]; then
        echo "$target: FAILED (exit $rc) after ${runs:-? executions}; see $log" >&2
        grep -E 'ERROR|SUMMARY|Test unit written|deadly signal|uncaught' "$log" | head -20 >&2 || true
        status=1
    else
        echo "$target: ${runs:-? executions}, ${cov:-cov ?}, no finding"
    fi
done
exit $status
