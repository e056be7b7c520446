#!/usr/bin/env bash
# tools/openjd/render-frame.yaml through openjd-cli (`openjd run`, PyPI openjd-cli): the Render
# step's chunks merged by the Merge step have the bits of the one-process frame.
# Exit 77 (ctest: skipped) when openjd is not installed (OPENJD names it, else PATH).
# Usage: openjd_test.sh GEOCOLD_CL SOURCE_DIR
set -euo pipefail
cli=$(realpath "$1") src=$(realpath "$2")
openjd=${OPENJD:-$(command -v openjd || true)}
[[ -n "$openjd" ]] || { echo "SKIP: openjd-cli not installed"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene="$src/scenes/cornell-box/CornellBox-Original.obj"
template="$src/tools/openjd/render-frame.yaml"
params=(-p "Scene=$scene" -p "Output=$work/frame.pfm" -p Spp=14 -p ChunkSamples=5 -p Chunks=0-2
        -p "GeocoldCl=$cli" -p Device=cpu -p "ExtraArgs=--res 24x16 --max-depth 4")
"$openjd" check "$template"
"$openjd" run "$template" --step Render "${params[@]}" > "$work/render.log" 2>&1 || { cat "$work/render.log"; exit 1; }
"$openjd" run "$template" --step Merge "${params[@]}" > "$work/merge.log" 2>&1 || { cat "$work/merge.log"; exit 1; }
"$cli" "$scene" --quiet --device cpu --spp 14 --chunk-samples 5 --res 24x16 --max-depth 4 -o "$work/direct.pfm"
cmp "$work/frame.pfm" "$work/direct.pfm" || { echo "FAIL: the OpenJD frame differs from the one-process frame"; exit 1; }
echo "ok: openjd Render + Merge == one process"
