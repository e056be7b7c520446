# The node builds' common configure step, sourced by the tools/device scripts that build: the
# `bare` preset against the OpenCL headers carried in .deps/include and the node's own ICD
# loader (a node has no package manager, so neither comes from a find_package search).
configure_bare_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)

# Prints the node's libOpenCL; fails with exit status 4 when there is none.
node_opencl_loader() {
    local lib
    lib=$(ldconfig -p | awk '/libOpenCL\.so(\.1)? /{print $NF; exit}')
    [ -n "$lib" ] || { echo "no libOpenCL (ICD loader) found" >&2; return 4; }
    echo "$lib"
}

# configure_bare BUILD_DIR [CMAKE_ARGS...]
configure_bare() {
    local build=$1 lib
    shift
    lib=$(node_opencl_loader) || return 4
    cmake --preset bare -B "$build" -DOpenCL_INCLUDE_DIR="$configure_bare_root/.deps/include" \
          -DOpenCL_LIBRARY="$lib" "$@"
}
