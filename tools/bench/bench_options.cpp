#include "tools/bench/bench_options.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "host/util/error.h"
#include "tools/bench/bench_scenes.h"

namespace gc::bench {

namespace {

constexpr const char* kUsage =
    "Usage: geocold-bench [options]\n"
    "\n"
    "Measures, per OpenCL device and scene: BVH build speed and SAH cost; primary, diffuse and\n"
    "shadow rays per second; path-traced samples per second (max depth 8, no Russian roulette);\n"
    "time to first image with a cold and a warm kernel cache. On CPUs Embree 3 builds and traces\n"
    "the same triangles and rays on the same cores in interleaved rounds, and each figure is\n"
    "printed with its ratio to Embree's (the median of the per-round ratios). GPU ray figures\n"
    "also give their share of a memory and an instruction-issue roofline.\n"
    "\n"
    "What and where:\n"
    "  --device SPEC         all (default) | gpu | cpu | <index> | <name substring>, as\n"
    "                        geocold-cl --list-devices shows them\n"
    "  --scene LIST          comma-separated, from cornell, bunny, dragon, large, tiny (default:\n"
    "                        cornell,bunny,dragon,large). The bunny and the dragon are read from\n"
    "                        $GEOCOLD_SHARED_DIR/scenes (else from shared/ in or beside the\n"
    "                        source tree) and skipped with a note when missing; large is a\n"
    "                        5.2M-triangle mesh made on the spot; tiny is the Cornell box at\n"
    "                        64x64\n"
    "  --threads N           cap every CPU thread of the run: PoCL's workers, Embree's and the\n"
    "                        host's (default: every core). With --threads 1 the per-core figure\n"
    "                        is one thread's, the conditions of the Mitsuba llvm_ad_rgb anchor\n"
    "How much:\n"
    "  --quick               one repeat, 64x64 rays, the tiny scene unless --scene says\n"
    "                        otherwise: a smoke test, not a measurement\n"
    "  --repeats N           timed repeats or interleaved rounds per figure (default 5)\n"
    "  --rays SIDE           SIDE x SIDE primary rays, from whose hits the diffuse and shadow\n"
    "                        rays start (default 1024). A GPU launch traces its set several\n"
    "                        times over, up to 2^22 rays, and the set alone is printed beside\n"
    "                        it\n"
    "  --no-rays             skip the ray figures\n"
    "  --no-path             skip the path-tracing figures\n"
    "  --no-first-image      skip the time to first image\n"
    "  --no-packet-probe     skip the explicit-SIMD probe (kernels/test/packet_probe.cl)\n"
    "Renderer settings (0: the renderer's own choice, as geocold-cl makes it):\n"
    "  --wavefront N         paths in flight per pass\n"
    "  --samples-per-pass N  samples per pixel in one pass (a CPU plans passes of half a second,\n"
    "                        in long runs up to two, and up to 256 samples:\n"
    "                        host/render/pass_planner.h)\n"
    "Output:\n"
    "  --json                the figures as one JSON document on stdout (the text goes to\n"
    "                        stderr), with each scene's view: tools/bench/mitsuba_yardstick.py\n"
    "                        reads it to time Mitsuba 3 on the same view in the same run\n"
    "  -h, --help            this text\n"
    "\n"
    "Exit status: 0 success, 1 a failed measurement (a device error, packets that disagree with\n"
    "single rays), 2 bad command line.\n";

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
            std::fputs(kUsage, stdout);
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
