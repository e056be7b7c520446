// The Vulkan reference on instanced scenes against OpenCL:
//  - the first-hit AOVs (aov.comp and aov.cl, both built with GC_SCENE_INSTANCED) on the
//    lattice scene and on rotated, scaled instances. Metric: the largest absolute difference of any channel of any pixel,
//    printed; it must be 0 (same operations on both sides, contraction off on both: see
//    docs/design.md, rule 4);
//  - the path and Whitted integrators (path.comp and whitted.comp built with
//    GC_SCENE_INSTANCED) on a glTF that reuses its meshes, area light included. Metric: the
//    fraction of bit-identical pixels, printed; the cross-check's strict limits must hold.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "../bvh/instance_scenes.h"
#include "../render/instanced_aov_render.h"
#include "host/bvh/bvh.h"
#include "host/image/compare.h"
#include "host/render/scene_convert.h"
#include "host/render/session.h"
#include "host/vk/cross_check.h"
#include "host/vk/agreement.h"
#include "host/vk/compute_reference.h"
#include "host/vk/instanced_aov.h"
#include "tests/cl/cl_test_util.h"
#include "tests/render/reused_meshes_gltf.h"
#include "vk_test_util.h"

namespace gc::vk {
namespace {

class InstancedCrossCheck : public VkDeviceTest {
protected:
    void SetUp() override
    {
        VkDeviceTest::SetUp();
        if (IsSkipped()) return;
        std::string why;
        cl_context = shared_cl_context(&why);
        if (!cl_context) GTEST_SKIP() << why;
    }
    cl::Context* cl_context = nullptr;
};

// The lattice scene (exact transforms) and randomly rotated, scaled instances.
void expect_vulkan_equals_opencl(Context& context, cl::Context& cl_context, const InstancedScene& s, const char* name,
                                 const Camera& camera)
{
    const InstanceBvhParts parts = build_instance_bvh(s);
    const InstancedBvh bvh = assemble_binary(parts);
    for (const AovKind aov : {AovKind::Depth, AovKind::Albedo, AovKind::Normal, AovKind::Preview}) {
        RenderSettings settings;
        settings.width = settings.height = 64;
        settings.aov = aov;
        settings.integrator = IntegratorKind::Aov;
        const std::vector<glm::vec4> cl_film = test::render_instanced_aov(cl_context, s, parts, camera, settings);
        const Film vk_film = render_instanced_aov(context, s, bvh, camera, settings);
        float worst = 0.0f;
        std::size_t covered = 0;
        for (std::uint32_t y = 0; y < 64; ++y)
            for (std::uint32_t x = 0; x < 64; ++x) {
                const glm::vec4 c = cl_film[y * 64 + x];
                const float* v = vk_film.pixel(x, y);
                covered += c.x != 0.0f || c.y != 0.0f || c.z != 0.0f;
                for (int k = 0; k < 3; ++k) worst = std::max(worst, std::fabs(v[k] - c[k]));
            }
        std::printf("[instanced aov, Vulkan vs OpenCL] %s, %s: %zu of 4096 pixels on geometry, max |difference| %g\n",
                    name, aov_name(aov), covered, static_cast<double>(worst));
        EXPECT_GT(covered, 4096u / 8u);
        EXPECT_EQ(worst, 0.0f) << name << " " << aov_name(aov);
    }
}

TEST_F(InstancedCrossCheck, AovsEqualOpenCl)
{
    Camera lattice;
    lattice.look_from = Point3(-4.0f, 11.0f, -6.0f);
    lattice.look_at = Point3(3.0f, 3.0f, 3.0f);
    lattice.vfov_degrees = 50.0f;
    expect_vulkan_equals_opencl(*context, *cl_context, test::lattice_instances(3, 7), "lattice", lattice);
    Camera rotated;
    rotated.look_from = Point3(0.0f, 3.0f, 12.0f);
    rotated.look_at = Point3(0.0f, 0.0f, 0.0f);
    rotated.vfov_degrees = 60.0f;
    expect_vulkan_equals_opencl(*context, *cl_context, test::rotated_instances(40, 3), "rotated", rotated);
}

TEST_F(InstancedCrossCheck, PathAndWhittedEqualOpenCl)
{
    cl::test::TempDir dir;
    SceneRequest request;
    request.path = test::write_reused_meshes_gltf(dir.path());
    request.keep_instances = true;
    request.camera.look_from = Point3(0.5f, 3.2f, 6.5f);
    request.camera.look_at = Point3(0.0f, 0.6f, 0.0f);
    request.camera.fov = 45.0f;
    const PreparedScene prepared = prepare_scene(request);
    ASSERT_TRUE(prepared.instances);
    RenderSettings settings;
    settings.width = 48;
    settings.height = 36;
    settings.spp = 4;
    settings.max_depth = 5;
    settings.seed = 2;
    // What `--cross-check vulkan` adds for a file that reuses meshes.
    CrossCheckReport report;
    add_instanced(report, *cl_context, *context, *prepared.instances, prepared.camera, settings);
    ASSERT_TRUE(report.instanced);
    const AgreementLimits strict;
    for (const auto& [integrator, d] :
         {std::pair{"path", &report.instanced->path}, std::pair{"whitted", &report.instanced->whitted}}) {
        std::printf("[instanced %s, Vulkan vs OpenCL] mean %.4g, rel MSE %.3g, %.3f %% of pixels bit-identical\n",
                    integrator, d->mean_ref, d->rel_mse, 100.0 * d->identical);
        const AgreementVerdict v = judge_agreement(*d, strict);
        EXPECT_TRUE(v.passed()) << integrator << ": " << v.why;
        EXPECT_GT(d->identical, 0.999) << integrator;
    }
}

}  // namespace
}  // namespace gc::vk
