#!/usr/bin/env bash
# The cross-device recipe (issue 5), one command on a bare GPU node that has gcc, cmake,
# ninja and an OpenCL driver (NVIDIA, plus PoCL for the CPU side) and the carried .deps/
# (tools/device/prepare-deps.sh, run on a Debian machine; it also carries the shared Cornell
# boxes). It
#   1. builds geocold-cl without OpenImageIO and Vulkan and runs the unit and device tests
#      (tools/device/build-and-test.sh);
#   2. runs the ctest label `consistency` (the bundled Cornell boxes with every device, PoCL
#      asked for its pthread and basic drivers; the stress corpus, 48x48 at 8 spp, with PoCL's
#      pthread driver and every other device);
#   3. renders every Cornell box with lights (scenes/cornell-box and .deps/scenes/cornell-box)
#      on every OpenCL device at 64 spp, 128x128 (`geocold-cl --consistency`) and prints the
#      tables: device pair, relative MSE, max |difference|, % of pixels within 1e-3, pass/fail;
#   3b. the same for the stress corpus (tools/stress/make_corpus.py: scales, far translations,
#      an oblique rotation, slivers, coincident faces, bent normals, a 1M-triangle mesh),
#      generated where step 2's ctest fixture puts it, so one corpus serves both;
# Everything is also written under $OUT/consistency when OUT is set (else under the build
# directory): consistency.log, tables.txt, one JSON per scene, heat maps (PPM: no OIIO).
# Exit status: 0 when the build, the tests and every pair pass; otherwise the first failure.
#
# Usage: tools/device/consistency.sh
#   4. measures what the strict build options cost (render time per device with and without
#      -cl-fp32-correctly-rounded-divide-sqrt, with -cl-denorms-are-zero, with
#      -cl-fast-relaxed-math) and prints the Original box's table without correct rounding.
# Environment: BUILD_DIR (default build/bare), SPP (64), RES (128x128), SKIP_BUILD=1 (reuse a
# build), POCL_DEVICES (PoCL's drivers for steps 3-4; unset = PoCL's default, all cores),
# MEASURE=0 (skip step 4), MEASURE_RES (step 4's size, default 256x256), STRESS=0 (skip
# step 3b), STRESS_SPP / STRESS_RES (step 3b's, default SPP and RES).
# Exit status 7: a scene was compared on fewer than two devices; 8: the stress corpus could
# not be generated (needs python3).
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
build=${BUILD_DIR:-build/bare}
mkdir -p "$build"
build=$(cd "$build" && pwd)
out=${OUT:+$OUT/consistency}
out=${out:-$build/consistency}
spp=${SPP:-64}
res=${RES:-128x128}
mkdir -p "$out/json" "$out/heatmaps"
exec > >(tee "$out/consistency.log") 2>&1
export GEOCOLD_CACHE_DIR="$build/kernel-cache"

status=0
note_failure() { [ "$status" -ne 0 ] || status=$1; }
elapsed() { echo "$(( $(date +%s) - $1 )) s"; }

echo "== host: $(uname -srm), $(nproc) cores; $(gcc --version | head -1); $(cmake --version | head -1)"
t=$(date +%s)
if [ "${SKIP_BUILD:-0}" != 1 ]; then
  echo "== 1. build (no OpenImageIO, no Vulkan) + unit and device tests"
  BUILD_DIR="$build" bash tools/device/build-and-test.sh || note_failure $?
  echo "== 1. done in $(elapsed "$t")"
fi
[ -x "$build/geocold-cl" ] || { echo "no $build/geocold-cl: the build failed"; exit $(( status ? status : 3 )); }

t=$(date +%s)
echo "== 2. ctest -L consistency (bundled Cornell boxes: every device, PoCL pthread + basic; stress corpus: PoCL pthread + every other device)"
ctest --test-dir "$build" --output-on-failure -L consistency || note_failure $?
echo "== 2. done in $(elapsed "$t")"

t=$(date +%s)
echo "== 3. consistency tables: every Cornell box with lights, ${spp} spp, ${res}"
"$build/geocold-cl" --list-devices || note_failure $?
scenes=()
declare -A seen=()
for f in scenes/cornell-box/*.obj .deps/scenes/cornell-box/*.obj; do
  [ -f "$f" ] || continue
  name=$(basename "$f")
  [ -n "${seen[$name]:-}" ] && continue  # the bundled copy wins
  seen[$name]=1
  scenes+=("$f")
done
: > "$out/tables.txt"
for f in "${scenes[@]}"; do
  stem=$(basename "$f" .obj)
  echo
  table=$("$build/geocold-cl" --consistency --quiet --spp "$spp" --res "$res" --json "$out/json/$stem.json" \
      --heatmap "$out/heatmaps" "$f")
  rc=$?
  printf '%s\n' "$table" | tee -a "$out/tables.txt"
  [ "$rc" -eq 0 ] || { echo "!! $f: geocold-cl --consistency exited $rc"; note_failure "$rc"; }
  # One device is not a pass here: the recipe exists to compare devices.
  if grep -q "consistency: SKIPPED" <<< "$table"; then
    echo "!! fewer than two devices: nothing was compared"; note_failure 7
  fi
done
echo "== 3. done in $(elapsed "$t")"
n_passed=$(grep -c 'consistency: PASSED' "$out/tables.txt")
n_failed=$(grep -c 'consistency: FAILED' "$out/tables.txt")
n_skipped=$(grep -c 'consistency: SKIPPED' "$out/tables.txt")

# 3b. The stress corpus on every OpenCL device (on a GPU node: NVIDIA against PoCL).
stress_summary="stress corpus: not run (STRESS=0)"
if [ "${STRESS:-1}" = 1 ]; then
  t=$(date +%s)
  stress_spp=${STRESS_SPP:-$spp}
  stress_res=${STRESS_RES:-$res}
  corpus="$build/tests/stress/corpus"
  echo "== 3b. stress corpus (tools/stress/make_corpus.py), ${stress_spp} spp, ${stress_res}"
  stress_tables="$out/stress-tables.txt"
  : > "$stress_tables"
  if command -v python3 >/dev/null && python3 tools/stress/make_corpus.py --out "$corpus"; then
    mkdir -p "$out/json/stress" "$out/heatmaps/stress"
    mapfile -t stress_names < <(python3 tools/stress/make_corpus.py --list)
    printf '\n== stress corpus (%s spp, %s)\n' "$stress_spp" "$stress_res" >> "$out/tables.txt"
    for name in "${stress_names[@]}"; do
      echo
      table=$("$build/geocold-cl" --consistency --quiet --spp "$stress_spp" --res "$stress_res" \
          --json "$out/json/stress/$name.json" --heatmap "$out/heatmaps/stress" "$corpus/$name.obj")
      rc=$?
      printf '%s\n' "$table" | tee -a "$stress_tables" "$out/tables.txt"
      [ "$rc" -eq 0 ] || { echo "!! $name: geocold-cl --consistency exited $rc"; note_failure "$rc"; }
      if grep -q "consistency: SKIPPED" <<< "$table"; then
        echo "!! fewer than two devices: nothing was compared"; note_failure 7
      fi
    done
    stress_summary="stress corpus: $(grep -c 'consistency: PASSED' "$stress_tables") passed, \
$(grep -c 'consistency: FAILED' "$stress_tables") failed, $(grep -c 'consistency: SKIPPED' "$stress_tables") skipped \
of ${#stress_names[@]} scenes"
  else
    echo "!! the stress corpus could not be generated (python3: $(command -v python3 || echo missing))"
    stress_summary="stress corpus: not generated"
    note_failure 8
  fi
  echo "== 3b. done in $(elapsed "$t")"
fi

# 4. What strict math costs and buys (DESIGN.md rule 5), measured with an LD_PRELOAD shim
#    that rewrites clBuildProgram's options (tools/device/cl_options_shim.cpp), kernel cache
#    off: render time per device for each build variant, and the consistency table of the
#    Original box when the devices may round division and sqrt as they like.
if [ "${MEASURE:-1}" = 1 ]; then
  t=$(date +%s)
  echo "== 4. strict-math cost: CornellBox-Original, ${MEASURE_RES:-256x256}, ${spp} spp, render time per device"
  shim="$build/cl_options_shim.so"
  if g++ -std=c++20 -shared -fPIC -O2 -I "$root/.deps/include" tools/device/cl_options_shim.cpp -o "$shim" -ldl; then
    scene=scenes/cornell-box/CornellBox-Original.obj
    ndev=$("$build/geocold-cl" --list-devices | grep -cE '^ *[0-9]+ ')
    strict="-cl-fp32-correctly-rounded-divide-sqrt"
    for ((d = 0; d < ndev; ++d)); do
      for variant in strict no-strict-div-sqrt denorms-are-zero fast-relaxed-math; do
        case $variant in
          strict) remove=""; add="" ;;
          no-strict-div-sqrt) remove="$strict"; add="" ;;
          denorms-are-zero) remove=""; add="-cl-denorms-are-zero" ;;
          fast-relaxed-math) remove="$strict"; add="-cl-fast-relaxed-math" ;;
        esac
        log=$(LD_PRELOAD="$shim" GEOCOLD_NO_CACHE=1 GEOCOLD_SHIM_REMOVE="$remove" GEOCOLD_SHIM_ADD="$add" \
              "$build/geocold-cl" -d "$d" --spp "$spp" --res "${MEASURE_RES:-256x256}" \
              -o "$out/measure-$d-$variant.pfm" "$scene" 2>&1)
        line=$(grep 'wrote ' <<< "$log" | sed -E 's/^[^(]*\(//; s/ on .*//')
        [ -n "$line" ] || line="failed: $(tail -1 <<< "$log")"
        printf '  device %s  %-20s %s\n' "$d" "$variant" "$line" | tee -a "$out/tables.txt"
      done
    done
    echo "  consistency without correctly rounded division/sqrt (same scene, ${spp} spp, ${res}):" | tee -a "$out/tables.txt"
    LD_PRELOAD="$shim" GEOCOLD_NO_CACHE=1 GEOCOLD_SHIM_REMOVE="$strict" \
      "$build/geocold-cl" --consistency --quiet --spp "$spp" --res "$res" --json "$out/json/no-strict-div-sqrt.json" \
      "$scene" | tee -a "$out/tables.txt"
  else
    echo "!! could not build the shim: step 4 skipped"
  fi
  rm -f "$out"/measure-*.pfm
  echo "== 4. done in $(elapsed "$t") (measurements only: not part of the verdict)"
fi
echo
echo "== summary: $n_passed passed, $n_failed failed, $n_skipped skipped of ${#scenes[@]} scenes; $stress_summary; output in $out"
[ "$status" -eq 0 ] && echo "== ALL PASSED" || echo "== FAILED (status $status)"
exit "$status"
