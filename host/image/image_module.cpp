#include "host/image/image_module.h"

#include <filesystem>
#include <future>
#include <mutex>
#include <system_error>
#include <vector>

#include <dlfcn.h>

namespace gc {
namespace {

namespace fs = std::filesystem;

struct Loaded {
    const ImageCodec* codec = nullptr;
    std::string error;
};

std::vector<fs::path> candidates(const fs::path& chosen)
{
    if (!chosen.empty()) return {chosen};
    std::vector<fs::path> paths;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        paths.push_back(exe.parent_path() / k_image_module_name);
        paths.push_back(exe.parent_path().parent_path() / k_image_module_install_dir / k_image_module_name);
    }
#ifdef GC_IMAGE_MODULE_BUILD_PATH
    paths.emplace_back(GC_IMAGE_MODULE_BUILD_PATH);
#endif
    return paths;
}

Loaded load(const fs::path& chosen)
{
    const std::vector<fs::path> paths = candidates(chosen);
    const fs::path* found = nullptr;
    std::error_code ec;
    for (const fs::path& path : paths) {
        if (fs::exists(path, ec)) {
            found = &path;
            break;
        }
    }
    // With the module chosen, let dlopen itself say what is wrong with that one file.
    if (!found && paths.size() == 1) found = &paths.front();
    if (!found) {
        std::string list;
        for (const fs::path& path : paths) list += (list.empty() ? "" : ", ") + path.string();
        return {nullptr, "the image module " + std::string(k_image_module_name) +
                             " was not found (tried " + list + "; GEOCOLD_IMAGE_MODULE names it)"};
    }
    const std::string name = found->string();
    // RTLD_NOW: every relocation is done here, on the loading thread, not at first call.
    void* handle = ::dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* why = ::dlerror();
        return {nullptr, "cannot load the image module " + name + ": " + (why ? why : "dlopen failed")};
    }
    // Never dlclose'd: the codec is used until exit.
    auto entry = reinterpret_cast<GcImageModuleEntry>(::dlsym(handle, GC_IMAGE_MODULE_ENTRY));
    if (!entry) {
        const char* why = ::dlerror();
        return {nullptr, "the image module " + name + " is not one this program can use (no " GC_IMAGE_MODULE_ENTRY
                         ": " + (why ? why : "dlsym failed") + "); it must come from the same build"};
    }
    const ImageCodec* codec = entry();
    if (!codec) return {nullptr, "the image module " + name + " returned no codec"};
    return {codec, {}};
}

std::mutex g_mutex;
fs::path g_chosen;  // set_image_module_path's file; empty: search
// From std::async: the last reference, destroyed at exit, waits for a load still running,
// so the process never tears down under the dynamic linker.
std::shared_future<Loaded> g_load;

void start_locked(std::launch policy)
{
    if (g_load.valid()) return;
    try {
        g_load = std::async(policy, load, g_chosen).share();
    } catch (const std::system_error&) {
        // No thread to be had: load when asked.
        g_load = std::async(std::launch::deferred, load, g_chosen).share();
    }
}

}  // namespace

void set_image_module_path(const std::filesystem::path& path)
{
    const std::lock_guard<std::mutex> lock(g_mutex);
    g_chosen = path;
}

void start_loading_image_module()
{
    const std::lock_guard<std::mutex> lock(g_mutex);
    start_locked(std::launch::async);
}

const ImageCodec* image_module(std::string* why)
{
    std::shared_future<Loaded> load_result;
    {
        const std::lock_guard<std::mutex> lock(g_mutex);
        start_locked(std::launch::deferred);
        load_result = g_load;
    }
    const Loaded& loaded = load_result.get();
    if (!loaded.codec && why) *why = loaded.error;
    return loaded.codec;
}

}  // namespace gc
