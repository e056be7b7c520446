#!/usr/bin/env bash
# Copies the header-only dependencies (and GoogleTest's sources) from this Debian machine
# into .deps/ of the repository, for a machine that has a compiler, CMake and an OpenCL
# driver but no package manager (e.g. a lent GPU node). .deps/ is git-ignored; carry it.
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
du -sh "$deps"
