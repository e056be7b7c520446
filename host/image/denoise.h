// Denoising with Intel Open Image Denoise (OIDN), loaded at run time: the library is not in
// Debian 12, so tools/install-deps.sh installs PyPI's pyoidn (which carries
// libOpenImageDenoise.so.2, its CPU device and its weights) into a virtual environment and
// links its library folder to k_oidn_install_dir. Nothing links OIDN; a build without it
// denoises as soon as the library is installed.
#pragma once

#include <filesystem>
#include <string>

#include "host/image/film.h"

namespace gc {

inline constexpr const char* k_oidn_library_name = "libOpenImageDenoise.so.2";
// Where tools/install-deps.sh puts it (a link to pyoidn's library folder).
inline constexpr const char* k_oidn_install_dir = "/opt/geocold-cl/oidn/lib";

struct DenoiseOptions {
    // The library to load; empty: k_oidn_install_dir, then the system's search path.
    std::filesystem::path library;
    // The guides are noise-free (rendered with enough samples), so OIDN trusts them as they
    // are (its cleanAux parameter); false when they are as noisy as the colour.
    bool clean_aux = true;
    int threads = 0;  // 0: OIDN's default (every core)
};

// Whether OIDN can be loaded; when not, `why` names what was tried and how to install it.
bool denoiser_available(const DenoiseOptions& options, std::string* why = nullptr);

// The colour film denoised by OIDN's "RT" filter (HDR, linear RGB). `albedo` and `normal`
// (either may be null; normal needs albedo, as OIDN says) are guides of the same size.
// Alpha is kept from `color`. Throws DeviceError when the library cannot be loaded (naming
// how to install it) or OIDN fails, UsageError on mismatched sizes.
Film denoise(const Film& color, const Film* albedo, const Film* normal, const DenoiseOptions& options = {});

}  // namespace gc
