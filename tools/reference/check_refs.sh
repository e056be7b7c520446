#!/usr/bin/env bash
# Renders every reference JSON of a directory (default ../shared/refs) with geocold-cl at the
# acceptance setting (>= 1024 spp, the reference's camera, resolution, max depth and
# environment) and prints the relative MSE against each reference through geocold-imgdiff.
# Acceptance: rel MSE <= 2e-3 for every scene.
#
#   tools/reference/check_refs.sh [-b BUILD_DIR] [-s SPP] [-o OUT_DIR] [-d DEVICE] [REFS_DIR|REF.json ...]
#
# Exit status: 0 all within the bound, 1 some scene above it or failed to render.
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$root/build"
spp=1024
out="${TMPDIR:-/tmp}/geocold-check-refs"
device=any
bound=2e-3
while getopts "b:s:o:d:h" opt; do
    case "$opt" in
    b) build="$OPTARG" ;;
    s) spp="$OPTARG" ;;
    o) out="$OPTARG" ;;
    d) device="$OPTARG" ;;
    *) sed -n '2,10p' "$0"; exit 2 ;;
    esac
done
shift $((OPTIND - 1))
[ $# -gt 0 ] || set -- "$root/../shared/refs"

geocold="$build/geocold-cl"
imgdiff="$build/tools/imgdiff/geocold-imgdiff"
for exe in "$geocold" "$imgdiff"; do
    [ -x "$exe" ] || { echo "check_refs: $exe not found (build geocold-cl and geocold-imgdiff, or pass -b)" >&2; exit 2; }
done
if [ "$spp" -lt 1024 ]; then echo "check_refs: note: $spp spp is below the acceptance setting (1024)" >&2; fi

jsons=()
for arg in "$@"; do
    if [ -d "$arg" ]; then
        for j in "$arg"/*.json; do [ -e "$j" ] && jsons+=("$j"); done
    else
        jsons+=("$arg")
    fi
done
[ ${#jsons[@]} -gt 0 ] || { echo "check_refs: no reference JSON found in $*" >&2; exit 2; }
mkdir -p "$out"

# The reference's settings as geocold-cl arguments, one per line: scene first, then flags.
args_of() {
    python3 - "$1" <<'PY'
import json, os, sys
path = sys.argv[1]
j = json.load(open(path))
c = j["camera"]
triple = lambda v: ",".join(repr(float(x)) for x in v)
print(os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(path)), j["scene"])))
print(os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(path)), j["image"])))
for a in ["--look-from", triple(c["look_from"]), "--look-at", triple(c["look_at"]),
          "--up", triple(c.get("up", [0, 1, 0])), "--fov", repr(float(c["fov"])),
          "--res", f"{c['res'][0]}x{c['res'][1]}", "--max-depth", str(j.get("max_depth", 8))]:
    print(a)
if j.get("env"):
    print("--env"); print(triple(j["env"]))
PY
}

status=0
printf "%-28s %10s %10s %8s  %s\n" scene "rel MSE" seconds verdict image
for json in "${jsons[@]}"; do
    name="$(basename "$json" .json)"
    mapfile -t a < <(args_of "$json")
    scene="${a[0]}" ref="${a[1]}"
    flags=("${a[@]:2}")
    img="$out/$name.exr"
    start=$(date +%s)
    if ! nice "$geocold" -q -d "$device" "$scene" --spp "$spp" "${flags[@]}" -o "$img" >"$out/$name.log" 2>&1; then
        printf "%-28s %10s %10s %8s  %s\n" "$name" - - FAILED "see $out/$name.log"
        status=1
        continue
    fi
    seconds=$(( $(date +%s) - start ))
    report="$("$imgdiff" "$img" "$ref" --heatmap "$out/$name-heat.exr" 2>&1 || true)"
    echo "$report" >"$out/$name-diff.txt"
    rel=$(echo "$report" | awk '$1 == "rel_mse" { print $2; exit }')
    if [ -z "$rel" ]; then
        verdict="?"; status=1
    elif python3 -c "import sys; sys.exit(0 if float('$rel') <= $bound else 1)"; then
        verdict=ok
    else
        verdict="> $bound"; status=1
    fi
    printf "%-28s %10s %10s %8s  %s\n" "$name" "$rel" "$seconds" "$verdict" "$img"
done
exit $status
