#!/usr/bin/env bash
# On the GPU node (no package registry): builds the geocold Python module and geocold-cl with
# CMake (the `bare` preset, carried .deps/) and runs the pytest cases that compare Python with
# the CLI bit for bit, on the GPU and on PoCL. The node's Python has numpy, pytest and
# nanobind; wheels carried in .whl/ (the device tool's README has the pip download line) are
# installed first where present. Logs go to $OUT; py-summary.log lists each test's outcome.
# Usage: tools/device/python-parity.sh
set -uo pipefail
out=${OUT:-build/py}
mkdir -p "$out"
[ ! -d .whl ] || python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --upgrade --target /tmp/site .whl/*.whl || exit 9
export PYTHONPATH=/tmp/site
# shellcheck source=tools/device/configure-bare.sh
source tools/device/configure-bare.sh
# PY_BUILD_DIR=build/bare reuses the CLI's build (configured with GEOCOLD_PYTHON=ON, as
# tools/device/multi-device-run.sh does); the default is a build of the module alone.
pybuild=${PY_BUILD_DIR:-build/py}
no_tests=-DGEOCOLD_BUILD_TESTS=OFF
[ "$pybuild" != build/bare ] || no_tests=
{ configure_bare "$pybuild" -DGEOCOLD_PYTHON=ON $no_tests -DPython_EXECUTABLE="$(command -v python3)" \
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
# One pytest process per test: the H200 node's GPU runs in exclusive-process compute mode (a
# geocold-cl started by a test saw no NVIDIA device once the test process held a context), and
# each test runs the CLI before its own Python render.
tests=(tests/python/test_render.py tests/python/test_edits.py)
selection="cli or two_renders or edit"
: > "$out/py-summary.log"
for d in gpu cpu; do
  : > "$out/py-$d.log"
  ids=$(python3 -m pytest -q --collect-only -p no:cacheprovider "${tests[@]}" -k "$selection" | grep '::')
  for id in $ids; do
    GEOCOLD_TEST_DEVICE=$d GEOCOLD_CLI=$PWD/$pybuild/geocold-cl python3 -m pytest -q -rs -p no:cacheprovider "$id" \
      >> "$out/py-$d.log" 2>&1 && echo "PASSED $d $id" || echo "FAILED $d $id"
  done | tee -a "$out/py-summary.log"
done
# PoCL compiling inside the node's Python died with SIGSEGV in pocl_llvm_build_program (session
# 34; the CLI compiles the same program): which interpreter settings it follows, each with no
# kernel cache so that PoCL compiles.
probe() { # label, command...
  GEOCOLD_NO_CACHE=1 POCL_KERNEL_CACHE=0 "$@" --device cpu --res 32x24 --spp 2 "$PWD/scenes/cornell-box/CornellBox-Original.obj" \
    -o /tmp/probe.pfm > /dev/null 2>&1
  echo "python PoCL compile probe, $1: exit $?" | tee -a "$out/py-summary.log"
}
probe "python3 -m geocold" python3 -m geocold
probe "python3 -S" python3 -S -m geocold
probe "LC_ALL=C" env LC_ALL=C LANG=C python3 -m geocold
[ ! -x /usr/bin/python3 ] || probe "/usr/bin/python3" /usr/bin/python3 -m geocold
echo "$(grep -c PASSED "$out/py-summary.log") passed, $(grep -c FAILED "$out/py-summary.log") failed"
! grep -q FAILED "$out/py-summary.log"
