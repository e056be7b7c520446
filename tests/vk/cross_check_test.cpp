// OpenCL vs Vulkan on real scenes (DESIGN.md "Cross-checks"): the raster G-buffer against the
// OpenCL ray-cast AOVs, and the Vulkan compute path tracer against the OpenCL wavefront one,
// at the same spp and seed. Small images and few samples: CI runs this on lavapipe + PoCL.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>

#include "host/bvh/bvh.h"
#include "host/render/scene_convert.h"
#include "host/scene/camera_framing.h"
#include "host/scene/load.h"
#include "host/vk/cross_check.h"
#include "host/vk/raster_pass.h"
#include "tests/render/alpha_scenes.h"
#include "tests/vk/vk_test_util.h"

namespace gc::vk {
namespace {

struct SceneCase {
    const char* name;
    const char* path; // relative to the repo (repo:) or to the shared scenes (shared:)
    bool shared;
    int size;         // square image
};

std::filesystem::path scene_path(const SceneCase& c)
{
    return c.shared ? std::filesystem::path(GC_TEST_SHARED_DIR "/scenes") / c.path
                    : std::filesystem::path(GC_TEST_SOURCE_DIR "/scenes") / c.path;
}

void PrintTo(const SceneCase& c, std::ostream* os) { *os << c.name; }

class CrossCheck : public VkDeviceTest, public ::testing::WithParamInterface<SceneCase> {};

TEST_P(CrossCheck, OpenClAndVulkanAgree)
{
    const SceneCase& c = GetParam();
    const std::filesystem::path path = scene_path(c);
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "scene not present: " << path;
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
    EXPECT_GT(r.radiance.ref_mean, 0.0);
    EXPECT_LE(r.radiance.rel_mse, tol.max_rel_mse);
    EXPECT_GE(r.radiance.within, tol.min_within);
    EXPECT_TRUE(r.passed(tol));
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, CrossCheck,
    ::testing::Values(SceneCase{"CornellOriginal", "cornell-box/CornellBox-Original.obj", false, 128},
                      SceneCase{"CornellMirror", "cornell-box/CornellBox-Mirror.obj", false, 128},
                      SceneCase{"CornellSphere", "cornell-box/CornellBox-Sphere.obj", false, 128},
                      SceneCase{"CornellGlossy", "cornell-box/CornellBox-Glossy.obj", true, 96},
                      SceneCase{"Bunny", "stanford-bunny/stanford-bunny.obj", true, 96},
                      SceneCase{"Spot", "spot/spot_textured.obj", true, 96},
                      SceneCase{"BoxTextured", "box-textured/BoxTextured.gltf", true, 96},
                      // Normal map with authored TANGENTs: GLSL and OpenCL decode them alike.
                      SceneCase{"Avocado", "avocado/Avocado.gltf", true, 96}),
    [](const ::testing::TestParamInfo<SceneCase>& param_info) { return std::string(param_info.param.name); });

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
