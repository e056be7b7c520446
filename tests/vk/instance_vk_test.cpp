// The Vulkan reference of the instanced first-hit AOVs (kernels/vk/aov_instances.comp) against
// the OpenCL kernel (kernels/aov_instances.cl) on the lattice scene. Metric: the largest
// absolute difference of any channel of any pixel, printed; it must be 0 (same operations
// on both sides, contraction off on both: see docs/design.md, rule 4).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "../bvh/instance_scenes.h"
#include "../render/instanced_aov_render.h"
#include "host/bvh/bvh.h"
#include "host/render/scene_convert.h"
#include "host/vk/instanced_aov.h"
#include "vk_test_util.h"

namespace gc::vk {
namespace {

class InstancedAovCrossCheck : public VkDeviceTest {
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
    DeviceTuning tuning;
    tuning.bvh_layout = BvhLayout::Binary;  // the layout the Vulkan reference reads
    const DeviceScene meshes = DeviceScene::upload(cl_context, s.meshes, build_bvh(s.meshes), {}, tuning);
    const InstancedBvh bvh = assemble_binary(parts);
    for (const AovKind aov : {AovKind::Depth, AovKind::Albedo, AovKind::Normal, AovKind::Preview}) {
        RenderSettings settings;
        settings.width = settings.height = 64;
        settings.aov = aov;
        settings.integrator = IntegratorKind::Aov;
        const dev::GcRenderParams params = make_render_params(s.meshes, camera, settings);
        const std::vector<glm::vec4> cl_film = test::render_instanced_aov(cl_context, meshes, parts, params);
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

TEST_F(InstancedAovCrossCheck, VulkanEqualsOpenCl)
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

}  // namespace
}  // namespace gc::vk
