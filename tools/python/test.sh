#!/usr/bin/env bash
# The Python package's tests, as ctest's `python` test runs them (label python):
#   tools/python/test.sh VENV [GEOCOLD_CLI]
# Creates the virtual environment VENV if needed, installs pytest, numpy, Pillow and pyoidn
# (gc.denoise) into it,
# builds and installs the package from this checkout with `pip install .` (scikit-build-core +
# nanobind from PyPI; the build folder build/python/ is kept, so a re-run rebuilds only what
# changed; ccache is used when installed), then runs tests/python with the geocold-cl binary
# GEOCOLD_CLI to compare against.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
venv="$(realpath -m "${1:?usage: test.sh VENV [GEOCOLD_CLI]}")"
[ $# -ge 2 ] && export GEOCOLD_CLI="$(realpath "$2")"

if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check pytest numpy Pillow pyoidn

config=()
if command -v ccache >/dev/null; then
    config+=(--config-settings=cmake.define.CMAKE_CXX_COMPILER_LAUNCHER=ccache)
    export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$root}"
fi
export CMAKE_BUILD_PARALLEL_LEVEL="${CMAKE_BUILD_PARALLEL_LEVEL:-$(nproc)}"
start=$(date +%s)
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "${config[@]}" "$root"
echo "python: pip install . took $(( $(date +%s) - start )) s"

# From outside the checkout, so that `import geocold` finds the installed package.
cd "$venv"
exec "$venv/bin/python" -m pytest -q -rs -s "$root/tests/python"  # -s: the tests print their timings
