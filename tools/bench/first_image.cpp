#include "tools/bench/first_image.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "host/bvh/bvh.h"
#include "host/cl/context.h"
#include "host/cl/device.h"
#include "host/render/renderer.h"
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

int first_image_child(const std::string& key, bool tiny)
{
    const auto start = Clock::now();
    std::string why;
    auto s = load_bench_scene(tiny ? "tiny" : "cornell", default_shared_dir(), &why);
    if (!s) {
        std::fprintf(stderr, "first-image: %s\n", why.c_str());
        return 2;
    }
    const FlatBvh bvh = build_bvh(s->scene);
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
    settings.max_depth = 8;
    settings.rr_depth = 9;
    Renderer renderer(context, s->scene, bvh, s->camera, settings);
    const auto render_start = Clock::now();
    renderer.render_sample();
    const Film film = renderer.film();
    const double render = seconds_since(render_start);
    std::printf("first-image %.6f %.6f %.6f %d %.6f %.6f\n", seconds_since(start), renderer.program().build_seconds(),
                render, renderer.program().from_cache() ? 1 : 0, devices_seconds, context_seconds);
    return 0;
}

FirstImage run_first_image(const std::string& key, const std::string& cache_root, bool tiny)
{
    namespace fs = std::filesystem;
    FirstImage result;
    const fs::path root(cache_root);
    for (const char* sub : {"geocold", "pocl", "cuda"}) fs::create_directories(root / sub);
    const std::string exe = fs::read_symlink("/proc/self/exe").string();
    const std::string command = "GEOCOLD_CACHE_DIR=" + quoted((root / "geocold").string()) +
                                " POCL_CACHE_DIR=" + quoted((root / "pocl").string()) +
                                " CUDA_CACHE_PATH=" + quoted((root / "cuda").string()) + " " + quoted(exe) +
                                " --first-image-child " + quoted(key) + (tiny ? " --quick" : "");
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
                                             result.devices_seconds >> result.context_seconds) {
            result.ok = status == 0;
            result.from_cache = cached != 0;
        }
    }
    if (!result.ok) result.error = "child failed (status " + std::to_string(status) + "): " + output;
    return result;
}

}  // namespace gc::bench
