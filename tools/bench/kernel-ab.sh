#!/usr/bin/env bash
# A/B of two kernel trees with one geocold-bench binary: the kernels are read at run time
# (GEOCOLD_KERNEL_DIR), so a change to kernels/ can be measured against the previous
# version without a second build, in interleaved rounds (A B A B ...) so that a machine
# whose speed drifts affects both alike. Prints every round, then per figure the median of
# A, the median of B and the median of the per-round ratios B/A.
#
# Usage: tools/bench/kernel-ab.sh DIR_A DIR_B [ROUNDS] [geocold-bench args...]
#   DIR_A, DIR_B   kernel trees (each with *.cl and shared/), e.g. from
#                  `git archive HEAD~1 kernels | tar -x -C /tmp/a` -> /tmp/a/kernels
#   ROUNDS         interleaved rounds (default 3)
#   bench args     default: --device cpu --scene cornell,dragon --no-first-image --repeats 3
# GEOCOLD_BENCH (default: build/release/geocold-bench, else build/bare/geocold-bench) picks
# the binary; other environment (GEOCOLD_KERNEL_FEATURES, GEOCOLD_BVH_WIDTH...) passes through.
set -euo pipefail
[ $# -ge 2 ] || { sed -n '2,14p' "$0" >&2; exit 2; }
dir_a=$1
dir_b=$2
shift 2
rounds=3
if [ $# -gt 0 ] && [[ $1 =~ ^[0-9]+$ ]]; then rounds=$1; shift; fi
[ $# -gt 0 ] || set -- --device cpu --scene cornell,dragon --no-first-image --repeats 3
for d in "$dir_a" "$dir_b"; do
    [ -d "$d/shared" ] || { echo "kernel-ab: $d is not a kernel tree (no shared/ in it)" >&2; exit 2; }
done
root=$(cd "$(dirname "$0")/../.." && pwd)
bench=${GEOCOLD_BENCH:-}
if [ -z "$bench" ]; then
    for b in "$root/build/release/geocold-bench" "$root/build/bare/geocold-bench"; do
        if [ -x "$b" ]; then bench=$b; break; fi
    done
fi
[ -n "$bench" ] && [ -x "$bench" ] || { echo "kernel-ab: no geocold-bench (set GEOCOLD_BENCH)" >&2; exit 2; }

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
             for (i = 1; i <= NF; i++) if ($(i+1) == "Msamples/s") { print scene "/" dev "/path=" $i; break } }'
}

results=$(mktemp)
trap 'rm -f "$results"' EXIT
for ((r = 1; r <= rounds; r++)); do
    for side in A B; do
        dir=$dir_a
        [ $side = B ] && dir=$dir_b
        line=$(GEOCOLD_KERNEL_DIR=$dir "$bench" "$@" 2>&1 | figures | tr '\n' ' ')
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
