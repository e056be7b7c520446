#!/usr/bin/env bash
# Paired A/B of geocold-bench's path figures on a GPU node: this tree against another source
# tree of geocold-cl (BASE_SRC, e.g. `git archive <commit>` of the commit before, unpacked
# into a git-ignored folder and carried with .deps/). Both are built the same way (the `bare`
# preset with the bench), then run in alternating rounds on the same devices, so a ratio is
# read within one round and the load of the moment cancels; the rounds give its range.
# Usage: BASE_SRC=.base tools/device/bench-ab.sh [rounds] [geocold-bench args...]
# Output: $OUT/bench-ab/{new,base}-<round>.txt when OUT is set, else under build/bench-ab.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
base=$(cd "${BASE_SRC:?set BASE_SRC to the other source tree}" && pwd)
rounds=${1:-3}
shift || true
args=("$@")
[ ${#args[@]} -gt 0 ] || args=(--device all --scene cornell,dragon --no-rays --no-first-image --no-packet-probe --repeats 3)
out=${OUT:+$OUT/bench-ab}
out=${out:-$root/build/bench-ab}
mkdir -p "$out"
[ -e "$base/.deps" ] || ln -s "$root/.deps" "$base/.deps"
for tree in "$root" "$base"; do
  # The node scripts build, then run ctest; '^$' matches no test, so this only builds.
  (cd "$tree" && BUILD_DIR=build/bench GEOCOLD_CMAKE_ARGS=-DGEOCOLD_BUILD_BENCH=ON \
     bash tools/device/build-and-test.sh -R '^$' > "$out/build-$(basename "$tree").log" 2>&1) ||
    { echo "build failed in $tree (see $out)"; exit 3; }
done
export GEOCOLD_SHARED_DIR="$root/.deps/shared"
source "$root/tools/device/embree-env.sh"
for ((r = 1; r <= rounds; ++r)); do
  "$root/build/bench/geocold-bench" "${args[@]}" > "$out/new-$r.txt" 2>&1
  "$base/build/bench/geocold-bench" "${args[@]}" > "$out/base-$r.txt" 2>&1
  echo "== round $r"
  grep -H -i "path" "$out/new-$r.txt" "$out/base-$r.txt" | sed "s|$out/||"
done
