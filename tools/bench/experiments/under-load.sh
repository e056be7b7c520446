#!/usr/bin/env bash
# Runs a command pinned to CPU 0 while clock_probe keeps every other CPU busy with one kind of
# code, once per kind named ("none" leaves them idle). Tells whether a one-thread figure falls
# because the rest of the package is busy, and with what: scalar code, or 256- or 512-bit FMAs.
# Usage: tools/bench/experiments/under-load.sh "none scalar avx2-fma avx512-fma" COMMAND [ARGS...]
set -euo pipefail
[ $# -ge 2 ] || { sed -n '2,5p' "$0" >&2; exit 2; }
kinds=$1
shift
here=$(cd "$(dirname "$0")" && pwd)
probe=${TMPDIR:-/tmp}/geocold-clock-probe
g++ -O2 -std=c++20 -pthread "$here/clock_probe.cpp" -o "$probe"
last=$(($(nproc) - 1))
pid=
# An interrupted run must not leave the load spinning for its hour.
trap '[ -z "$pid" ] || kill "$pid" 2>/dev/null || true' EXIT
for kind in $kinds; do
    echo "== under-load: CPU 0 runs the command; CPUs 1-$last run: $kind"
    pid=
    if [ "$kind" != none ]; then
        "$probe" load "$kind" 1 "$last" 3600 &
        pid=$!
        sleep 0.5
    fi
    status=0
    taskset -c 0 "$@" || status=$?
    [ -z "$pid" ] || { kill "$pid"; wait "$pid" 2>/dev/null || true; pid=; }
    [ "$status" = 0 ] || { echo "under-load: the command failed under $kind (exit $status)" >&2; exit "$status"; }
done
