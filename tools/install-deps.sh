#!/usr/bin/env bash
# Installs every Debian 12 package geocold-cl needs to build, test and benchmark.
# Idempotent and non-interactive: run it as root (or through sudo) as often as you like.
set -euo pipefail

packages=(
    # Toolchain
    build-essential cmake ninja-build pkg-config python3
    # The Python package (pip install . into a venv: tools/python/test.sh) and ccache for it
    python3-dev python3-venv ccache
    # OpenCL: headers, ICD loader, PoCL (the CPU device), clinfo for diagnostics
    opencl-c-headers opencl-clhpp-headers ocl-icd-opencl-dev pocl-opencl-icd clinfo
    # Host libraries
    libglm-dev libopenimageio-dev openimageio-tools
    libtinyobjloader-dev libtinygltf-dev nlohmann-json3-dev libstb-dev
    libgtest-dev libgmock-dev
    # Vulkan cross-check path: loader, headers, lavapipe, GLSL -> SPIR-V
    libvulkan-dev mesa-vulkan-drivers glslc glslang-tools
    # Benchmark yardstick only
    libembree-dev
    # Fuzzing only (tools/fuzz, tools/ci/robustness.sh): clang; libclang-common-15-dev holds
    # the libFuzzer and sanitizer runtimes (libclang_rt.fuzzer-x86_64.a)
    clang-15 libclang-common-15-dev
    # The render-farm test (tests/slurm/real_slurm_test.sh starts its own daemons on localhost)
    slurmctld slurmd slurm-client munge
)

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi

# pip_venv DIR REQUIREMENT: a virtual environment at DIR (made once) with REQUIREMENT in it,
# for what Debian 12 does not package.
pip_venv() {
    if [ ! -x "$1/bin/python" ]; then "${sudo_cmd[@]}" python3 -m venv "$1"; fi
    "${sudo_cmd[@]}" "$1/bin/python" -m pip install --quiet --disable-pip-version-check "$2"
}

export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${packages[@]}"

# Open Image Denoise for --denoise and gc.denoise: not in Debian 12, so PyPI's pyoidn (its
# wheel carries libOpenImageDenoise.so.2, the CPU device and the weights) goes into a virtual
# environment, and its library folder is linked to /opt/geocold-cl/oidn, where geocold-cl
# looks (host/image/denoise.h). GEOCOLD_OIDN_VENV moves the environment.
oidn_venv="${GEOCOLD_OIDN_VENV:-/opt/geocold-cl/oidn-venv}"
"${sudo_cmd[@]}" mkdir -p /opt/geocold-cl
pip_venv "$oidn_venv" 'pyoidn==2.5.1.0'
oidn_lib="$("$oidn_venv/bin/python" -c 'import importlib.util as u; print(u.find_spec("pyoidn").submodule_search_locations[0])')/oidn"
"${sudo_cmd[@]}" ln -sfn "$oidn_lib" /opt/geocold-cl/oidn

# Open Job Description's CLI (PyPI openjd-cli, not in Debian 12) for the OpenJD template's test
# (tests/slurm/openjd_test.sh): the build looks for it in this environment, then on PATH.
pip_venv /opt/geocold-cl/openjd-venv 'openjd-cli==0.8.0'
