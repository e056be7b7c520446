// geocold-instances: the instancing stress scene. One mesh (the 100k-triangle dragon for the
// acceptance run) copied N times on a cubic grid under seeded random rotations, traced as a
// two-level BVH (kernels/trace_instances.cl) with one primary ray per pixel. Prints the device
// bytes of the meshes' trees and of the instances (and per instance), and writes the hit
// depth as a PGM when asked.
//
//     geocold-instances --mesh dragon.obj --instances 1000000 --device gpu --out depth.pgm
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "host/bvh/instance_bvh.h"
#include "host/cl/buffer.h"
#include "host/cl/context.h"
#include "host/cl/device.h"
#include "host/cl/program.h"
#include "host/math/to_device.h"
#include "host/render/device_bvh.h"
#include "host/scene/instances.h"
#include "host/scene/load.h"
#include "host/util/error.h"

namespace gc {
namespace {

struct Options {
    std::string mesh;
    std::size_t instances = 1000;
    std::string device = "any";
    std::string layout = "auto";
    int width = 256;
    int height = 256;
    std::uint32_t seed = 1;
    std::string out;
};

const char* kUsage =
    "Usage: geocold-instances --mesh FILE [options]\n"
    "  --mesh FILE        the mesh to copy (.obj or .gltf; its triangles become one mesh)\n"
    "  --instances N      copies on a cubic grid, each randomly rotated (default 1000)\n"
    "  --device SPEC      any, cpu, gpu, an index or a name (default any)\n"
    "  --layout L         auto, bvh2, bvh4 or bvh8: the meshes' tree layout (default auto)\n"
    "  --size WxH         primary rays (default 256x256)\n"
    "  --seed S           rotations' seed (default 1)\n"
    "  --out FILE.pgm     the hit depth as an 8-bit PGM\n"
    "Exit status: 0 success, 1 no ray hit, otherwise geocold-cl's codes (usage, input, device).\n";

Options parse(int argc, char** argv)
{
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw UsageError(a + " needs a value\n" + kUsage);
            return argv[++i];
        };
        if (a == "--mesh") o.mesh = value();
        else if (a == "--instances") o.instances = std::stoull(value());
        else if (a == "--device") o.device = value();
        else if (a == "--layout") o.layout = value();
        else if (a == "--size") {
            const std::string v = value();
            if (std::sscanf(v.c_str(), "%dx%d", &o.width, &o.height) != 2 || o.width <= 0 || o.height <= 0)
                throw UsageError("--size wants WxH, got '" + v + "'");
        } else if (a == "--seed") o.seed = static_cast<std::uint32_t>(std::stoul(value()));
        else if (a == "--out") o.out = value();
        else if (a == "-h" || a == "--help") {
            std::fputs(kUsage, stdout);
            std::exit(0);
        } else throw UsageError("unknown option '" + a + "'\n" + kUsage);
    }
    if (o.mesh.empty()) throw UsageError(std::string("--mesh is required\n") + kUsage);
    if (o.instances == 0 || o.instances > 0xfffffff0u) throw UsageError("--instances must be 1 .. 4294967280");
    return o;
}

double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The mesh on a side^3 grid (the first n cells), spaced 1.2 bounding diagonals apart.
InstancedScene make_scene(Scene mesh, std::size_t n, std::uint32_t seed, float& spacing, int& side)
{
    InstancedScene s;
    const Bounds3 b = mesh.bounds();
    const glm::vec3 centre = b.centroid().glm();
    spacing = 1.2f * length(b.diagonal());
    s.mesh_ranges.push_back({0u, static_cast<std::uint32_t>(mesh.triangle_count())});
    s.meshes = std::move(mesh);
    side = static_cast<int>(std::ceil(std::cbrt(static_cast<double>(n)) - 1e-9));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    s.instances.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3 cell(float(i % side), float((i / side) % side), float(i / (std::size_t(side) * side)));
        glm::vec3 axis(u(rng), u(rng), u(rng));
        axis = glm::length(axis) > 1e-3f ? glm::normalize(axis) : glm::vec3(0.0f, 1.0f, 0.0f);
        glm::mat4 m = glm::translate(glm::mat4(1.0f), spacing * cell);
        m = glm::rotate(m, 3.14159265f * u(rng), axis);
        m = glm::translate(m, -centre);
        s.instances.push_back({0u, m});
    }
    return s;
}

template <class Bvh>
int run(const Options& o, const cl::DeviceInfo& device, BvhLayout layout, const Bvh& bvh, float spacing, int side,
        std::size_t triangles_drawn)
{
    const cl::Context context(device);
    const cl::Program program(context, "trace_instances.cl", program_options(layout));
    auto tlas = cl::read_only_buffer(context, bvh.tlas, "tlas");
    auto instances = cl::read_only_buffer(context, bvh.instances, "instances");
    auto nodes = cl::read_only_buffer(context, bvh.nodes, "mesh nodes");
    auto tris = cl::read_only_buffer(context, bvh.tris, "mesh triangles");
    const std::uint64_t mesh_bytes = nodes.bytes() + tris.bytes();
    const std::uint64_t instance_bytes = tlas.bytes() + instances.bytes();
    std::printf("device %s, layout %s\n", device.device_name.c_str(), layout_name(layout));
    std::printf("device bytes: meshes %llu, instances %llu (%.1f per instance), total %llu for %zu triangles drawn "
                "(%.4f bytes per drawn triangle)\n",
                (unsigned long long)mesh_bytes, (unsigned long long)instance_bytes,
                double(instance_bytes) / double(o.instances), (unsigned long long)(mesh_bytes + instance_bytes),
                triangles_drawn, double(mesh_bytes + instance_bytes) / double(triangles_drawn));

    // A pinhole camera outside the grid's corner, looking at its far corner.
    const float extent = spacing * float(side);
    const glm::vec3 eye(-0.35f * extent, 0.6f * extent, -0.45f * extent);
    const glm::vec3 forward = glm::normalize(glm::vec3(extent) * 0.6f - eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
    const glm::vec3 up = glm::cross(right, forward);
    const float half = std::tan(0.5f * glm::radians(50.0f));
    std::vector<dev::GcRay> rays;
    rays.reserve(std::size_t(o.width) * o.height);
    for (int y = 0; y < o.height; ++y)
        for (int x = 0; x < o.width; ++x) {
            const float sx = (2.0f * (x + 0.5f) / o.width - 1.0f) * half * o.width / o.height;
            const float sy = (1.0f - 2.0f * (y + 0.5f) / o.height) * half;
            rays.push_back(dev::gc_make_ray(eye, glm::normalize(forward + sx * right + sy * up), 0.0f, GC_INFINITY));
        }
    const auto count = static_cast<std::uint32_t>(rays.size());
    auto ray_buf = cl::read_only_buffer(context, rays, "rays");
    auto hit_buf = cl::Buffer<dev::GcInstanceHit>::create(context, count, CL_MEM_WRITE_ONLY, "hits");
    auto occ_buf = cl::Buffer<std::uint32_t>::create(context, count, CL_MEM_WRITE_ONLY, "occluded");
    cl::Kernel kernel = program.kernel("trace_instances_closest");
    kernel.set_args(tlas, instances, nodes, tris, ray_buf, hit_buf, occ_buf, count);
    const auto t0 = std::chrono::steady_clock::now();
    kernel.launch(context, count);
    context.finish();
    const double trace_s = seconds_since(t0);
    std::vector<dev::GcInstanceHit> hits(count);
    hit_buf.read(hits);
    std::size_t hit_count = 0;
    float t_min = GC_INFINITY, t_max = 0.0f;
    for (const dev::GcInstanceHit& h : hits)
        if (h.instance != GC_INVALID) {
            ++hit_count;
            t_min = std::fmin(t_min, h.hit.t);
            t_max = std::fmax(t_max, h.hit.t);
        }
    std::printf("traced %u rays (closest + any) in %.3f s: %zu hits (%.1f %%)\n", count, trace_s, hit_count,
                100.0 * double(hit_count) / count);
    if (!o.out.empty()) {
        std::ofstream f(o.out, std::ios::binary);
        f << "P5\n" << o.width << " " << o.height << "\n255\n";
        for (const dev::GcInstanceHit& h : hits) {
            const float d = h.instance == GC_INVALID ? 0.0f : 1.0f - 0.8f * (h.hit.t - t_min) / std::fmax(t_max - t_min, 1e-6f);
            f.put(static_cast<char>(static_cast<unsigned char>(std::lround(255.0f * d))));
        }
        if (!f) throw InputError(o.out + ": cannot write the image");
    }
    return hit_count > 0 ? 0 : 1;
}

}  // namespace
}  // namespace gc

int main(int argc, char** argv)
{
    using namespace gc;
    try {
        const Options o = parse(argc, argv);
        const auto t0 = std::chrono::steady_clock::now();
        Scene mesh = load_scene(o.mesh);
        float spacing = 0.0f;
        int side = 0;
        const InstancedScene scene = make_scene(std::move(mesh), o.instances, o.seed, spacing, side);
        validate_instances(scene);
        std::printf("scene: %zu instances of %zu triangles = %.4g triangles drawn (loaded in %.2f s)\n",
                    scene.instances.size(), scene.meshes.triangle_count(), double(scene.instanced_triangle_count()),
                    seconds_since(t0));
        const auto t1 = std::chrono::steady_clock::now();
        const InstanceBvhParts parts = build_instance_bvh(scene);
        std::printf("two-level BVH built in %.2f s\n", seconds_since(t1));
        const cl::DeviceInfo device = cl::select_device(o.device);
        std::optional<BvhLayout> chosen;
        if (o.layout == "bvh2") chosen = BvhLayout::Binary;
        else if (o.layout == "bvh4") chosen = BvhLayout::Wide;
        else if (o.layout == "bvh8") chosen = BvhLayout::Wide8;
        else if (o.layout != "auto") throw UsageError("--layout wants auto, bvh2, bvh4 or bvh8");
        const BvhLayout layout = bvh_layout_for(device, chosen);
        const std::size_t drawn = scene.instanced_triangle_count();
        switch (layout) {
        case BvhLayout::Binary: return run(o, device, layout, assemble_binary(parts), spacing, side, drawn);
        case BvhLayout::Wide: return run(o, device, layout, assemble_wide(parts), spacing, side, drawn);
        case BvhLayout::Wide8: return run(o, device, layout, assemble_wide8(parts), spacing, side, drawn);
        }
        return 1;
    } catch (const Error& e) {
        std::fprintf(stderr, "geocold-instances: %s\n", e.what());
        return static_cast<int>(e.code());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "geocold-instances: %s\n", e.what());
        return 1;
    }
}
