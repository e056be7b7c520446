# Sourced by the node scripts: unpacks the Embree 3 + TBB that tools/device/prepare-deps.sh
# carried in .deps/embree (once; the library travels xz-compressed), links the sonames, and
# sets embree_args (CMake's embree_DIR / TBB_DIR) and LD_LIBRARY_PATH. embree_args stays
# empty when nothing was carried. Uses $root, the repository, when the caller set it, else
# the repository this file is in (a bare `source tools/device/embree-env.sh` on the node
# used to find nothing and leave geocold-bench without libembree3.so.3).
root=${root:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}
embree_args=()
emb="$root/.deps/embree/lib/x86_64-linux-gnu"
if [ -f "$emb/libembree3.so.3.13.5.xz" ]; then
  [ -f "$emb/libembree3.so.3.13.5" ] || xz -dkc "$emb/libembree3.so.3.13.5.xz" > "$emb/libembree3.so.3.13.5"
  for lib in "$emb"/lib*.so.*[0-9]; do
    soname=$(basename "$lib" | sed -E 's/^(lib[a-z0-9_]+\.so\.[0-9]+).*/\1/')
    ln -sf "$(basename "$lib")" "$emb/$soname"
  done
  embree_args=(-Dembree_DIR="$emb/cmake/embree-3.13.5" -DTBB_DIR="$emb/cmake/TBB")
  export LD_LIBRARY_PATH="$emb${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
fi
