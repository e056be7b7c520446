// OpenCL vs Vulkan on real scenes (DESIGN.md "Cross-checks"): the raster G-buffer against the
// OpenCL ray-cast AOVs, and the Vulkan compute path and Whitted integrators against the
// OpenCL ones, at the same spp and seed, under every kind of light. Small images and few
// samples: CI runs this on lavapipe + PoCL.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>

#include <unistd.h>

#include "host/bvh/bvh.h"
#include "host/image/image_io.h"
#include "host/render/scene_convert.h"
#include "host/scene/camera_framing.h"
#include "host/scene/load.h"
#include "host/vk/cross_check.h"
#include "host/vk/raster_pass.h"
#include "host/vk/compute_reference.h"
#include "host/image/compare.h"
#include "host/render/renderer.h"
#include "host/render/session.h"
#include "tests/render/alpha_scenes.h"
#include "tests/vk/vk_test_util.h"

namespace gc::vk {
namespace {

struct SceneCase {
    const char* name;
    const char* path; // relative to the repository
    int size;         // square image
};

std::filesystem::path scene_path(const SceneCase& c) { return std::filesystem::path(GC_TEST_SOURCE_DIR) / c.path; }

void PrintTo(const SceneCase& c, std::ostream* os) { *os << c.name; }

class CrossCheck : public VkDeviceTest, public ::testing::WithParamInterface<SceneCase> {};

TEST_P(CrossCheck, OpenClAndVulkanAgree)
{
    const SceneCase& c = GetParam();
    const std::filesystem::path path = scene_path(c);
    std::string why;
    cl::Context* cl_context = shared_cl_context(&why);
    if (!cl_context) GTEST_SKIP() << why;

    const Scene scene = load_scene(path);
    const Camera camera = resolve_camera(scene, {});
    const FlatBvh bvh = build_bvh(scene);
    RenderSettings settings;
    settings.width = c.size;
    settings.height = c.size;
    settings.spp = 4;
    settings.seed = 7;
    // Scenes without emitters are lit by a white environment, so radiance is not black.
    if (make_emitters(scene).empty()) settings.env_radiance = glm::vec3(1.0f);

    const CrossCheckReport r = cross_check(*cl_context, *context, scene, bvh, camera, settings);
    std::printf("%s: %s", c.name, r.format().c_str());

    const Tolerances tol;
    EXPECT_GT(r.raster.covered, 0u) << "the camera sees nothing: the check would prove nothing";
    // The edge rule must leave most covered pixels in the comparison.
    EXPECT_GE(r.raster.compared, r.raster.covered * 3 / 4);
    EXPECT_GE(r.raster.id_agreement, tol.min_id_agreement);
    EXPECT_LE(r.raster.max_depth_rel_error, tol.max_depth_rel_error);
    // The compute reference runs the OpenCL traversal code: every pixel must agree.
    EXPECT_EQ(r.compute_aov.equal_ids, r.compute_aov.compared);
    EXPECT_LE(r.compute_aov.max_depth_rel_error, tol.max_depth_rel_error);
    for (const ImageDifference* radiance : {&r.path, &r.whitted}) {
        const AgreementVerdict v = judge_agreement(*radiance, tol.radiance);
        EXPECT_TRUE(v.passed()) << v.why;
    }
    EXPECT_TRUE(r.passed(tol));
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, CrossCheck,
    ::testing::Values(SceneCase{"CornellOriginal", "scenes/cornell-box/CornellBox-Original.obj", 128},
                      SceneCase{"CornellMirror", "scenes/cornell-box/CornellBox-Mirror.obj", 128},
                      SceneCase{"CornellSphere", "scenes/cornell-box/CornellBox-Sphere.obj", 128},
                      SceneCase{"CornellGlossy", "scenes/cornell-box/CornellBox-Glossy.obj", 96},
                      // 16k triangles under 253 nodes, no emitters: a large mesh lit by the sky.
                      SceneCase{"RetroUfo", "tests/data/scenes/retro-ufo/retroufo.glb", 96},
                      SceneCase{"Spot", "tests/data/scenes/spot/spot_textured.obj", 96},
                      SceneCase{"BoxTextured", "tests/data/scenes/box-textured/BoxTextured.gltf", 96},
                      // Normal map with authored TANGENTs: GLSL and OpenCL decode them alike.
                      SceneCase{"Avocado", "tests/data/scenes/avocado/Avocado.gltf", 96},
                      // KHR_texture_transform: transformed texture views on both sides.
                      SceneCase{"TextureTransform", "tests/data/scenes/texture-transform/TextureTransformTest.gltf", 96},
                      // KHR_materials_clearcoat with its factor and roughness textures.
                      SceneCase{"ClearCoat", "tests/data/scenes/ClearCoatTest/ClearCoatTest.gltf", 96},
                      // KHR_materials_specular and KHR_materials_clearcoat factors on spheres.
                      SceneCase{"MaterialLayers", "tests/data/scenes/material-layers/MaterialLayers.gltf", 96},
                      // Rough KHR_materials_transmission with KHR_materials_volume (refraction, absorption).
                      SceneCase{"RoughGlassVolume", "tests/data/scenes/rough-glass-volume/RoughGlassVolume.gltf", 96}),
    [](const ::testing::TestParamInfo<SceneCase>& param_info) { return std::string(param_info.param.name); });

// Every light the OpenCL side has, on scenes in the repository, each through both integrators
// (path and Whitted; Whitted sees an environment map's scale as a constant sky, as whitted.cl
// does). The metric: for each integrator, AgreementLimits{}: relative MSE <= 1e-5 and >= 99.9 %
// of pixels within 1e-3 relative (stricter than the tool's own limits, Tolerances{}: the two
// sides share every decision, so they should agree to rounding); the figures are printed with
// the report.
class CrossCheckLights : public VkDeviceTest {
protected:
    void SetUp() override
    {
        VkDeviceTest::SetUp();
        if (IsSkipped()) return;
        std::string why;
        cl_context = shared_cl_context(&why);
        if (!cl_context) GTEST_SKIP() << why;
    }
    void TearDown() override
    {
        std::error_code ec;
        if (!env_map.empty()) std::filesystem::remove(env_map, ec);
    }

    static Scene repo_scene(const char* path) { return load_scene(std::filesystem::path(GC_TEST_SOURCE_DIR) / path); }

    static RenderSettings small_settings()
    {
        RenderSettings s;
        s.width = 96;
        s.height = 96;
        s.spp = 4;
        s.seed = 7;
        return s;
    }

    // A 32 x 16 lat-long sky with a small, very bright sun: importance sampling picks the sun
    // texels most of the time, and the rest of the sky still lights the shadows.
    std::string write_sun_map()
    {
        Film image(32, 16);
        image.fill(Rgba{0.2f, 0.3f, 0.45f, 1.0f});
        for (std::uint32_t y = 4; y < 6; ++y)
            for (std::uint32_t x = 20; x < 22; ++x) image.set(x, y, Rgba{60.0f, 52.0f, 40.0f, 1.0f});
        env_map = std::filesystem::temp_directory_path() /
                  ("gc-vk-cross-check-sun-" + std::to_string(::getpid()) + ".pfm");
        write_image(env_map, image, {});
        return env_map.string();
    }

    void expect_agreement(const char* name, const Scene& scene, const RenderSettings& settings)
    {
        const Camera camera = resolve_camera(scene, {});
        const FlatBvh bvh = build_bvh(scene);
        const CrossCheckReport r = cross_check(*cl_context, *context, scene, bvh, camera, settings);
        std::printf("%s: %s", name, r.format().c_str());
        const AgreementLimits strict;  // the consistency check's limits
        for (const auto& [integrator, radiance] : {std::pair{"path", &r.path}, std::pair{"whitted", &r.whitted}}) {
            std::printf("[%s] %s: rel MSE %.3g (limit %.0e), %.3f %% of pixels within 1e-3 (limit %.1f %%), "
                        "%.3f %% bit-identical\n",
                        name, integrator, radiance->rel_mse, strict.max_rel_mse, 100.0 * radiance->within_tolerance,
                        100.0 * strict.min_within, 100.0 * radiance->identical);
            const AgreementVerdict v = judge_agreement(*radiance, strict);
            EXPECT_TRUE(v.passed()) << integrator << ": " << v.why;
        }
        EXPECT_EQ(r.compute_aov.equal_ids, r.compute_aov.compared);
        EXPECT_TRUE(r.passed());
    }

    cl::Context* cl_context = nullptr;
    std::filesystem::path env_map;
};

TEST_F(CrossCheckLights, ConstantEnvironment)
{
    RenderSettings s = small_settings();
    s.env_radiance = glm::vec3(0.8f, 0.9f, 1.0f);
    expect_agreement("constant environment (textured box)", repo_scene("tests/data/scenes/box-textured/BoxTextured.gltf"),
                     s);
}

TEST_F(CrossCheckLights, EnvironmentMap)
{
    RenderSettings s = small_settings();
    s.env_map_path = write_sun_map();
    s.env_radiance = glm::vec3(1.0f); // the map's scale, as --env FILE sets it
    expect_agreement("environment map (textured box)", repo_scene("tests/data/scenes/box-textured/BoxTextured.gltf"),
                     s);
}

TEST_F(CrossCheckLights, PointLight)
{
    const Scene scene = repo_scene("tests/data/scenes/box-textured/BoxTextured-PointLight.gltf");
    ASSERT_EQ(scene.point_lights.size(), 1u);
    expect_agreement("point light (textured box, nothing else lights it)", scene, small_settings());
}

// KHR_texture_transform on every slot of a normal-mapped model: transformed lookups and the
// normal map's frame turned by its view (gc_texture_tangent_xy), on both sides.
TEST_F(CrossCheckLights, TransformedTexturesOnEverySlot)
{
    Scene scene = repo_scene("tests/data/scenes/avocado/Avocado.gltf");
    ASSERT_GE(scene.materials[0].normal_texture, 0);
    Material& m = scene.materials[0];
    m.albedo_uv.offset = {0.25f, -0.5f};
    m.albedo_uv.rotation = 0.4f;
    m.metallic_roughness_uv.scale = {2.0f, 0.5f};
    m.normal_uv.rotation = 1.1f;
    m.normal_uv.scale = {1.5f, -0.75f};
    RenderSettings s = small_settings();
    s.env_radiance = glm::vec3(0.8f, 0.9f, 1.0f);
    expect_agreement("uv transforms on every slot (avocado, constant sky)", scene, s);
}

// KHR_materials_transmission's transmissionTexture (R scales the factor) over the rough glass
// cube: half its texels turn transmission off.
TEST_F(CrossCheckLights, TransmissionTexture)
{
    Scene scene = repo_scene("tests/data/scenes/rough-glass-volume/RoughGlassVolume.gltf");
    Texture t;
    t.name = "transmission";
    t.width = t.height = 2;
    t.srgb = false;
    t.texels = {0xff000000u, 0xff0000ffu, 0xff000040u, 0xff0000c0u};
    scene.textures.push_back(t);
    for (Material& m : scene.materials)
        if (m.transmission > 0.0f) m.layers.transmission_texture.texture = static_cast<int>(scene.textures.size() - 1);
    RenderSettings s = small_settings();
    s.env_radiance = glm::vec3(1.0f);
    expect_agreement("transmission texture (rough glass cube, constant sky)", scene, s);
}

// KHR_materials_sheen with its colour and roughness textures (the Khronos sheen cloth): the
// Charlie lobe, its albedo table (a buffer on the Vulkan side, gc_sheen_table.h on the other)
// scaling the layers beneath, and sampling among the layers.
TEST_F(CrossCheckLights, SheenWithTextures)
{
    const Scene scene = repo_scene("tests/data/scenes/SheenCloth/SheenCloth.glb");
    ASSERT_TRUE(std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) {
        return m.layers.sheen_on && m.layers.sheen_color_texture.texture >= 0;
    })) << "the cloth lost its textured sheen";
    RenderSettings s = small_settings();
    s.env_radiance = glm::vec3(1.0f);
    expect_agreement("sheen with textures (sheen cloth, constant sky)", scene, s);
}

// Emitters, a point light and an environment map at once: next-event estimation chooses among
// all three groups, and MIS weighs emitter and environment hits against that choice.
TEST_F(CrossCheckLights, AllLightGroups)
{
    Scene scene = repo_scene("scenes/cornell-box/CornellBox-Sphere.obj");
    scene.point_lights.push_back({Point3(-0.4f, 1.4f, 0.6f), glm::vec3(0.6f, 0.5f, 0.4f)});
    RenderSettings s = small_settings();
    s.env_map_path = write_sun_map();
    s.env_radiance = glm::vec3(1.0f);
    expect_agreement("emitters + point light + environment map (glass sphere box)", scene, s);
}

// Whitted's ray tree deeper than its 16-entry stack: glass spawns two rays per hit, so the
// overflow rule (keep the heavier ray) decides, and must decide alike on both sides.
TEST_F(CrossCheckLights, WhittedDeeperThanItsStack)
{
    RenderSettings s = small_settings();
    s.max_depth = 24;
    expect_agreement("Whitted, max depth 24 (glass sphere box)", repo_scene("scenes/cornell-box/CornellBox-Sphere.obj"),
                     s);
}

// The G-buffer itself, independent of OpenCL: sane values, and the time per frame.
TEST_F(VkDeviceTest, RasterGBufferOfTheCornellBox)
{
    const Scene scene = load_scene(GC_TEST_SOURCE_DIR "/scenes/cornell-box/CornellBox-Original.obj");
    const Camera camera = resolve_camera(scene, {});
    RenderSettings settings;
    settings.width = 160;
    settings.height = 120; // not square: the aspect ratio must follow the camera's
    settings.env_radiance = glm::vec3(0.25f, 0.5f, 0.75f);
    RasterPass pass(*context, scene, camera, settings);
    using Clock = std::chrono::steady_clock;
    auto t0 = Clock::now();
    const GBuffer first = pass.render();
    const double first_s = std::chrono::duration<double>(Clock::now() - t0).count();
    t0 = Clock::now();
    const GBuffer g = pass.render();
    const double warm_s = std::chrono::duration<double>(Clock::now() - t0).count();
    std::printf("raster %ux%u: first frame %.4f s, warm frame %.4f s\n", g.width, g.height, first_s, warm_s);

    ASSERT_EQ(g.primid.size(), 160u * 120u);
    EXPECT_EQ(g.primid, first.primid) << "two frames of the same scene differ";
    std::size_t covered = 0;
    for (std::size_t i = 0; i < g.primid.size(); ++i) {
        const std::uint32_t x = static_cast<std::uint32_t>(i % g.width), y = static_cast<std::uint32_t>(i / g.width);
        if (g.primid[i] < 0) {
            EXPECT_EQ(g.depth[i], 0.0f);
            EXPECT_EQ(g.preview.at(x, y), (Rgba{0.25f, 0.5f, 0.75f, 1.0f}));
            continue;
        }
        ++covered;
        ASSERT_LT(static_cast<std::size_t>(g.primid[i]), scene.triangle_count());
        EXPECT_NEAR(glm::length(g.normal[i]), 1.0f, 1e-4f);
        EXPECT_GT(g.depth[i], 0.0f);
    }
    // The framed camera looks into the box: the box walls fill most of the view.
    EXPECT_GT(covered, g.primid.size() / 2);
}

// glTF alphaMode MASK (a quad whose left half is cut away in front of an opaque backstop,
// seen head-on): the raster pass discards the cut-away fragments as the ray tracer's
// traversal skips those hits (gc_alpha.h), so both see the backstop through the left half and
// the full cross-check agrees.
TEST_F(VkDeviceTest, RasterAndOpenClAgreeOnAlphaMaskCutOut)
{
    std::string why;
    cl::Context* cl_context = shared_cl_context(&why);
    if (!cl_context) GTEST_SKIP() << why;
    const Scene scene = test::half_cut_quad();
    const Camera camera = frame_camera(scene); // from +z, +x to the right
    const FlatBvh bvh = build_bvh(scene);
    RenderSettings settings;
    settings.width = 64; // even: no pixel centre on the cut at x = 0
    settings.height = 64;
    settings.spp = 4;
    settings.seed = 7;
    settings.env_radiance = glm::vec3(1.0f);

    RasterPass pass(*context, scene, camera, settings);
    const GBuffer g = pass.render();
    std::size_t quad_left = 0, quad_right = 0; // pixels showing the MASK quad (triangles 0-1)
    for (std::size_t i = 0; i < g.primid.size(); ++i) {
        if (g.primid[i] != 0 && g.primid[i] != 1) continue;
        (i % g.width < g.width / 2 ? quad_left : quad_right) += 1;
    }
    std::printf("[alpha] raster: MASK quad seen in %zu pixels left of the cut (cut away), %zu right\n", quad_left,
                quad_right);
    EXPECT_EQ(quad_left, 0u) << "the raster pass drew the cut-away half of the MASK quad";
    EXPECT_GT(quad_right, 0u) << "the opaque half of the MASK quad is missing";

    const CrossCheckReport r = cross_check(*cl_context, *context, scene, bvh, camera, settings);
    std::printf("alpha-mask quad: %s", r.format().c_str());
    EXPECT_TRUE(r.passed());
}

}  // namespace
}  // namespace gc::vk

namespace gc::vk {
namespace {

// The denoiser's guides (gc_aov_trace.h) follow mirrors and glass in both implementations
// alike: OpenCL and the Vulkan reference give the same bits on the Cornell spheres.
TEST_F(VkDeviceTest, DenoiseGuidesAgreeWithOpenCl)
{
    std::string why;
    cl::Context* cl_context = shared_cl_context(&why);
    if (!cl_context) GTEST_SKIP() << why;
    SceneRequest request;
    request.path = std::filesystem::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Sphere.obj";
    const PreparedScene prepared = prepare_scene(request);
    for (AovKind kind : {AovKind::GuideAlbedo, AovKind::GuideNormal}) {
        RenderSettings settings;
        settings.width = 40;
        settings.height = 32;
        settings.integrator = IntegratorKind::Aov;
        settings.aov = kind;
        settings.spp = 2;
        Renderer cl_renderer(*cl_context, prepared.scene, prepared.bvh, prepared.camera, settings);
        cl_renderer.render(0, settings.spp);
        ComputeReference reference(*context, prepared.scene, prepared.bvh, prepared.camera, settings);
        for (std::uint32_t i = 0; i < settings.spp; ++i) reference.render_sample();
        const Film a = cl_renderer.film(), b = reference.film();
        std::size_t same = 0;
        for (std::size_t i = 0; i < a.data().size(); ++i) same += a.data()[i] == b.data()[i];
        std::printf("%s: %.3f %% of the values bit-identical\n", aov_name(kind), 100.0 * double(same) / double(a.data().size()));
        const ImageDifference d = compare_images(b, a);
        EXPECT_LT(d.rel_mse, 1e-5) << aov_name(kind);
        EXPECT_GT(d.within_tolerance, 0.999) << aov_name(kind);
    }
}

}  // namespace
}  // namespace gc::vk

namespace gc::vk {
namespace {

// Depth of field is shared camera code: the Vulkan reference and OpenCL agree through a lens.
TEST_F(VkDeviceTest, ThinLensAgreesWithOpenCl)
{
    std::string why;
    cl::Context* cl_context = shared_cl_context(&why);
    if (!cl_context) GTEST_SKIP() << why;
    SceneRequest request;
    request.path = std::filesystem::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Sphere.obj";
    request.camera.aperture_radius = 0.1f;
    request.camera.focus_distance = 3.0f;
    const PreparedScene prepared = prepare_scene(request);
    RenderSettings settings;
    settings.width = 48;
    settings.height = 40;
    settings.spp = 4;
    const CrossCheckReport r = cross_check(*cl_context, *context, prepared.scene, prepared.bvh, prepared.camera, settings);
    std::printf("thin lens: %s", r.format().c_str());
    EXPECT_TRUE(r.passed());
    // The Sobol sampler's scrambles and recurrence, in GLSL, through every block a path takes
    // (the lens's two dimensions among them): the same numbers, so the same pixels.
    settings.sampler = SamplerKind::Sobol;
    const CrossCheckReport sobol =
        cross_check(*cl_context, *context, prepared.scene, prepared.bvh, prepared.camera, settings);
    std::printf("thin lens, sobol sampler: %s", sobol.format().c_str());
    EXPECT_TRUE(sobol.passed());
    EXPECT_GT(sobol.path.identical, 0.999) << "path pixels bit-identical";
}

}  // namespace
}  // namespace gc::vk
