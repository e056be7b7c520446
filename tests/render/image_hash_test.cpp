// Every integrator's image, as bits, against hashes stored in
// tests/data/image-hashes/integrators.txt. The hashes were taken before the library-core
// refactor moved the integrators behind one interface; a refactor of the host or a reshuffle
// of kernels/shared that changes no arithmetic must leave every one of them as it is. A
// deliberate change of the images (a new estimator, a fixed bug) regenerates the file: run the
// test with GEOCOLD_WRITE_IMAGE_HASHES=1 and say why in the commit.
//
// The images are a pure function of the scene and the settings on every device that passes
// --consistency at 100 % (docs/design.md), so one file holds for all of them; the test renders
// on the first OpenCL device.
#include <gtest/gtest.h>

#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "host/bvh/bvh.h"
#include "host/image/image_io.h"
#include "host/render/renderer.h"
#include "host/scene/load.h"
#include "tests/cl/cl_test_util.h"

namespace gc {
namespace {

namespace fs = std::filesystem;

struct HashCase {
    const char* name;
    const char* scene;  // relative to the source tree
    IntegratorKind integrator;
    AovKind aov;
    PathKernelForm form;
    bool point_light_and_env_map;
    // The hashes taken before the library core drew independent samples; the Sobol sampler
    // (the default since) has cases of its own.
    SamplerKind sampler = SamplerKind::Independent;
};

constexpr HashCase kCases[] = {
    {"original-path-megakernel", "scenes/cornell-box/CornellBox-Original.obj", IntegratorKind::Path, AovKind::Preview,
     PathKernelForm::Megakernel, false},
    {"original-path-wavefront", "scenes/cornell-box/CornellBox-Original.obj", IntegratorKind::Path, AovKind::Preview,
     PathKernelForm::Wavefront, false},
    {"sphere-path-megakernel", "scenes/cornell-box/CornellBox-Sphere.obj", IntegratorKind::Path, AovKind::Preview,
     PathKernelForm::Megakernel, false},
    {"mirror-env-path-wavefront", "scenes/cornell-box/CornellBox-Mirror.obj", IntegratorKind::Path, AovKind::Preview,
     PathKernelForm::Wavefront, true},
    {"mirror-env-path-megakernel", "scenes/cornell-box/CornellBox-Mirror.obj", IntegratorKind::Path, AovKind::Preview,
     PathKernelForm::Megakernel, true},
    {"textured-path-megakernel", "tests/data/scenes/box-textured/BoxTextured-PointLight.gltf", IntegratorKind::Path,
     AovKind::Preview, PathKernelForm::Megakernel, false},
    {"sphere-whitted", "scenes/cornell-box/CornellBox-Sphere.obj", IntegratorKind::Whitted, AovKind::Preview,
     PathKernelForm::Auto, false},
    {"mirror-env-whitted", "scenes/cornell-box/CornellBox-Mirror.obj", IntegratorKind::Whitted, AovKind::Preview,
     PathKernelForm::Auto, true},
    {"textured-aov-preview", "tests/data/scenes/box-textured/BoxTextured.gltf", IntegratorKind::Aov, AovKind::Preview,
     PathKernelForm::Auto, false},
    {"textured-aov-albedo", "tests/data/scenes/box-textured/BoxTextured.gltf", IntegratorKind::Aov, AovKind::Albedo,
     PathKernelForm::Auto, false},
    {"sphere-aov-normal", "scenes/cornell-box/CornellBox-Sphere.obj", IntegratorKind::Aov, AovKind::Normal,
     PathKernelForm::Auto, false},
    {"sphere-aov-depth", "scenes/cornell-box/CornellBox-Sphere.obj", IntegratorKind::Aov, AovKind::Depth,
     PathKernelForm::Auto, false},
    {"sphere-aov-primid", "scenes/cornell-box/CornellBox-Sphere.obj", IntegratorKind::Aov, AovKind::PrimitiveId,
     PathKernelForm::Auto, false},
    {"original-path-megakernel-sobol", "scenes/cornell-box/CornellBox-Original.obj", IntegratorKind::Path,
     AovKind::Preview, PathKernelForm::Megakernel, false, SamplerKind::Sobol},
    {"original-path-wavefront-sobol", "scenes/cornell-box/CornellBox-Original.obj", IntegratorKind::Path,
     AovKind::Preview, PathKernelForm::Wavefront, false, SamplerKind::Sobol},
    {"mirror-env-whitted-sobol", "scenes/cornell-box/CornellBox-Mirror.obj", IntegratorKind::Whitted,
     AovKind::Preview, PathKernelForm::Auto, true, SamplerKind::Sobol},
};

// FNV-1a over the pixels' float bits, row by row.
std::uint64_t image_hash(const Film& film)
{
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (std::uint32_t y = 0; y < film.height(); ++y)
        for (std::uint32_t x = 0; x < film.width(); ++x) {
            const Rgba p = film.at(x, y);
            const float c[4] = {p.r, p.g, p.b, p.a};
            unsigned char bytes[sizeof c];
            std::memcpy(bytes, c, sizeof c);
            for (unsigned char b : bytes) h = (h ^ b) * 0x100000001b3ull;
        }
    return h;
}

fs::path hash_file() { return fs::path(GC_TEST_SOURCE_DIR) / "tests/data/image-hashes/integrators.txt"; }

std::map<std::string, std::string> read_hashes()
{
    std::map<std::string, std::string> hashes;
    std::ifstream in(hash_file());
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream fields(line);
        std::string name, hash;
        if (fields >> name >> hash) hashes[name] = hash;
    }
    return hashes;
}

class ImageHashTest : public cl::test::DeviceTest {};

Film render_case(const cl::Context& context, const HashCase& c, const fs::path& env_map)
{
    Scene scene = load_scene(fs::path(GC_TEST_SOURCE_DIR) / c.scene);
    RenderSettings settings;
    settings.width = 40;
    settings.height = 32;
    settings.spp = c.integrator == IntegratorKind::Aov ? 1 : 6;
    settings.max_depth = 6;
    settings.rr_depth = 3;
    settings.seed = 7;
    settings.integrator = c.integrator;
    settings.aov = c.aov;
    settings.sampler = c.sampler;
    if (c.point_light_and_env_map) {
        scene.point_lights.push_back({Point3(0.3f, 1.5f, 0.5f), glm::vec3(0.8f, 0.6f, 0.4f)});
        settings.env_map_path = env_map.string();
    }
    Camera camera;
    camera.look_from = Point3(0, 1, 3.9f);
    camera.look_at = Point3(0, 1, 0);
    camera.vfov_degrees = 39.3077f;
    if (std::strstr(c.scene, "box-textured")) {
        camera.look_from = Point3(1.6f, 1.3f, 2.2f);
        camera.look_at = Point3(0, 0, 0);
        camera.vfov_degrees = 40.0f;
    }
    const FlatBvh bvh = build_bvh(scene);
    RenderSetup setup;
    setup.tuning.path_kernel = c.form;
    // Passes of two samples: the grouping must not show in the bits either.
    settings.samples_per_pass = 2;
    Renderer renderer(context, scene, bvh, camera, settings, setup);
    while (renderer.samples_done() < settings.spp) renderer.render_samples(settings.spp - renderer.samples_done());
    return renderer.film();
}

TEST_F(ImageHashTest, EveryIntegratorKeepsItsBits)
{
    // A 16 x 8 map with a bright patch, seen through the mirror box's open front.
    Film map(16, 8);
    map.fill({0.2f, 0.3f, 0.5f, 1.0f});
    map.set(5, 3, {20.0f, 18.0f, 12.0f, 1.0f});
    const fs::path env_map = fs::temp_directory_path() / ("gc-hash-env-" + std::to_string(::getpid()) + ".pfm");
    write_image(env_map, map, {});

    const bool write = std::getenv("GEOCOLD_WRITE_IMAGE_HASHES") != nullptr;
    const std::map<std::string, std::string> stored = read_hashes();
    std::ostringstream table;
    table << "# name  FNV-1a 64 of the RGBA float bits (tests/render/image_hash_test.cpp)\n";
    for (const HashCase& c : kCases) {
        char hash[32];
        std::snprintf(hash, sizeof hash, "%016" PRIx64, image_hash(render_case(*context, c, env_map)));
        table << c.name << ' ' << hash << '\n';
        std::printf("%-28s %s\n", c.name, hash);
        if (write) continue;
        const auto it = stored.find(c.name);
        ASSERT_NE(it, stored.end()) << c.name << " has no stored hash in " << hash_file();
        EXPECT_EQ(it->second, hash) << c.name << ": the image's bits changed";
    }
    fs::remove(env_map);
    if (write) {
        std::ofstream(hash_file()) << table.str();
        std::printf("wrote %s\n", hash_file().c_str());
    }
}

}  // namespace
}  // namespace gc
