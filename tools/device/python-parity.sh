#!/usr/bin/env bash
# On the GPU node (no package registry): builds the geocold Python module with CMake and runs
# the pytest cases that compare Python with the CLI bit for bit, on the GPU and on PoCL.
# Needs a build of the CLI at build/bare (tools/device/build-and-test.sh) and, carried in
# .whl/, the wheels of nanobind, pytest, pluggy, iniconfig, packaging and pygments for the
# node's Python (see the device tool's README for the pip download line). Logs go to $OUT.
# Usage: tools/device/python-parity.sh
set -uo pipefail
out=${OUT:-build/py}
mkdir -p "$out"
[ ! -d .whl ] || python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --upgrade --target /tmp/site .whl/*.whl || exit 9
export PYTHONPATH=/tmp/site
opencl_lib=$(ldconfig -p | awk '/libOpenCL\.so(\.1)? /{print $NF; exit}')
# PY_BUILD_DIR=build/bare reuses the CLI's build (configured with GEOCOLD_PYTHON=ON, as
# tools/device/multi-device-run.sh does); the default is a build of the module alone.
pybuild=${PY_BUILD_DIR:-build/py}
no_tests=-DGEOCOLD_BUILD_TESTS=OFF
[ "$pybuild" != build/bare ] || no_tests=
{ cmake --preset bare -B "$pybuild" -DOpenCL_INCLUDE_DIR="$PWD/.deps/include" -DOpenCL_LIBRARY="$opencl_lib" \
    -DGEOCOLD_PYTHON=ON $no_tests -DPython_EXECUTABLE="$(command -v python3)" \
    -Dnanobind_DIR="$(python3 -m nanobind --cmake_dir)" &&
  cmake --build "$pybuild" -j "$(nproc)" --target _geocold geocold-cl &&
  cmake --install "$pybuild" --component python --prefix /tmp/pyinst; } > "$out/py-build.log" 2>&1 ||
  { tail -30 "$out/py-build.log"; exit 8; }
# Where the package went: the install rule's destination can be the interpreter's own
# site-packages (absolute), which --prefix does not move.
init=$(grep -oE '(Installing|Up-to-date): .*/geocold/__init__\.py' "$out/py-build.log" | head -1 | sed -E 's/^[A-Za-z-]+: //')
[ -n "$init" ] || { echo "the install log names no geocold/__init__.py" >&2; exit 8; }
site=$(dirname "$(dirname "$init")")
export PYTHONPATH=$site:/tmp/site
status=0
for d in gpu cpu; do
  GEOCOLD_TEST_DEVICE=$d GEOCOLD_CLI=$PWD/$pybuild/geocold-cl python3 -m pytest -q -rs -p no:cacheprovider \
    tests/python/test_render.py tests/python/test_edits.py -k "cli or two_renders or edit" 2>&1 | tee "$out/py-$d.log" | tail -15
  [ "${PIPESTATUS[0]}" -eq 0 ] || status=1
done
exit $status
