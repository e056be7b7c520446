#include "host/image/denoise.h"

#include <map>
#include <mutex>
#include <system_error>
#include <vector>

#include <dlfcn.h>

#include "host/image/oidn_api.h"
#include "host/util/error.h"

namespace gc {
namespace {

namespace fs = std::filesystem;

struct Oidn {
    oidnNewDevice_t new_device = nullptr;
    oidnCommitDevice_t commit_device = nullptr;
    oidnSetDeviceInt_t set_device_int = nullptr;
    oidnGetDeviceError_t get_device_error = nullptr;
    oidnReleaseDevice_t release_device = nullptr;
    oidnNewFilter_t new_filter = nullptr;
    oidnSetSharedFilterImage_t set_shared_filter_image = nullptr;
    oidnSetFilterBool_t set_filter_bool = nullptr;
    oidnCommitFilter_t commit_filter = nullptr;
    oidnExecuteFilter_t execute_filter = nullptr;
    oidnReleaseFilter_t release_filter = nullptr;
};

struct Loaded {
    Oidn api;
    std::string error;  // empty when loaded
};

const char* k_install_hint =
    "install it with tools/install-deps.sh (PyPI's pyoidn in a virtual environment, linked to "
    "/opt/geocold-cl/oidn), or install Open Image Denoise 2 system-wide, or name the library with "
    "GEOCOLD_OIDN_LIBRARY";

template <class F>
bool symbol(void* handle, const char* name, F& out, std::string& error)
{
    out = reinterpret_cast<F>(::dlsym(handle, name));
    if (!out && error.empty()) error = std::string("it has no ") + name + " (OIDN 2 is needed)";
    return out != nullptr;
}

Loaded load(const fs::path& chosen)
{
    // dlopen by name searches LD_LIBRARY_PATH, the ld.so cache and the system folders.
    std::vector<std::string> names;
    if (!chosen.empty()) names.push_back(chosen.string());
    else {
        names.push_back((fs::path(k_oidn_install_dir) / k_oidn_library_name).string());
        names.emplace_back(k_oidn_library_name);
    }
    std::string tried;
    void* handle = nullptr;
    std::string name;
    for (const std::string& candidate : names) {
        handle = ::dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (handle) {
            name = candidate;
            break;
        }
        const char* why = ::dlerror();
        tried += (tried.empty() ? "" : "; ") + (why ? std::string(why) : candidate);
    }
    Loaded loaded;
    if (!handle) {
        loaded.error = "Open Image Denoise (" + std::string(k_oidn_library_name) + ") cannot be loaded (" + tried +
                       "): " + k_install_hint;
        return loaded;
    }
    // Never dlclose'd: OIDN keeps threads and device modules for the process's life.
    Oidn& a = loaded.api;
    std::string error;
    symbol(handle, "oidnNewDevice", a.new_device, error);
    symbol(handle, "oidnCommitDevice", a.commit_device, error);
    symbol(handle, "oidnSetDeviceInt", a.set_device_int, error);
    symbol(handle, "oidnGetDeviceError", a.get_device_error, error);
    symbol(handle, "oidnReleaseDevice", a.release_device, error);
    symbol(handle, "oidnNewFilter", a.new_filter, error);
    symbol(handle, "oidnSetSharedFilterImage", a.set_shared_filter_image, error);
    symbol(handle, "oidnSetFilterBool", a.set_filter_bool, error);
    symbol(handle, "oidnCommitFilter", a.commit_filter, error);
    symbol(handle, "oidnExecuteFilter", a.execute_filter, error);
    symbol(handle, "oidnReleaseFilter", a.release_filter, error);
    if (!error.empty()) loaded.error = "the Open Image Denoise library " + name + " is not one this program can use: " + error;
    return loaded;
}

const Loaded& library(const fs::path& chosen)
{
    static std::mutex mutex;
    static std::map<fs::path, Loaded> loaded;
    const std::lock_guard<std::mutex> lock(mutex);
    auto it = loaded.find(chosen);
    if (it == loaded.end()) it = loaded.emplace(chosen, load(chosen)).first;
    return it->second;
}

// Releases the device and filter however denoise() leaves.
struct Handles {
    const Oidn& api;
    OIDNDevice device = nullptr;
    OIDNFilter filter = nullptr;
    ~Handles()
    {
        if (filter) api.release_filter(filter);
        if (device) api.release_device(device);
    }
    void check(const char* what) const
    {
        const char* message = nullptr;
        if (api.get_device_error(device, &message) != OIDN_ERROR_NONE)
            throw DeviceError(std::string("Open Image Denoise: ") + what + " failed: " +
                              (message ? message : "no message"));
    }
};

void check_size(const Film& color, const Film* guide, const char* name)
{
    if (guide && (guide->width() != color.width() || guide->height() != color.height()))
        throw UsageError(std::string("denoise: the ") + name + " guide is " + std::to_string(guide->width()) + "x" +
                         std::to_string(guide->height()) + ", the colour " + std::to_string(color.width()) + "x" +
                         std::to_string(color.height()));
}

}  // namespace

bool denoiser_available(const DenoiseOptions& options, std::string* why)
{
    const Loaded& loaded = library(options.library);
    if (!loaded.error.empty() && why) *why = loaded.error;
    return loaded.error.empty();
}

Film denoise(const Film& color, const Film* albedo, const Film* normal, const DenoiseOptions& options)
{
    check_size(color, albedo, "albedo");
    check_size(color, normal, "normal");
    if (normal && !albedo) throw UsageError("denoise: a normal guide needs an albedo guide too (OIDN's rule)");
    const Loaded& loaded = library(options.library);
    if (!loaded.error.empty()) throw DeviceError(loaded.error);
    if (color.empty()) return color;

    Handles h{loaded.api};
    h.device = h.api.new_device(OIDN_DEVICE_TYPE_CPU);
    if (!h.device) throw DeviceError("Open Image Denoise: no CPU device (this CPU may lack SSE4.1)");
    h.check("creating the CPU device");
    if (options.threads > 0) h.api.set_device_int(h.device, "numThreads", options.threads);
    h.api.commit_device(h.device);
    h.check("committing the CPU device");
    h.filter = h.api.new_filter(h.device, "RT");
    h.check("creating the RT filter");

    // The films are RGBA floats: OIDN reads and writes their RGB through a 16-byte stride.
    Film output = color;
    const size_t stride = 4 * sizeof(float);
    auto bind = [&](const char* name, const Film& film) {
        h.api.set_shared_filter_image(h.filter, name, const_cast<float*>(film.data().data()), OIDN_FORMAT_FLOAT3,
                                      film.width(), film.height(), 0, stride, stride * film.width());
    };
    bind("color", color);
    if (albedo) bind("albedo", *albedo);
    if (normal) bind("normal", *normal);
    bind("output", output);
    h.api.set_filter_bool(h.filter, "hdr", true);
    h.api.set_filter_bool(h.filter, "cleanAux", options.clean_aux && albedo);
    h.api.commit_filter(h.filter);
    h.check("committing the filter");
    h.api.execute_filter(h.filter);
    h.check("denoising");
    return output;
}

}  // namespace gc
