#include "tools/bench/first_image.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <sys/wait.h>

#include "host/bvh/bvh.h"
#include "host/cl/context.h"
#include "host/cl/device.h"
#include "host/render/renderer.h"
#include "tools/bench/bench_environment.h"
#include "tools/bench/bench_scenes.h"
#include "tools/bench/timing.h"

namespace gc::bench {
namespace {

std::string quoted(const std::string& s)
{
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

}  // namespace

std::string device_key(const cl::DeviceInfo& device, const std::vector<cl::DeviceInfo>& devices)
{
    std::size_t ordinal = 0;
    for (const cl::DeviceInfo& d : devices) {
        if (d.id == device.id) break;
        if (d.platform_name == device.platform_name && d.device_name == device.device_name) ++ordinal;
    }
    return device.platform_name + " / " + device.device_name + " #" + std::to_string(ordinal);
}

int first_image_child(const std::string& key, const std::string& scene_name)
{
    const auto start = Clock::now();
    std::string why;
    auto s = load_bench_scene(scene_name, default_shared_dir(), &why);
    if (!s) {
        std::printf("first-image-skipped %s\n", why.c_str());
        return kFirstImageSceneMissing;
    }
    const FlatBvh bvh = build_bvh(s->scene);
    const double scene_seconds = seconds_since(start);
    std::string why_none;
    const auto devices_start = Clock::now();
    const std::vector<cl::DeviceInfo> devices = cl::list_devices(&why_none);
    const double devices_seconds = seconds_since(devices_start);
    const cl::DeviceInfo* device = nullptr;
    for (const cl::DeviceInfo& d : devices)
        if (device_key(d, devices) == key) device = &d;
    if (!device) {
        std::fprintf(stderr, "first-image: no OpenCL device '%s' in this process; it sees:\n%s%s%s\n", key.c_str(),
                     cl::format_device_list(devices).c_str(), why_none.empty() ? "" : "  why: ", why_none.c_str());
        return 2;
    }
    const auto context_start = Clock::now();
    const cl::Context context(*device);
    const double context_seconds = seconds_since(context_start);
    RenderSettings settings;
    settings.width = s->pt_width;
    settings.height = s->pt_height;
    settings.env_radiance = s->env;
    settings.max_depth = 8;
    settings.rr_depth = 9;
    const auto renderer_start = Clock::now();
    Renderer renderer(context, s->scene, bvh, s->camera, settings, bench_render_setup());
    // The renderer's constructor uploads the scene and builds the program; the rest of its
    // time, past the program's, is the device layout (BVH4/8 collapse) and the buffers.
    const double upload_seconds = std::max(0.0, seconds_since(renderer_start) - renderer.program().build_seconds());
    const auto render_start = Clock::now();
    renderer.render_sample();
    const Film film = renderer.film();
    const double render = seconds_since(render_start);
    std::printf("first-image %.6f %.6f %.6f %d %.6f %.6f %.6f %.6f\n", seconds_since(start),
                renderer.program().build_seconds(), render, renderer.program().from_cache() ? 1 : 0, devices_seconds,
                context_seconds, scene_seconds, upload_seconds);
    return 0;
}

FirstImage run_first_image(const std::string& key, const std::string& scene, const std::string& cache_root)
{
    namespace fs = std::filesystem;
    FirstImage result;
    const fs::path root(cache_root);
    for (const char* sub : {"geocold", "pocl", "cuda"}) fs::create_directories(root / sub);
    const std::string exe = fs::read_symlink("/proc/self/exe").string();
    const std::string command = "GEOCOLD_CACHE_DIR=" + quoted((root / "geocold").string()) +
                                " POCL_CACHE_DIR=" + quoted((root / "pocl").string()) +
                                " CUDA_CACHE_PATH=" + quoted((root / "cuda").string()) + " " + quoted(exe) +
                                " --first-image-child " + quoted(key) + " --first-image-scene " + quoted(scene);
    const auto start = Clock::now();
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) {
        result.error = "popen failed";
        return result;
    }
    std::string output;
    char buffer[256];
    while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
    const int status = pclose(pipe);
    result.process_seconds = seconds_since(start);
    std::istringstream in(output);
    std::string word;
    int cached = 0;
    while (in >> word) {
        if (word == "first-image" && in >> result.total_seconds >> result.compile_seconds >> result.render_seconds >> cached >>
                                             result.devices_seconds >> result.context_seconds >> result.scene_seconds >>
                                             result.upload_seconds) {
            result.ok = status == 0;
            result.from_cache = cached != 0;
        } else if (word == "first-image-skipped" && WIFEXITED(status) && WEXITSTATUS(status) == kFirstImageSceneMissing) {
            std::getline(in >> std::ws, result.error);
            result.skipped = true;
            return result;
        }
    }
    if (!result.ok) result.error = "child failed (status " + std::to_string(status) + "): " + output;
    return result;
}

}  // namespace gc::bench
