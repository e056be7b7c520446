#!/usr/bin/env bash
# On a bare GPU node (gcc, cmake, ninja, an OpenCL driver; no package manager): builds
# geocold-cl with the carried .deps/ (tools/device/prepare-deps.sh) and OpenImageIO and
# Vulkan switched off, lists the devices, and runs the unit and device tests.
# Usage: tools/device/build-and-test.sh [extra ctest args]
# BUILD_DIR overrides the build directory (default: build/bare, the `bare` preset's);
# GEOCOLD_CMAKE_ARGS adds configure arguments (e.g. -DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON to
# rehearse a node without GoogleTest on a Debian machine).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
build=${BUILD_DIR:-build/bare}
[ -d .deps/include ] || { echo "missing .deps/: run tools/device/prepare-deps.sh on a Debian machine and carry it" >&2; exit 2; }

# shellcheck source=tools/device/configure-bare.sh
source "$root/tools/device/configure-bare.sh"
node_opencl_loader > /dev/null || exit 4

# GoogleTest from the carried sources, built and installed once into the build directory so
# that find_package(GTest) finds it. (The top level's GEOCOLD_GTEST_SOURCE_DIR fallback adds
# GTest::gtest aliases that googletest >= 1.11 already defines, which CMake rejects.)
mkdir -p "$build"
build_abs=$(cd "$build" && pwd)
gtest_prefix="$build_abs/_gtest/install"
if [ ! -f "$gtest_prefix/lib/cmake/GTest/GTestConfig.cmake" ]; then
  cmake -S "$root/.deps/googletest" -B "$build_abs/_gtest/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_INSTALL_PREFIX="$gtest_prefix" -DCMAKE_INSTALL_LIBDIR=lib -DBUILD_GMOCK=OFF -DINSTALL_GTEST=ON >/dev/null
  cmake --build "$build_abs/_gtest/build" -j "$(nproc)" >/dev/null
  cmake --install "$build_abs/_gtest/build" >/dev/null
fi

# Embree for geocold-bench's yardstick, when prepare-deps.sh packed it: unpacked once, found
# through its CMake files, and on the loader's path for the bench (export LD_LIBRARY_PATH as
# printed below to run geocold-bench by hand).
# shellcheck source=tools/device/embree-env.sh
source "$root/tools/device/embree-env.sh"
[ ${#embree_args[@]} -eq 0 ] || echo "Embree yardstick: LD_LIBRARY_PATH=$emb"

configure_bare "$build" -DCMAKE_PREFIX_PATH="$gtest_prefix" -DGEOCOLD_GTEST_SOURCE_DIR="$root/.deps/googletest" \
      "${embree_args[@]}" ${GEOCOLD_CMAKE_ARGS:-}
cmake --build "$build" -j "$(nproc)"
"$build_abs/geocold-cl" --list-devices
ctest --test-dir "$build_abs" --output-on-failure -L 'unit|device' "$@"
