#!/usr/bin/env bash
# Copies the header-only dependencies (and GoogleTest's sources) from this Debian machine
# into .deps/ of the repository, for a machine that has a compiler, CMake and an OpenCL
# driver but no package manager (e.g. a lent GPU node), and Embree 3 for geocold-bench's
# yardstick. .deps/ is git-ignored; carry it.
# The shared Cornell boxes (../shared/scenes/cornell-box: the shared scenes that have lights)
# go to .deps/scenes/cornell-box when present, so tools/device/consistency.sh can check them
# on a node that has only the repository.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
deps="$root/.deps"
rm -rf "$deps"
mkdir -p "$deps/include"
cp -r /usr/include/CL /usr/include/glm /usr/include/nlohmann "$deps/include/"
cp /usr/include/tiny_obj_loader.h /usr/include/tiny_gltf.h "$deps/include/"
mkdir -p "$deps/include/stb"
cp /usr/include/stb/stb_image.h /usr/include/stb/stb_image_write.h "$deps/include/stb/"
cp -r /usr/src/googletest "$deps/googletest"
shared_boxes="${GEOCOLD_SHARED_DIR:-$root/../shared}/scenes/cornell-box"
if [ -d "$shared_boxes" ]; then
  mkdir -p "$deps/scenes/cornell-box"
  cp "$shared_boxes"/*.obj "$shared_boxes"/*.mtl "$deps/scenes/cornell-box/"
  cp "$shared_boxes"/README.md "$shared_boxes"/copyright.txt "$deps/scenes/cornell-box/" 2>/dev/null || true
fi
# Embree 3 and TBB, only as geocold-bench's CPU yardstick on the node (its CMake finds them
# through embree_DIR / TBB_DIR; tools/device/build-and-test.sh unpacks and points at them).
# The same prefix layout as Debian's, so both packages' relocatable CMake files work; the
# 44 MB library travels xz-compressed. Skipped when libembree-dev is not installed.
multiarch=lib/x86_64-linux-gnu
if [ -f "/usr/$multiarch/cmake/embree-3.13.5/embree-config.cmake" ] && [ -d "/usr/$multiarch/cmake/TBB" ]; then
  emb="$deps/embree"
  mkdir -p "$emb/include" "$emb/$multiarch/cmake"
  cp -r /usr/include/embree3 "$emb/include/"
  cp -r "/usr/$multiarch/cmake/embree-3.13.5" "/usr/$multiarch/cmake/TBB" "$emb/$multiarch/cmake/"
  xz -T0 -6 -c "/usr/$multiarch/libembree3.so.3.13.5" > "$emb/$multiarch/libembree3.so.3.13.5.xz"
  cp /usr/$multiarch/libtbb.so.12.* /usr/$multiarch/libtbbmalloc.so.2.* /usr/$multiarch/libtbbmalloc_proxy.so.2.* \
     /usr/$multiarch/libtbbbind_2_5.so.3.* "$emb/$multiarch/"
fi
# The bench's bunny and dragon (../shared/scenes), for geocold-bench on the node (point
# GEOCOLD_SHARED_DIR at .deps/shared there), and the helmet of tools/device/denoise-study.sh.
for scene in stanford-bunny stanford-dragon-100k damaged-helmet; do
  src="${GEOCOLD_SHARED_DIR:-$root/../shared}/scenes/$scene"
  [ -d "$src" ] && mkdir -p "$deps/shared/scenes" && cp -r "$src" "$deps/shared/scenes/"
done
# Mitsuba 3 for tools/bench/mitsuba_yardstick.py on the node (GEOCOLD_PACK_MITSUBA=1; needs
# PyPI here): the wheels for the node's Python (GEOCOLD_NODE_PYTHON, default 3.12), unpacked
# and cut to the rgb variants and the plugins the yardstick's scenes load (95 MB of 200),
# xz-compressed (about 17 MB). tools/device/mitsuba-yardstick.sh unpacks it there.
if [ "${GEOCOLD_PACK_MITSUBA:-0}" = 1 ]; then
  py=${GEOCOLD_NODE_PYTHON:-3.12}
  tmp=$(mktemp -d)
  # The versions of tools/reference/requirements.txt.
  versions=$(grep -E '^(mitsuba|drjit)==' "$root/tools/reference/requirements.txt")
  # shellcheck disable=SC2086
  python3 -m pip download -q --no-deps --only-binary=:all: --python-version "$py" --implementation cp \
    --platform manylinux_2_28_x86_64 --platform manylinux_2_27_x86_64 --platform manylinux_2_17_x86_64 \
    -d "$tmp/wheels" $versions
  mkdir -p "$tmp/site"
  for w in "$tmp"/wheels/mitsuba-*.whl "$tmp"/wheels/drjit-*.whl; do (cd "$tmp/site" && python3 -m zipfile -e "$w" .); done
  keep=" path perspective independent hdrfilm box diffuse twosided area constant conductor blendbsdf dielectric srgb bitmap uniform principled normalmap d65 regular merge "
  for f in "$tmp"/site/mitsuba/plugins/*.so; do
    case "$keep" in *" $(basename "$f" .so) "*) ;; *) rm "$f" ;; esac
  done
  rm -rf "$tmp"/site/mitsuba/*spectral* "$tmp"/site/mitsuba/*mono* "$tmp"/site/mitsuba/data/srgb.coeff \
         "$tmp"/site/mitsuba/data/sunsky "$tmp"/site/share
  mkdir -p "$deps/mitsuba"
  tar -C "$tmp/site" -cf - . | xz -T0 -6 > "$deps/mitsuba/site.tar.xz"
  rm -rf "$tmp"
fi
du -sh "$deps"
