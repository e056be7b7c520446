#include "tools/bench/bench_options.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "host/util/error.h"
#include "tools/bench/bench_scenes.h"

namespace gc::bench {

namespace {

std::vector<std::string> split(const std::string& s)
{
    std::vector<std::string> out;
    std::stringstream in(s);
    std::string item;
    while (std::getline(in, item, ','))
        if (!item.empty()) out.push_back(item);
    return out;
}

}  // namespace

Options parse_options(int argc, char** argv)
{
    Options o;
    auto value = [&](int& i) -> std::string {
        if (i + 1 >= argc) throw UsageError(std::string(argv[i]) + " needs a value");
        return argv[++i];
    };
    auto integer = [&](int& i, long lo = 0, long hi = 1 << 20) {
        const std::string v = value(i);
        char* end = nullptr;
        const long n = std::strtol(v.c_str(), &end, 10);
        if (!end || *end || n < lo || n > hi)
            throw UsageError(std::string(argv[i - 1]) + " wants an integer from " +
                             std::to_string(lo) + " to " + std::to_string(hi) + ", got '" + v + "'");
        return static_cast<int>(n);
    };
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--device") o.device = value(i);
        else if (a == "--scene") o.scenes = split(value(i));
        else if (a == "--quick") o.quick = true;
        else if (a == "--json") o.json_out = true;
        else if (a == "--repeats") o.repeats = std::max(1, integer(i));
        else if (a == "--rays") o.ray_side = std::max(1, integer(i));
        else if (a == "--no-path") o.path = false;
        else if (a == "--no-rays") o.rays = false;
        else if (a == "--no-first-image") o.first_image = false;
        else if (a == "--no-packet-probe") o.packet_probe = false;
        else if (a == "--threads") o.threads = integer(i, 1, 4096);
        else if (a == "--wavefront") o.wavefront = integer(i, 1, 1 << 24);
        else if (a == "--samples-per-pass") o.samples_per_pass = integer(i, 0, 1 << 16);
        else if (a == "--first-image-child") o.first_image_child = value(i);
        else if (a == "--first-image-scene") o.first_image_scene = value(i);
        else if (a == "--list-device-keys") o.list_device_keys = true;
        else if (a == "--help" || a == "-h") {
            std::printf("usage: geocold-bench [--device all|gpu|cpu|N|text] [--scene cornell,bunny,dragon,large]\n"
                        "                     [--quick] [--json] [--repeats N] [--rays SIDE] [--no-path]\n"
                        "                     [--no-rays] [--no-first-image] [--no-packet-probe] [--threads N]\n"
                        "                     [--wavefront N] [--samples-per-pass N]\n"
                        "--threads N caps every CPU thread of the run: PoCL's workers, Embree's and the host's\n"
                        "(default: every core). With --threads 1 the per-core figure is one thread's, the\n"
                        "conditions of the Mitsuba llvm_ad_rgb anchor.\n"
                        "--json puts each scene's view in the document too; tools/bench/mitsuba_yardstick.py\n"
                        "reads it to time Mitsuba 3 on the same view in the same run (the anchors are fixed\n"
                        "figures from another day).\n"
                        "--wavefront N and --samples-per-pass N (0: the default) fix what the renderer otherwise\n"
                        "chooses per device: paths in flight per pass, and samples per pixel in one pass (a CPU\n"
                        "plans passes of half a second, in long runs up to two, and up to 256 samples:\n"
                        "host/render/pass_planner.h).\n");
            std::exit(0);
        } else {
            throw UsageError("unknown option '" + a + "' (see --help)");
        }
    }
    if (o.quick) {
        o.repeats = 1;
        o.ray_side = std::min(o.ray_side, 64);
        if (o.scenes.empty()) o.scenes = {"tiny"};
    }
    if (o.scenes.empty()) o.scenes = default_scene_names();
    return o;
}

}  // namespace gc::bench
