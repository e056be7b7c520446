#!/usr/bin/env bash
# CI stage "robustness": the unit and robustness tests under AddressSanitizer +
# UndefinedBehaviorSanitizer (the `asan` preset), then each libFuzzer target for a bounded time.
#
#   tools/ci/robustness.sh [FUZZ_SECONDS]     default 60 per fuzzer; 0 skips fuzzing
#
# Environment: GEOCOLD_ASAN_LABELS (ctest labels to build and run, default 'unit|robustness'),
# GEOCOLD_ASAN_BUILD_DIR (default: the preset's build/asan),
# GEOCOLD_FUZZ_BUILD_DIR (default build/fuzz), CI_JOBS (default 2).
# Builds only the test binaries labelled unit or robustness (and what they need), not the
# whole tree. Prints the time each step took.
set -euo pipefail

fuzz_seconds=${1:-60}
root=$(cd "$(dirname "$0")/../.." && pwd)
jobs=${CI_JOBS:-2}
cd "$root"
start=$(date +%s)
step_start=$start
step() {
    local now
    now=$(date +%s)
    printf '== %s (previous step %ds, total %ds)\n' "$1" $((now - step_start)) $((now - start))
    step_start=$now
}

step "configure (asan preset)"
build_args=()
if [ -n "${GEOCOLD_ASAN_BUILD_DIR:-}" ]; then build_args=(-B "$GEOCOLD_ASAN_BUILD_DIR"); fi
# No -Werror here: GCC 12 with ASan warns falsely (-Wmaybe-uninitialized inside
# <regex> and <functional>); the ci preset is the warnings gate. The preset compiles with
# -O1 -g1 (line tables, enough for the reports' file:line): with RelWithDebInfo's -O2 -g,
# GCC's variable tracking made this build 586 s of a 1619 s CI run (now about 210-270 s).
cmake --preset asan "${build_args[@]}" > /dev/null
build=${GEOCOLD_ASAN_BUILD_DIR:-$root/build/asan}

# The gc_add_test() targets whose LABELS include unit or robustness.
labels=${GEOCOLD_ASAN_LABELS:-unit|robustness}
mapfile -t targets < <(python3 - "$root/tests" "$labels" <<'PY'
import pathlib, re, sys
for cml in sorted(pathlib.Path(sys.argv[1]).glob("*/CMakeLists.txt")):
    for block in re.findall(r"gc_add_test\s*\((.*?)\)", cml.read_text(), re.S):
        name = re.search(r"\bNAME\s+(\S+)", block)
        labels = re.search(r"\bLABELS\s+([^\n)]*)", block)
        if name and labels and re.search(r"\b(" + sys.argv[2] + r")\b", labels.group(1)):
            print(name.group(1))
PY
)
if ! printf '%s\n' "${targets[@]}" | grep -qx robustness_test; then
    echo "robustness.sh: no robustness_test target: tests/CMakeLists.txt must add_subdirectory(robustness)" >&2
    exit 2
fi
step "build ${targets[*]}"
cmake --build "$build" --target "${targets[@]}" -j "$jobs"

step "ctest -L '$labels'"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
export LSAN_OPTIONS="suppressions=$root/tools/ci/lsan-suppressions.txt${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
# A test failure does not skip the fuzzers: one CI run reports both.
status=0
ctest --test-dir "$build" -L "$labels" --output-on-failure -j "$jobs" || status=1

if [ "$fuzz_seconds" -gt 0 ]; then
    step "fuzzers, ${fuzz_seconds}s each"
    FUZZ_JOBS=$jobs "$root/tools/fuzz/run.sh" "$fuzz_seconds" || status=1
fi
step "done (exit $status)"
exit $status
