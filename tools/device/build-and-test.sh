#!/usr/bin/env bash
# On a bare GPU node (gcc, cmake, ninja, an OpenCL driver; no package manager): builds
# geocold-cl with the carried .deps/ (tools/device/prepare-deps.sh) and OpenImageIO and
# Vulkan switched off, lists the devices, and runs the unit and device tests.
# Usage: tools/device/build-and-test.sh [extra ctest args]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
[ -d .deps/include ] || { echo "missing .deps/: run tools/device/prepare-deps.sh on a Debian machine and carry it" >&2; exit 2; }

opencl_lib=$(ldconfig -p | awk '/libOpenCL\.so(\.1)? /{print $NF; exit}')
[ -n "$opencl_lib" ] || { echo "no libOpenCL (ICD loader) found" >&2; exit 4; }

cmake --preset bare -DOpenCL_INCLUDE_DIR="$root/.deps/include" -DOpenCL_LIBRARY="$opencl_lib" \
      -DGEOCOLD_GTEST_SOURCE_DIR="$root/.deps/googletest"
cmake --build --preset bare -j "$(nproc)"
./build/bare/geocold-cl --list-devices
ctest --test-dir build/bare --output-on-failure -L 'unit|device' "$@"
