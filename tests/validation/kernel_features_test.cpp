// Programs specialised for a scene's features (host/render/kernel_features.h,
// kernels/shared/gc_features.h) render the same bits as the full programs: the code they drop
// is code the scene's data never reaches. Four scenes between them switch every feature on
// and off: glass, mirror + point light + environment map, textures + normal map + alpha MASK,
// and alpha BLEND. Each prints the options its program was built with, so a case that no
// longer specialises anything shows.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "host/image/image_io.h"
#include "host/scene/load.h"
#include "tests/cl/cl_test_util.h"
#include "tests/validation/validation_util.h"

namespace gc {
namespace {

namespace fs = std::filesystem;

struct Output {
    Film mean;
    std::string options;
};

Output render_with(const cl::Context& context, const Scene& scene, const Camera& camera, const RenderSettings& s,
                   KernelFeatureSet features)
{
    RenderSetup setup;
    setup.tuning.kernel_features = features;
    const FlatBvh bvh = build_bvh(scene);
    Renderer renderer(context, scene, bvh, camera, s, setup);
    for (std::uint32_t k = 0; k < s.spp; ++k) renderer.render_sample();
    return {renderer.film(), renderer.program().options()};
}

Camera box_camera()
{
    Camera camera;
    camera.look_from = Point3(1.6f, 1.2f, 2.2f);
    camera.look_at = Point3(0, 0, 0);
    return camera;
}

RenderSettings small_path_settings()
{
    RenderSettings s;
    s.integrator = IntegratorKind::Path;
    s.width = 40;
    s.height = 32;
    s.spp = 4;
    s.seed = 5;
    s.rr_depth = 3;
    return s;
}

class KernelFeaturesTest : public cl::test::DeviceTest {
protected:
    void expect_same_bits(const char* name, const Scene& scene, const Camera& camera, const RenderSettings& s)
    {
        const Output full = render_with(*context, scene, camera, s, KernelFeatureSet::All);
        const Output specialised = render_with(*context, scene, camera, s, KernelFeatureSet::Scene);
        std::size_t differing = 0;
        double sum = 0.0;
        for (std::size_t i = 0; i < full.mean.data().size(); ++i) {
            differing += std::memcmp(&full.mean.data()[i], &specialised.mean.data()[i], sizeof(float)) != 0;
            sum += full.mean.data()[i];
        }
        std::printf("[features] %s: %zu of %zu floats differ (image sum %.3f)\n  full:        %s\n  specialised: %s\n",
                    name, differing, full.mean.data().size(), sum, full.options.c_str(), specialised.options.c_str());
        EXPECT_EQ(differing, 0u) << name;
        EXPECT_GT(sum, 0.0) << name << ": a black image compares equal too easily";
        EXPECT_NE(full.options, specialised.options) << name << ": nothing was specialised";
    }
};

TEST_F(KernelFeaturesTest, GlassBox)
{
    const Scene scene = load_scene(fs::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Sphere.obj");
    expect_same_bits("glass sphere box", scene, validation::cornell_camera(), small_path_settings());
}

TEST_F(KernelFeaturesTest, MirrorBoxWithPointLightAndEnvironmentMap)
{
    Scene scene = load_scene(fs::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Mirror.obj");
    scene.point_lights.push_back({Point3(0.3f, 1.5f, 0.5f), glm::vec3(0.8f, 0.6f, 0.4f)});
    // A 16 x 8 map with a bright patch, seen through the box's open front.
    Film map(16, 8);
    map.fill({0.2f, 0.3f, 0.5f, 1.0f});
    map.set(5, 3, {20.0f, 18.0f, 12.0f, 1.0f});
    const fs::path map_path = fs::temp_directory_path() / ("gc-features-env-" + std::to_string(::getpid()) + ".pfm");
    write_image(map_path, map, {});
    RenderSettings s = small_path_settings();
    s.env_map_path = map_path.string();
    expect_same_bits("mirror box + point light + environment map", scene, validation::cornell_camera(), s);
    fs::remove(map_path);
}

TEST_F(KernelFeaturesTest, TexturedBoxWithNormalMapAndAlphaMask)
{
    Scene scene = load_scene(fs::path(GC_TEST_SOURCE_DIR) / "tests/data/scenes/box-textured/BoxTextured.gltf");
    ASSERT_FALSE(scene.textures.empty());
    for (Material& m : scene.materials) {
        m.normal_texture = 0;  // the logo as a normal map: any texel values exercise the code
        m.alpha_mode = AlphaMode::Mask;
        m.opacity = 0.55f;  // traversal asks the alpha test (factor x texture alpha) on every hit
        m.alpha_cutoff = 0.5f;
    }
    RenderSettings s = small_path_settings();
    s.env_radiance = glm::vec3(1.0f);
    expect_same_bits("textured box + normal map + MASK", scene, box_camera(), s);
}

TEST_F(KernelFeaturesTest, BlendedBox)
{
    Scene scene = load_scene(fs::path(GC_TEST_SOURCE_DIR) / "tests/data/scenes/box-textured/BoxTextured.gltf");
    for (Material& m : scene.materials) {
        m.alpha_mode = AlphaMode::Blend;
        m.opacity = 0.5f;
    }
    RenderSettings s = small_path_settings();
    s.env_radiance = glm::vec3(1.0f);
    expect_same_bits("textured box + BLEND", scene, box_camera(), s);
}

}  // namespace
}  // namespace gc
