#include "tools/bench/measure_first_images.h"

#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include "tools/bench/bench_devices.h"
#include "tools/bench/bench_output.h"
#include "tools/bench/first_image.h"

namespace gc::bench {

// Time to first image, each scene on each device in fresh child processes with fresh caches
// (a cold start compiles the program each scene's features ask for). The parent must not
// have touched OpenCL yet: on the lent H200 node a child started after the parent had merely
// enumerated the NVIDIA platform no longer saw it (while the same child started from a shell
// did), so even the device list comes from a child here.
void measure_first_images(const Options& o, nlohmann::json& doc)
{
    if (!o.first_image) return;
    say("\n== time to first image (each scene's path view, 1 sample, depth 8, a fresh process; cold: empty "
        "kernel caches) ==\n");
    std::vector<std::pair<std::string, std::string>> devices;  // label, key
    {
        const std::string exe = std::filesystem::read_symlink("/proc/self/exe").string();
        FILE* pipe = popen(("'" + exe + "' --list-device-keys --device '" + o.device + "'").c_str(), "r");
        if (!pipe) {
            say("  failed: cannot start the device-list child\n");
            return;
        }
        char line[1024];
        while (std::fgets(line, sizeof line, pipe)) {
            std::string text(line);
            while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
            const std::size_t tab = text.find('\t');
            if (tab != std::string::npos) devices.emplace_back(text.substr(0, tab), text.substr(tab + 1));
        }
        pclose(pipe);
    }
    for (const std::string& scene : o.scenes) {
        for (std::size_t i = 0; i < devices.size(); ++i) {
            const auto& [name, key] = devices[i];
            namespace fs = std::filesystem;
            const fs::path root =
                fs::temp_directory_path() / ("geocold-bench-cache-" + std::to_string(::getpid()) + "-" + std::to_string(i));
            fs::remove_all(root);
            fs::create_directories(root);
            const FirstImage cold = run_first_image(key, scene, root.string());
            const FirstImage warm = cold.skipped ? cold : run_first_image(key, scene, root.string());
            fs::remove_all(root);
            if (cold.skipped) {
                say("  %s: skipped (%s)\n", scene.c_str(), cold.error.c_str());
                doc["first_image"][scene] = {{"skipped", cold.error}};
                break;
            }
            for (const auto& [label, fi] : {std::pair<const char*, const FirstImage&>{"cold", cold}, {"warm", warm}}) {
                if (!fi.ok) {
                    say("  %s %s %s: failed: %s\n", scene.c_str(), name.c_str(), label, fi.error.c_str());
                    continue;
                }
                say("  %s %s %s: %.3f s in process (%.3f s wall with process start): scene + BVH %.3f s, device "
                    "layout %.3f s, program %s %.3f s, first sample + read-back %.3f s; devices listed %.3f s, "
                    "context %.3f s\n",
                    scene.c_str(), name.c_str(), label, fi.total_seconds, fi.process_seconds, fi.scene_seconds,
                    fi.upload_seconds, fi.from_cache ? "from cache" : "compiled", fi.compile_seconds, fi.render_seconds,
                    fi.devices_seconds, fi.context_seconds);
                doc["first_image"][scene][name][label] = {
                    {"seconds", fi.total_seconds},       {"process_seconds", fi.process_seconds},
                    {"scene_seconds", fi.scene_seconds}, {"upload_seconds", fi.upload_seconds},
                    {"compile_seconds", fi.compile_seconds}, {"render_seconds", fi.render_seconds},
                    {"from_cache", fi.from_cache},       {"devices_seconds", fi.devices_seconds},
                    {"context_seconds", fi.context_seconds}};
            }
        }
    }
}

int list_device_keys(const Options& o)
{
    std::string why;
    const std::vector<cl::DeviceInfo> all = cl::list_devices(&why);
    for (const DeviceSlot& d : selected_devices(o, all)) std::printf("%s\t%s\n", d.label().c_str(), device_key(d.info, all).c_str());
    return 0;
}

}  // namespace gc::bench
