// Finds and dlopen()s the image module (geocold-image-oiio.so, see image_codec.h), once per
// process, optionally on a background thread so that its ~0.35 s of dynamic linking overlaps
// other start-up work.
//
// Where it looks, first match wins:
//   set_image_module_path's file   when set: that file and nothing else
//   <dir of the executable>/geocold-image-oiio.so         (the build tree)
//   <dir of the executable>/../lib/geocold-cl/geocold-image-oiio.so   (cmake --install)
//   the build tree's module, by the absolute path compiled in (tests and tools that live in
//   other build folders)
#pragma once

#include <filesystem>
#include <string>

#include "host/image/image_codec.h"

namespace gc {

// The module's file name and its folder under an install prefix (CMake installs it there).
inline constexpr const char* k_image_module_name = "geocold-image-oiio.so";
inline constexpr const char* k_image_module_install_dir = "lib/geocold-cl";

// Loads `path` and nothing else (empty: search the usual places). The process's front end
// decides where the module is; this takes effect only before the first load starts.
void set_image_module_path(const std::filesystem::path& path);

// Starts loading the module on a background thread and returns at once; a no-op after the
// first call. A program that exits while the load runs waits for it at exit.
void start_loading_image_module();

// The module's codec, loading it now unless a load is under way (then waits for it). Null
// when it cannot be loaded: `why` then names the file(s) tried and dlerror()'s reason. The
// answer is the same for the whole process.
const ImageCodec* image_module(std::string* why);

}  // namespace gc
