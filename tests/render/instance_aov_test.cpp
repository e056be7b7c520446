// First-hit images of an instanced scene (kernels/aov.cl with GC_SCENE_INSTANCED, through
// DeviceScene::upload_instanced) against the flattened scene's, on every OpenCL device in the
// layout it uses. Metric: the largest absolute difference of any channel of any pixel,
// printed; depth and albedo must agree bit for bit under the lattice transforms (both spaces
// exact), the world-space normal and the preview (a headlight on it) to 1e-6: the instance's
// normals are taken to world space per vertex (gc_instance_attribs.h) and interpolated there,
// the flat scene's were transformed on the host.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "../bvh/instance_scenes.h"
#include "instanced_aov_render.h"
#include "host/bvh/bvh.h"
#include "host/bvh/instance_bvh.h"
#include "host/bvh/traverse_instances_host.h"
#include "gc_aov.h"
#include "host/cl/buffer.h"
#include "host/cl/context.h"
#include "host/cl/device.h"
#include "host/cl/program.h"
#include "host/render/device_scene.h"
#include "host/render/integrator.h"
#include "host/render/scene_convert.h"

namespace gc {
namespace {

constexpr int kSide = 64;
using test::render_instanced_aov;

// One sample of the flat scene's aov.cl, launched directly.
std::vector<glm::vec4> render_flat_aov(const cl::Context& context, const DeviceScene& scene,
                                       const dev::GcRenderParams& params)
{
    const cl::Program program(context, "aov.cl", scene_program_options(scene));
    auto film = cl::Buffer<glm::vec4>::create(context, params.pixel_count, CL_MEM_READ_WRITE, "film");
    film.write(std::vector<glm::vec4>(params.pixel_count, glm::vec4(0.0f)));
    cl::Kernel kernel = program.kernel("aov_render");
    kernel.set_args(params, scene.scene_args(), film);
    kernel.launch(context, params.pixel_count, 0, "flattened aov");
    context.finish();
    std::vector<glm::vec4> out(params.pixel_count);
    film.read(out);
    return out;
}

TEST(InstanceAov, LatticeImagesEqualTheFlattenedScenes)
{
    std::string why;
    const std::vector<cl::DeviceInfo> devices = cl::list_devices(&why);
    if (devices.empty()) GTEST_SKIP() << "no OpenCL device: " << why;
    const InstancedScene s = test::lattice_instances(3, 7);
    const Scene flat = flatten_instances(s);
    const FlatBvh flat_bvh = build_bvh(flat);
    const InstanceBvhParts parts = build_instance_bvh(s);
    Camera camera;
    camera.look_from = Point3(-4.0f, 11.0f, -6.0f);
    camera.look_at = Point3(3.0f, 3.0f, 3.0f);
    camera.vfov_degrees = 50.0f;
    for (const cl::DeviceInfo& device : devices) {
        const cl::Context context(device);
        const DeviceScene flat_scene = DeviceScene::upload(context, flat, flat_bvh);
        for (const AovKind aov : {AovKind::Depth, AovKind::Albedo, AovKind::Normal, AovKind::Preview}) {
            RenderSettings settings;
            settings.width = settings.height = kSide;
            settings.integrator = IntegratorKind::Aov;
            settings.aov = aov;
            const std::vector<glm::vec4> want =
                render_flat_aov(context, flat_scene, make_render_params(flat, camera, settings));
            BvhLayout layout = BvhLayout::Binary;
            const std::vector<glm::vec4> got = render_instanced_aov(context, s, parts, camera, settings, &layout);
            float worst = 0.0f;
            std::size_t covered = 0;
            for (std::size_t p = 0; p < want.size(); ++p) {
                covered += want[p].x != 0.0f || want[p].y != 0.0f || want[p].z != 0.0f;
                for (int c = 0; c < 4; ++c) worst = std::max(worst, std::fabs(got[p][c] - want[p][c]));
            }
            const float bound = aov == AovKind::Normal || aov == AovKind::Preview ? 1e-6f : 0.0f;
            std::printf("[instanced aov] %s on %s, %s: %zu of %d pixels on geometry, max |difference| %g (bound %g)\n",
                        aov_name(aov), device.device_name.c_str(), layout_name(layout), covered,
                        kSide * kSide, static_cast<double>(worst), static_cast<double>(bound));
            EXPECT_GT(covered, std::size_t{kSide * kSide / 8});  // sparse soups: a sixth of the image
            EXPECT_LE(worst, bound) << aov_name(aov) << " on " << device.device_name;
        }
    }
}

// 32^3 instances of a 1.2k-triangle torus knot (39M triangles drawn) render a 96 x 96 depth
// image on each device; every pixel's depth equals the host reference's t for that pixel's
// camera ray (gc_aov_camera_ray on the host), bit for bit.
TEST(InstanceAov, ThirtyTwoThousandInstancesDepthEqualsTheHost)
{
    std::string why;
    const std::vector<cl::DeviceInfo> devices = cl::list_devices(&why);
    if (devices.empty()) GTEST_SKIP() << "no OpenCL device: " << why;
    InstancedScene s;
    test::add_mesh(s, test::torus_knot(100, 6, 0.12f));
    for (int x = 0; x < 32; ++x)
        for (int y = 0; y < 32; ++y)
            for (int z = 0; z < 32; ++z) {
                const glm::mat4 at = glm::translate(glm::mat4(1.0f), glm::vec3(3.0f * x, 3.0f * y, 3.0f * z));
                s.instances.push_back({0u, glm::rotate(at, 0.1f * float(x + 2 * y + 3 * z), glm::vec3(0.3f, 0.8f, 0.5f))});
            }
    const InstanceBvhParts parts = build_instance_bvh(s);
    const InstancedBvh host_bvh = assemble_binary(parts);
    Camera camera;
    camera.look_from = Point3(-20.0f, 60.0f, -30.0f);
    camera.look_at = Point3(48.0f, 40.0f, 48.0f);
    camera.vfov_degrees = 40.0f;
    RenderSettings settings;
    settings.width = settings.height = 96;
    settings.integrator = IntegratorKind::Aov;
    settings.aov = AovKind::Depth;
    const dev::GcRenderParams params = make_render_params(s.meshes, camera, settings);
    for (const cl::DeviceInfo& device : devices) {
        const cl::Context context(device);
        BvhLayout layout = BvhLayout::Binary;
        const std::vector<glm::vec4> film = render_instanced_aov(context, s, parts, camera, settings, &layout);
        std::size_t hits = 0, mismatches = 0;
        for (std::uint32_t p = 0; p < params.pixel_count; ++p) {
            const dev::GcRay ray = dev::gc_aov_camera_ray(params, p);
            Ray r;
            r.origin = Point3(ray.org_tmin.x, ray.org_tmin.y, ray.org_tmin.z);
            r.direction = Vec3(ray.dir_tmax.x, ray.dir_tmax.y, ray.dir_tmax.z);
            r.tmin = ray.org_tmin.w;
            r.tmax = ray.dir_tmax.w;
            const dev::GcInstanceHit h = trace_closest(host_bvh, r);
            const float want = h.instance == GC_INVALID ? 0.0f : h.hit.t;
            hits += h.instance != GC_INVALID;
            mismatches += film[p].x != want;
        }
        std::printf("[instanced aov] 32768 instances, %zu triangles drawn, on %s, %s: %zu of %u pixels hit, "
                    "%zu depths differ from the host's\n",
                    s.instanced_triangle_count(), device.device_name.c_str(), layout_name(layout), hits,
                    params.pixel_count, mismatches);
        EXPECT_GT(hits, std::size_t{params.pixel_count / 4});
        EXPECT_EQ(mismatches, 0u);
    }
}

}  // namespace
}  // namespace gc
