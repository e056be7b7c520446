// The two-level traversal on every OpenCL device and layout (kernels/test/trace_instances.cl)
// against the host reference (traverse_instances_host.h), bit for bit, and against the
// flattened scene where flattening is exact; plus a 32^3-instance scene traced in one launch.
#include <gtest/gtest.h>

#include <bit>
#include <cstdio>
#include <string>
#include <vector>

#include "../bvh/bvh_checks.h"
#include "../bvh/instance_scenes.h"
#include "host/bvh/bvh.h"
#include "host/bvh/traverse_host.h"
#include "host/bvh/traverse_instances_host.h"
#include "host/cl/buffer.h"
#include "host/cl/context.h"
#include "host/cl/device.h"
#include "host/cl/program.h"
#include "host/math/to_device.h"
#include "host/render/device_bvh.h"

namespace gc {
namespace {

bool same_bits(const dev::GcInstanceHit& a, const dev::GcInstanceHit& b)
{
    return a.instance == b.instance && test::same_bits(a.hit, b.hit);
}

struct DeviceResult {
    std::vector<dev::GcInstanceHit> hits;
    std::vector<std::uint32_t> occluded;
};

template <class Bvh>
DeviceResult trace_on_device(const cl::DeviceInfo& device, BvhLayout layout, const Bvh& bvh, const std::vector<Ray>& rays)
{
    const cl::Context context(device);
    const cl::Program program(context, "trace_instances.cl", program_options(layout));
    std::vector<dev::GcRay> device_rays;
    for (const Ray& r : rays) device_rays.push_back(to_device(r));
    const auto count = static_cast<std::uint32_t>(rays.size());
    auto tlas = cl::read_only_buffer(context, bvh.tlas, "tlas");
    auto instances = cl::read_only_buffer(context, bvh.instances, "instances");
    auto nodes = cl::read_only_buffer(context, bvh.nodes, "mesh nodes");
    auto tris = cl::read_only_buffer(context, bvh.tris, "mesh triangles");
    auto ray_buf = cl::read_only_buffer(context, device_rays, "rays");
    auto hit_buf = cl::Buffer<dev::GcInstanceHit>::create(context, count, CL_MEM_WRITE_ONLY, "hits");
    auto occ_buf = cl::Buffer<std::uint32_t>::create(context, count, CL_MEM_WRITE_ONLY, "occluded");
    cl::Kernel kernel = program.kernel("trace_instances_closest");
    kernel.set_args(tlas, instances, nodes, tris, ray_buf, hit_buf, occ_buf, count);
    kernel.launch(context, count);
    context.finish();
    DeviceResult r;
    r.hits.resize(count);
    r.occluded.resize(count);
    hit_buf.read(r.hits);
    occ_buf.read(r.occluded);
    return r;
}

// Device vs host reference in one layout: mismatching closest hits and any hits.
template <class Bvh>
std::pair<std::size_t, std::size_t> compare(const cl::DeviceInfo& device, BvhLayout layout, const Bvh& bvh,
                                            const std::vector<Ray>& rays)
{
    const DeviceResult d = trace_on_device(device, layout, bvh, rays);
    std::size_t closest = 0, any = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        closest += !same_bits(d.hits[i], trace_closest(bvh, rays[i]));
        any += (d.occluded[i] != 0u) != trace_any(bvh, rays[i]);
    }
    return {closest, any};
}

void expect_device_equals_host(const InstancedScene& s, const std::vector<Ray>& rays, const char* name)
{
    std::string why;
    const std::vector<cl::DeviceInfo> devices = cl::list_devices(&why);
    if (devices.empty()) GTEST_SKIP() << "no OpenCL device: " << why;
    const InstanceBvhParts parts = build_instance_bvh(s);
    const InstancedBvh b2 = assemble_binary(parts);
    const InstancedBvh4 b4 = assemble_wide(parts);
    const InstancedBvh8 b8 = assemble_wide8(parts);
    std::size_t hits = 0;
    for (const Ray& r : rays) hits += trace_closest(b2, r).instance != GC_INVALID;
    for (const cl::DeviceInfo& device : devices) {
        const std::pair<std::size_t, std::size_t> m[3] = {compare(device, BvhLayout::Binary, b2, rays),
                                                          compare(device, BvhLayout::Wide, b4, rays),
                                                          compare(device, BvhLayout::Wide8, b8, rays)};
        for (int l = 0; l < 3; ++l) {
            const char* layout = l == 0 ? "BVH2" : (l == 1 ? "BVH4" : "BVH8");
            std::printf("[instances] %s on %s, %s: %zu rays, %zu hits, closest mismatches %zu, any mismatches %zu\n",
                        name, device.device_name.c_str(), layout, rays.size(), hits, m[l].first, m[l].second);
            EXPECT_EQ(m[l].first, 0u) << device.device_name << " " << layout;
            EXPECT_EQ(m[l].second, 0u) << device.device_name << " " << layout;
        }
    }
    EXPECT_GT(hits, rays.size() / 4);
}

TEST(DeviceInstances, LatticeSceneEqualsHostAndFlattened)
{
    // The host reference equals the flattened scene bit for bit here (instance_bvh_test), so
    // device == host is device == flattened.
    const InstancedScene s = test::lattice_instances(3, 7);
    expect_device_equals_host(s, test::grid_rays(flatten_instances(s), 3000, 11), "lattice");
}

TEST(DeviceInstances, RotatedSceneEqualsHost)
{
    const InstancedScene s = test::rotated_instances(40, 3);
    expect_device_equals_host(s, test::mixed_rays(flatten_instances(s), 3000, 5), "rotated");
}

TEST(DeviceInstances, ThirtyTwoThousandInstancesTraceInOneLaunch)
{
    // 32^3 instances of a 1.2k-triangle torus knot (39M triangles drawn): primary rays of a
    // 96 x 96 camera looking into the grid.
    InstancedScene s;
    test::add_mesh(s, test::torus_knot(100, 6, 0.12f));
    const int n = 32;
    for (int x = 0; x < n; ++x)
        for (int y = 0; y < n; ++y)
            for (int z = 0; z < n; ++z) {
                Instance inst;
                inst.object_to_world = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(3.0f * x, 3.0f * y, 3.0f * z)),
                                                   0.1f * float(x + 2 * y + 3 * z), glm::vec3(0.3f, 0.8f, 0.5f));
                s.instances.push_back(inst);
            }
    std::vector<Ray> rays;
    const int w = 96;
    for (int j = 0; j < w; ++j)
        for (int i = 0; i < w; ++i) {
            Ray r;
            r.origin = Point3(-20.0f, -15.0f, -25.0f);
            r.direction = Vec3(1.0f, 0.8f + 0.6f * float(j) / w, 0.9f + 0.6f * float(i) / w);
            rays.push_back(r);
        }
    std::printf("[instances] %zu instances, %zu triangles drawn\n", s.instances.size(), s.instanced_triangle_count());
    expect_device_equals_host(s, rays, "32k instances");
}

}  // namespace
}  // namespace gc
