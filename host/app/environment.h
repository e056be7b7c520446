// The environment variables geocold-cl documents (--help's "Environment" section, README),
// read in this one place: the libraries take their settings as values, and the front ends
// (geocold-cl, geocold-bench) turn the variables into those values here.
#pragma once

#include <filesystem>

#include "host/render/render_setup.h"

namespace gc {

// GEOCOLD_BVH_WIDTH, GEOCOLD_KERNEL_FEATURES and GEOCOLD_PATH_KERNEL into the tuning;
// GEOCOLD_KERNEL_DIR, GEOCOLD_NO_CACHE, GEOCOLD_CACHE_DIR (else $XDG_CACHE_HOME or $HOME),
// GEOCOLD_CACHE_ALWAYS and POCL_KERNEL_CACHE into the build config. Unset or empty means the
// default; a value outside a variable's choices is a UsageError naming the variable.
RenderSetup render_setup_from_environment();

// GEOCOLD_IMAGE_MODULE: the image module to load, or empty to search beside the executable.
std::filesystem::path image_module_from_environment();

// GEOCOLD_OIDN_LIBRARY: Open Image Denoise's library for --denoise, or empty to look where
// tools/install-deps.sh puts it, then on the system's library path.
std::filesystem::path oidn_library_from_environment();

}  // namespace gc
