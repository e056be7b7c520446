#!/usr/bin/env bash
# A/B of two kernel trees, or of two geocold-bench builds, in interleaved rounds (A B A B ...)
# so that a machine whose speed drifts affects both alike. Kernels are read at run time
# (GEOCOLD_KERNEL_DIR), so a change to kernels/ is measured with one binary and no second
# build; a change to host code (the BVH builder, the collapse) needs a bench built from each
# revision. Prints every round, then per figure the median of A, the median of B and the
# median of the per-round ratios B/A. Figures: each ray and path line of the bench, and the
# tree and CPU-start speeds against Embree.
#
# Usage: tools/bench/kernel-ab.sh SIDE_A SIDE_B [ROUNDS] [geocold-bench args...]
#   SIDE_A, SIDE_B  each a kernel tree (with *.cl and shared/), e.g. from
#                   `git archive HEAD~1 kernels | tar -x -C /tmp/a` -> /tmp/a/kernels,
#                   or a geocold-bench executable (it reads its own tree's kernels). For
#                   the GPU node: `git archive BASE | tar -x -C .deps/base` here, carry .deps,
#                   and there `ln -s "$PWD/.deps" .deps/base/.deps`, build both trees with
#                   GEOCOLD_CMAKE_ARGS=-DGEOCOLD_BUILD_BENCH=ON tools/device/build-and-test.sh
#                   (in each), then pass .deps/base/build/bare/geocold-bench build/bare/geocold-bench
#   ROUNDS          interleaved rounds (default 3)
#   bench args      default: --device cpu --scene cornell,dragon --no-first-image --repeats 3
# GEOCOLD_BENCH (default: build/release/geocold-bench, else build/bare/geocold-bench) is the
# binary for kernel-tree sides; other environment (GEOCOLD_KERNEL_FEATURES,
# GEOCOLD_BVH_WIDTH...) passes through.
set -euo pipefail
[ $# -ge 2 ] || { sed -n '2,23p' "$0" >&2; exit 2; }
side_a=$1
side_b=$2
shift 2
rounds=3
if [ $# -gt 0 ] && [[ $1 =~ ^[0-9]+$ ]]; then rounds=$1; shift; fi
[ $# -gt 0 ] || set -- --device cpu --scene cornell,dragon --no-first-image --repeats 3
for d in "$side_a" "$side_b"; do
    [ -d "$d/shared" ] || { [ -f "$d" ] && [ -x "$d" ]; } ||
        { echo "kernel-ab: $d is neither a kernel tree (no shared/ in it) nor an executable" >&2; exit 2; }
done
root=$(cd "$(dirname "$0")/../.." && pwd)
bench=${GEOCOLD_BENCH:-}
if [ -z "$bench" ]; then
    for b in "$root/build/release/geocold-bench" "$root/build/bare/geocold-bench"; do
        if [ -x "$b" ]; then bench=$b; break; fi
    done
fi
if [ -d "$side_a" ] || [ -d "$side_b" ]; then
    [ -n "$bench" ] && [ -x "$bench" ] || { echo "kernel-ab: no geocold-bench (set GEOCOLD_BENCH)" >&2; exit 2; }
fi

# One run's figures as "name=value" words: each ray and path line of the bench, named by
# scene, device index and kind (e.g. cornell/0/diffuse, dragon/0/path).
figures() {
    awk '/^== scene /{scene=$3; sub(":", "", scene)}
         /\[[0-9]+\].*(primary|diffuse|shadow) *:/{
             dev=$1; gsub(/[\[\]]/, "", dev)
             kind = ""
             for (i = 1; i <= NF; i++) { t = $i; sub(":", "", t); if (t ~ /^(primary|diffuse|shadow)$/) kind = t }
             for (i = 1; i <= NF; i++) if ($(i+1) == "Mrays/s") { print scene "/" dev "/" kind "=" $i; break } }
         /^ *path \[[0-9]+\]/{
             dev=$2; gsub(/[\[\]]/, "", dev)
             for (i = 1; i <= NF; i++) if ($(i+1) == "Msamples/s") { print scene "/" dev "/path=" $i; break } }
         /ours\/Embree: speed/{ for (i = 1; i <= NF; i++) if ($i == "speed") { v = $(i+1); sub("x", "", v); print scene "/tree=" v; break } }
         /CPU start:.*speed/{ for (i = 1; i <= NF; i++) if ($i == "speed") { v = $(i+1); sub("x", "", v); print scene "/start=" v; break } }'
}

results=$(mktemp)
trap 'rm -f "$results"' EXIT
for ((r = 1; r <= rounds; r++)); do
    for side in A B; do
        spec=$side_a
        [ $side = B ] && spec=$side_b
        if [ -d "$spec" ]; then
            line=$(GEOCOLD_KERNEL_DIR=$spec "$bench" "$@" 2>&1 | figures | tr '\n' ' ')
        else
            line=$("$spec" "$@" 2>&1 | figures | tr '\n' ' ')
        fi
        echo "round $r $side: $line"
        for f in $line; do echo "$r $side ${f%%=*} ${f#*=}" >> "$results"; done
    done
done

echo "figure: median A, median B, median of per-round B/A ($rounds rounds)"
awk '
    { v[$3, $2, $1] = $4; names[$3] = 1; if ($1 > n) n = $1 }
    function median(arr, k,    i, j, t) {
        for (i = 1; i <= k; i++) for (j = i + 1; j <= k; j++) if (arr[j] < arr[i]) { t = arr[i]; arr[i] = arr[j]; arr[j] = t }
        return k % 2 ? arr[(k + 1) / 2] : (arr[k / 2] + arr[k / 2 + 1]) / 2
    }
    END {
        for (name in names) {
            ka = kb = kr = 0
            delete a; delete b; delete q
            for (r = 1; r <= n; r++) {
                if ((name, "A", r) in v) a[++ka] = v[name, "A", r]
                if ((name, "B", r) in v) b[++kb] = v[name, "B", r]
                if ((name, "A", r) in v && (name, "B", r) in v && v[name, "A", r] > 0) q[++kr] = v[name, "B", r] / v[name, "A", r]
            }
            if (ka && kb && kr) printf "  %-20s %10.4g %10.4g   %.3fx\n", name, median(a, ka), median(b, kb), median(q, kr)
        }
    }' "$results" | sort
