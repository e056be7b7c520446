// geocold-instances: the instancing stress scene. One mesh (the 100k-triangle dragon for the
// acceptance run) copied N times on a cubic grid under seeded random rotations, rendered
// through the two-level BVH (DeviceScene::upload_instanced and a Renderer, as geocold-cl
// renders a glTF that reuses meshes) as first-hit AOVs (aov.cl, one sample per pixel) or, with
// --spp, path traced under a white sky. Prints the device bytes of the meshes and of the
// instances (and per instance), and writes the image when asked.
//
//     geocold-instances --mesh dragon.obj --instances 1000000 --device gpu --out dragons.png
//     geocold-instances --mesh dragon.obj --instances 1000000 --spp 16 --out dragons-path.png
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "host/bvh/bvh.h"
#include "host/bvh/instance_bvh.h"
#include "host/image/image_io.h"
#include "host/cl/buffer.h"
#include "host/cl/context.h"
#include "host/cl/device.h"
#include "host/cl/program.h"
#include "host/math/to_device.h"
#include "host/render/device_bvh.h"
#include "host/render/device_scene.h"
#include "host/render/integrator.h"
#include "host/render/renderer.h"
#include "host/render/scene_convert.h"
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
    AovKind aov = AovKind::Preview;
    std::uint32_t spp = 0;  // 0: the AOV; else path traced with this many samples per pixel
};

const char* kUsage =
    "Usage: geocold-instances --mesh FILE [options]\n"
    "  --mesh FILE        the mesh to copy (.obj or .gltf; its triangles become one mesh)\n"
    "  --instances N      copies on a cubic grid, each randomly rotated (default 1000)\n"
    "  --device SPEC      any, cpu, gpu, an index or a name (default any)\n"
    "  --layout L         auto, bvh2, bvh4 or bvh8: the meshes' tree layout (default auto)\n"
    "  --size WxH         primary rays (default 256x256)\n"
    "  --seed S           rotations' seed (default 1)\n"
    "  --aov NAME         preview, albedo, normal, depth or primid (default preview)\n"
    "  --spp N            path trace N samples per pixel under a white sky instead of the AOV\n"
    "  --out FILE         the image (.png, .exr, ...; linear formats keep the values)\n"
    "Exit status: 0 success, 1 no ray hit (path: a black image), otherwise geocold-cl's codes (usage, input, device).\n";

std::optional<BvhLayout> layout_of(const Options& o)
{
    if (o.layout == "bvh2") return BvhLayout::Binary;
    if (o.layout == "bvh4") return BvhLayout::Wide;
    if (o.layout == "bvh8") return BvhLayout::Wide8;
    return std::nullopt;
}

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
        else if (a == "--spp") o.spp = static_cast<std::uint32_t>(std::stoul(value()));
        else if (a == "--aov") {
            const std::string v = value();
            const std::optional<AovKind> k = aov_from_name(v);
            if (!k) throw UsageError("--aov: unknown AOV '" + v + "'");
            o.aov = *k;
        }
        else if (a == "-h" || a == "--help") {
            std::fputs(kUsage, stdout);
            std::exit(0);
        } else throw UsageError("unknown option '" + a + "'\n" + kUsage);
    }
    if (o.mesh.empty()) throw UsageError(std::string("--mesh is required\n") + kUsage);
    if (o.layout != "auto" && !layout_of(o)) throw UsageError("--layout wants auto, bvh2, bvh4 or bvh8");
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

// A pinhole camera just outside the grid's corner, looking along its diagonal: the nearest
// copies fill the foreground, the rest recede to the far corner.
Camera grid_camera(float spacing, int side)
{
    const float extent = spacing * float(side);
    Camera camera;
    camera.look_from = Point3(-1.2f * spacing, 0.5f * extent, -1.6f * spacing);
    camera.look_at = Point3(extent, 0.35f * extent, extent);
    camera.vfov_degrees = 50.0f;
    return camera;
}

void write_film(const Options& o, const Film& film, const std::string& device, const char* integrator, double seconds)
{
    if (o.out.empty()) return;
    ImageMetadata meta;
    meta.device = device;
    meta.integrator = integrator;
    meta.scene = o.mesh + " x " + std::to_string(o.instances);
    meta.spp = o.spp > 0 ? o.spp : 1;
    meta.seconds = seconds;
    write_image(o.out, film, meta);
}

// Renders o.aov (one sample) or, with o.spp, the path tracer under a white sky.
int run(const Options& o, const cl::DeviceInfo& device, const InstancedScene& scene, const InstanceBvhParts& parts,
        float spacing, int side)
{
    const cl::Context context(device);
    DeviceTuning tuning;
    tuning.bvh_layout = bvh_layout_for(device, layout_of(o));
    auto device_scene =
        std::make_shared<const DeviceScene>(DeviceScene::upload_instanced(context, scene, parts, {}, tuning));
    const std::uint64_t instance_bytes =
        device_scene->instance_level.tlas.bytes() + device_scene->instance_level.instances.bytes();
    const std::uint64_t mesh_bytes = device_scene->bytes() - instance_bytes;
    const std::size_t drawn = scene.instanced_triangle_count();
    std::printf("device %s, layout %s\n", device.device_name.c_str(), layout_name(device_scene->bvh.layout()));
    std::printf("device bytes: meshes %llu (trees and shading data), instances %llu (%.1f per instance), total %llu "
                "for %zu triangles drawn (%.4f bytes per drawn triangle)\n",
                (unsigned long long)mesh_bytes, (unsigned long long)instance_bytes,
                double(instance_bytes) / double(o.instances), (unsigned long long)(mesh_bytes + instance_bytes), drawn,
                double(mesh_bytes + instance_bytes) / double(drawn));
    const bool path = o.spp > 0;
    RenderSettings settings;
    settings.width = o.width;
    settings.height = o.height;
    settings.spp = path ? o.spp : 1;
    if (path) {
        settings.env_radiance = glm::vec3(1.0f);
    } else {
        settings.integrator = IntegratorKind::Aov;
        settings.aov = o.aov;
    }
    RenderSetup setup;
    setup.tuning = tuning;
    Renderer renderer(context, device_scene, grid_camera(spacing, side), settings, setup);
    const auto t0 = std::chrono::steady_clock::now();
    renderer.render(0, settings.spp);
    const double render_s = seconds_since(t0);
    const Film film = renderer.film();
    double mean = 0.0;
    std::size_t lit = 0;
    for (std::uint32_t y = 0; y < film.height(); ++y)
        for (std::uint32_t x = 0; x < film.width(); ++x) {
            const Rgba v = film.at(x, y);
            mean += v.g;
            lit += v.r != 0.0f || v.g != 0.0f || v.b != 0.0f;
        }
    const double pixels = double(film.width()) * film.height();
    mean /= pixels;
    if (path)
        std::printf("path traced %dx%d, %u spp in %.3f s (%.2f Msamples/s), mean green %.4f\n", o.width, o.height,
                    o.spp, render_s, pixels * o.spp / render_s * 1e-6, mean);
    else
        std::printf("rendered %dx%d (%s, 1 sample) in %.3f s: %zu pixels on geometry (%.1f %%)\n", o.width, o.height,
                    aov_name(o.aov), render_s, lit, 100.0 * double(lit) / pixels);
    write_film(o, film, device.device_name, path ? "path" : "aov", render_s);
    return (path ? mean > 0.0 : lit > 0) ? 0 : 1;
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
        return run(o, cl::select_device(o.device), scene, parts, spacing, side);
    } catch (const Error& e) {
        std::fprintf(stderr, "geocold-instances: %s\n", e.what());
        return static_cast<int>(e.code());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "geocold-instances: %s\n", e.what());
        return 1;
    }
}
