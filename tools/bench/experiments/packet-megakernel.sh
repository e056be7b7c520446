#!/usr/bin/env bash
# Reproduces the explicit-SIMD path tracer experiment (README.md here): builds two kernel
# trees in a temporary directory, A = kernels/ and B = kernels/ with megakernel.cl replaced
# by packet_megakernel.cl, checks that both render the same bits (Cornell box, and the dragon
# when ../shared has it), then times both with tools/bench/kernel-ab.sh.
#
# Usage: tools/bench/experiments/packet-megakernel.sh [ROUNDS] [geocold-bench args...]
#   ROUNDS      interleaved A/B rounds (default 3)
#   bench args  default: --device cpu --scene cornell,dragon --no-rays --no-first-image
#               --no-packet-probe --repeats 3
# PK_VARIANT picks what runs in packets besides the shading: shading (rays lane by lane),
# shadow (default: shadow rays as packets), all (path rays too); and how lanes are filled:
# those three give each lane its own pixel, pixel and pixel-primary give a work-item one
# pixel and its lanes eight consecutive samples of it (Mitsuba's layout), with shadow rays as
# packets, and pixel-primary the camera rays too.
# GEOCOLD_BENCH and GEOCOLD_CL pick the binaries (default: build/release, else build/bare).
# Exit status: 0 when the bits match and the timing ran, 1 when the images differ, 2 when a
# render fails (its messages are shown).
set -euo pipefail
root=$(cd "$(dirname "$0")/../../.." && pwd)
rounds=3
if [ $# -gt 0 ] && [[ $1 =~ ^[0-9]+$ ]]; then rounds=$1; shift; fi
[ $# -gt 0 ] || set -- --device cpu --scene cornell,dragon --no-rays --no-first-image --no-packet-probe --repeats 3

pick() {
    for b in "$root/build/release/$1" "$root/build/bare/$1"; do
        if [ -x "$b" ]; then echo "$b"; return; fi
    done
}
cl=${GEOCOLD_CL:-$(pick geocold-cl)}
bench=${GEOCOLD_BENCH:-$(pick geocold-bench)}
[ -n "$cl" ] && [ -n "$bench" ] || { echo "packet-megakernel: build geocold-cl and geocold-bench first (or set GEOCOLD_CL, GEOCOLD_BENCH)" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp -r "$root/kernels" "$work/a"
cp -r "$root/kernels" "$work/b"
pixel=0 primary=0
case ${PK_VARIANT:-shadow} in
    shading) shadow=0 closest=0 ;;
    shadow) shadow=1 closest=0 ;;
    all) shadow=1 closest=1 ;;
    pixel) shadow=1 closest=0 pixel=1 ;;
    pixel-primary) shadow=1 closest=0 pixel=1 primary=1 ;;
    *) echo "packet-megakernel: PK_VARIANT must be shading, shadow, all, pixel or pixel-primary" >&2; exit 2 ;;
esac
sed -e "s/^#define PK_PACKET_SHADOW .*/#define PK_PACKET_SHADOW $shadow/" \
    -e "s/^#define PK_PACKET_CLOSEST .*/#define PK_PACKET_CLOSEST $closest/" \
    -e "s/^#define PK_PIXEL_LANES .*/#define PK_PIXEL_LANES $pixel/" \
    -e "s/^#define PK_PACKET_PRIMARY .*/#define PK_PACKET_PRIMARY $primary/" \
    "$root/tools/bench/experiments/packet_megakernel.cl" > "$work/b/megakernel.cl"
echo "variant: ${PK_VARIANT:-shadow} (PK_PACKET_SHADOW $shadow, PK_PACKET_CLOSEST $closest, PK_PIXEL_LANES $pixel, PK_PACKET_PRIMARY $primary)"

# Same bits: the experiment's scope is untextured Lambert with triangle emitters or a
# constant environment, which these two scenes are. --device cpu: the megakernel is the CPU form.
same=0
check() {
    local name=$1
    shift
    local side
    for side in a b; do
        if ! GEOCOLD_KERNEL_DIR="$work/$side" "$cl" --device cpu -q "$@" -o "$work/$name-$side.pfm" 2>"$work/log"; then
            echo "packet-megakernel: rendering $name with kernel tree $side failed:" >&2
            cat "$work/log" >&2
            exit 2
        fi
    done
    if cmp -s "$work/$name-a.pfm" "$work/$name-b.pfm"; then
        echo "bits: $name identical to the scalar megakernel"
    else
        echo "bits: $name DIFFERS from the scalar megakernel"
        same=1
    fi
}
check cornell "$root/scenes/cornell-box/CornellBox-Original.obj" --spp 4 --res 128x128
dragon="${GEOCOLD_SHARED_DIR:-$root/../shared}/scenes/stanford-dragon-100k/dragon.obj"
if [ -f "$dragon" ]; then
    check dragon "$dragon" --env 1,1,1 --spp 2 --res 160x120
fi

GEOCOLD_BENCH=$bench "$root/tools/bench/kernel-ab.sh" "$work/a" "$work/b" "$rounds" "$@"
exit $same
