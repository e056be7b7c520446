// The kernels agree with the host on every OpenCL device present: BVH traversal equals a
// brute-force loop over all triangles, and the counter-based RNG draws identical numbers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "../bvh/test_scenes.h"
#include "gc_intersect.h"
#include "gc_rng.h"
#include "gc_sampling.h"
#include "host/bvh/bvh.h"
#include "host/bvh/traverse_host.h"
#include "host/cl/buffer.h"
#include "host/cl/context.h"
#include "host/cl/device.h"
#include "host/cl/program.h"
#include "host/math/to_device.h"
#include "host/render/device_bvh.h"
#include "host/scene/load.h"

namespace gc {
namespace {

std::vector<cl::DeviceInfo> devices_or_skip()
{
    std::string why;
    std::vector<cl::DeviceInfo> devices = cl::list_devices(&why);
    return devices;
}

// Random rays: origins inside the scene's (slightly enlarged) bounds, uniform directions.
std::vector<Ray> random_rays(const Scene& scene, std::size_t count, std::uint32_t seed)
{
    test::Rng rng(seed);
    Bounds3 b = scene.bounds();
    const Vec3 pad = 0.1f * b.diagonal();
    b.lo -= pad;
    b.hi += pad;
    std::vector<Ray> rays(count);
    for (Ray& r : rays) {
        r.origin = rng.point(b);
        r.direction = rng.direction();
    }
    return rays;
}

struct TraversalFigures {
    std::size_t hits = 0;
    std::size_t prim_mismatches = 0;
    std::size_t t_mismatches = 0;
    std::size_t any_mismatches = 0;
    float max_rel_t = 0.0f;
};

// trace.cl over the BVH in `layout` (both layouts on every device: the choice per device is
// about speed, the hits must not depend on it).
TraversalFigures compare_traversal(const cl::DeviceInfo& device, BvhLayout layout, const Scene& scene,
                                   const std::vector<Ray>& rays, const std::vector<dev::GcHit>& brute_force)
{
    const FlatBvh bvh = build_bvh(scene);
    const cl::Context context(device);
    const DeviceBvh device_bvh = DeviceBvh::upload(context, bvh, layout);
    const cl::Program program(context, "trace.cl", program_options(layout));
    std::vector<dev::GcRay> device_rays;
    for (const Ray& r : rays) device_rays.push_back(to_device(r));
    const auto count = static_cast<std::uint32_t>(rays.size());

    auto ray_buf = cl::Buffer<dev::GcRay>::create(context, count, CL_MEM_READ_ONLY, "rays");
    auto hit_buf = cl::Buffer<dev::GcHit>::create(context, count, CL_MEM_WRITE_ONLY, "hits");
    auto occ_buf = cl::Buffer<std::uint32_t>::create(context, count, CL_MEM_WRITE_ONLY, "occluded");
    ray_buf.write(device_rays);

    cl::Kernel closest = program.kernel("trace_closest");
    closest.set_args(device_bvh.nodes(), device_bvh.triangles(), ray_buf, hit_buf, count);
    closest.launch(context, count);
    cl::Kernel any = program.kernel("trace_any");
    any.set_args(device_bvh.nodes(), device_bvh.triangles(), ray_buf, occ_buf, count);
    any.launch(context, count);
    context.finish();
    std::vector<dev::GcHit> hits(count);
    std::vector<std::uint32_t> occluded(count);
    hit_buf.read(hits);
    occ_buf.read(occluded);

    TraversalFigures f;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const dev::GcHit& expected = brute_force[i];
        const dev::GcHit& got = hits[i];
        if (expected.prim != GC_INVALID) ++f.hits;
        if (got.prim != expected.prim) {
            ++f.prim_mismatches;
            continue;
        }
        if ((occluded[i] != 0) != (expected.prim != GC_INVALID)) ++f.any_mismatches;
        if (expected.prim == GC_INVALID) continue;
        const float rel = std::fabs(got.t - expected.t) / std::fmax(std::fabs(expected.t), 1e-30f);
        f.max_rel_t = std::fmax(f.max_rel_t, rel);
        if (rel > 1e-5f) ++f.t_mismatches;
    }
    return f;
}

void expect_traversal_matches(const Scene& scene, const std::string& name, std::size_t ray_count)
{
    const std::vector<cl::DeviceInfo> devices = devices_or_skip();
    if (devices.empty()) GTEST_SKIP() << "no OpenCL device";
    const std::vector<Ray> rays = random_rays(scene, ray_count, 1234);
    // The brute-force answer (every ray against every triangle) is the slow part: once per scene.
    std::vector<dev::GcHit> brute_force;
    for (const Ray& r : rays) brute_force.push_back(trace_brute_force(scene, r));
    for (const cl::DeviceInfo& device : devices) {
        for (const BvhLayout layout : {BvhLayout::Binary, BvhLayout::Wide, BvhLayout::Wide8}) {
            const TraversalFigures f = compare_traversal(device, layout, scene, rays, brute_force);
            std::printf("[traversal] %s on %s, %s: %zu rays, %zu hits, prim mismatches %zu, t mismatches %zu "
                        "(max rel t error %.3g), any-hit mismatches %zu\n",
                        name.c_str(), device.device_name.c_str(), layout_name(layout), rays.size(), f.hits,
                        f.prim_mismatches, f.t_mismatches, static_cast<double>(f.max_rel_t), f.any_mismatches);
            EXPECT_GT(f.hits, ray_count / 5) << "too few hits to mean anything";
            EXPECT_EQ(f.prim_mismatches, 0u) << device.device_name << " " << layout_name(layout);
            EXPECT_EQ(f.t_mismatches, 0u) << device.device_name << " " << layout_name(layout);
            EXPECT_EQ(f.any_mismatches, 0u) << device.device_name << " " << layout_name(layout);
        }
    }
}

TEST(DeviceTraversal, RandomSoupEqualsBruteForce)
{
    expect_traversal_matches(test::random_soup(5000, 7, 0.15f), "random soup (5k triangles)", 10000);
}

TEST(DeviceTraversal, CornellSphereEqualsBruteForce)
{
    const Scene scene =
        load_scene(std::filesystem::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Sphere.obj");
    expect_traversal_matches(scene, "CornellBox-Sphere", 10000);
}

TEST(DeviceTraversal, TorusKnotEqualsBruteForce)
{
    // A 100k-triangle surface that winds past itself (test::torus_knot). 2,500 rays x 100k
    // triangles of brute force is already 2.5e8 triangle tests.
    expect_traversal_matches(test::torus_knot(1000, 50, 0.5f), "torus knot (100k triangles)", 2500);
}

// Eight rays per work-item as one packet (gc_packet8.h, what the CPU path megakernel traces
// a pixel's camera rays with) against the single-ray traversal of the same BVH8 on the same
// device: the same hit records, bit for bit, lane by lane; inactive lanes miss.
std::size_t packet_hits_differing(const cl::DeviceInfo& device, const Scene& scene, const std::vector<dev::GcRay>& rays,
                                  std::size_t* hits)
{
    const FlatBvh bvh = build_bvh(scene);
    const cl::Context context(device);
    const DeviceBvh device_bvh = DeviceBvh::upload(context, bvh, BvhLayout::Wide8);
    const cl::Program program(context, "trace.cl", program_options(BvhLayout::Wide8));
    const auto count = static_cast<std::uint32_t>(rays.size());
    std::vector<int> active(count);
    for (std::uint32_t i = 0; i < count; ++i) active[i] = (i / 8 * 3 + i % 8) % 7 == 6 ? 0 : 1;  // some lanes idle
    auto ray_buf = cl::Buffer<dev::GcRay>::create(context, count, CL_MEM_READ_ONLY, "rays");
    auto active_buf = cl::Buffer<int>::create(context, count, CL_MEM_READ_ONLY, "active lanes");
    auto single_buf = cl::Buffer<dev::GcHit>::create(context, count, CL_MEM_WRITE_ONLY, "single-ray hits");
    auto packet_buf = cl::Buffer<dev::GcHit>::create(context, count, CL_MEM_WRITE_ONLY, "packet hits");
    ray_buf.write(rays);
    active_buf.write(active);
    cl::Kernel single = program.kernel("trace_closest");
    single.set_args(device_bvh.nodes(), device_bvh.triangles(), ray_buf, single_buf, count);
    single.launch(context, count);
    cl::Kernel packets = program.kernel("trace_closest8");
    packets.set_args(device_bvh.nodes(), device_bvh.triangles(), ray_buf, active_buf, packet_buf, count / 8);
    packets.launch(context, count / 8);
    context.finish();
    std::vector<dev::GcHit> expected(count);
    std::vector<dev::GcHit> got(count);
    single_buf.read(expected);
    packet_buf.read(got);
    std::size_t differing = 0;
    *hits = 0;
    for (std::uint32_t i = 0; i < count; ++i) {
        const dev::GcHit want = active[i] ? expected[i] : dev::gc_no_hit();
        if (active[i] && want.prim != GC_INVALID) ++*hits;
        differing += std::memcmp(&want, &got[i], sizeof want) != 0 ? 1 : 0;
    }
    return differing;
}

TEST(DeviceTraversal, PacketsOfEightEqualSingleRays)
{
    const std::vector<cl::DeviceInfo> devices = devices_or_skip();
    if (devices.empty()) GTEST_SKIP() << "no OpenCL device";
    // Incoherent: every lane its own random ray through a random soup whose first 2500
    // triangles appear twice, so that many hits are exact ties in t, which the smaller scene
    // index must win (gc_traverse.h's tie rule) in the packet as in the single ray.
    Scene soup = test::random_soup(5000, 7, 0.15f);
    for (std::size_t i = 0; i < 2500; ++i) {
        for (int j = 0; j < 3; ++j) {
            soup.positions.push_back(soup.positions[3 * i + j]);
            soup.normals.push_back(soup.normals[3 * i + j]);
        }
        soup.material_ids.push_back(soup.material_ids[i]);
        soup.has_vertex_normals.push_back(soup.has_vertex_normals[i]);
    }
    std::vector<dev::GcRay> scattered;
    for (const Ray& r : random_rays(soup, 8000, 4321)) scattered.push_back(to_device(r));
    // Every other one a segment: its closest hit lies before its end or is a miss.
    const float reach = 0.3f * length(soup.bounds().diagonal());
    for (std::size_t i = 1; i < scattered.size(); i += 2) scattered[i].dir_tmax.w = reach;
    // Coherent: a pixel's camera rays into the Cornell box with the sphere (eight jittered
    // directions per pixel of a 40x40 view, as the megakernel's packets), every fifth packet a
    // segment from t 0.5 to 3 instead of a whole ray.
    const Scene box = load_scene(std::filesystem::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Sphere.obj");
    std::vector<dev::GcRay> camera;
    test::Rng rng(77);
    for (int p = 0; p < 40 * 40; ++p) {
        const bool segment = p % 5 == 4;
        for (int k = 0; k < 8; ++k) {
            const float sx = ((p % 40) + rng.uniform()) / 20.0f - 1.0f;
            const float sy = 1.0f - ((p / 40) + rng.uniform()) / 20.0f;
            const glm::vec3 d = glm::normalize(glm::vec3(0.72f * sx, 0.72f * sy, -2.0f));
            camera.push_back(dev::gc_make_ray(glm::vec3(0.0f, 1.0f, 3.9f), d, segment ? 0.5f : 0.0f,
                                              segment ? 3.0f : GC_RAY_UNBOUNDED));
        }
    }
    for (const cl::DeviceInfo& device : devices) {
        for (const auto& [name, scene, rays] : {std::tuple<const char*, const Scene&, const std::vector<dev::GcRay>&>{
                                                    "random soup with duplicates, scattered rays", soup, scattered},
                                                {"CornellBox-Sphere, camera rays", box, camera}}) {
            std::size_t hits = 0;
            const std::size_t differing = packet_hits_differing(device, scene, rays, &hits);
            std::printf("[packets] %s on %s: %zu rays in packets of 8, %zu hits, %zu hit records differ from the "
                        "single-ray traversal's\n",
                        name, device.device_name.c_str(), rays.size(), hits, differing);
            EXPECT_GT(hits, rays.size() / 5) << "too few hits to mean anything";
            EXPECT_EQ(differing, 0u) << device.device_name << ", " << name;
        }
    }
}

// Both samplers (gc_rand4, and gc_sobol_rand4's integer scrambles and Sobol recurrence).
TEST(DeviceRng, StreamEqualsHost)
{
    const std::vector<cl::DeviceInfo> devices = devices_or_skip();
    if (devices.empty()) GTEST_SKIP() << "no OpenCL device";
    // Keys spread over pixels, samples, blocks and seeds, including the extremes.
    std::vector<glm::uvec4> keys;
    test::Rng rng(99);
    for (std::uint32_t i = 0; i < 4096; ++i)
        keys.push_back({rng.below(1u << 24), rng.below(1u << 20), rng.below(4096), rng.below(1000)});
    keys.push_back({0u, 0u, 0u, 0u});
    keys.push_back({0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu});
    const auto count = static_cast<std::uint32_t>(keys.size());
    for (const cl::DeviceInfo& device : devices) {
        const cl::Context context(device);
        const cl::Program program(context, "test/rng_probe.cl");
        auto key_buf = cl::Buffer<glm::uvec4>::create(context, count, CL_MEM_READ_ONLY, "rng keys");
        auto value_buf = cl::Buffer<glm::vec4>::create(context, count, CL_MEM_WRITE_ONLY, "rng values");
        key_buf.write(keys);
        cl::Kernel kernel = program.kernel("rng_probe");
        for (const std::uint32_t sobol : {0u, 1u}) {
            kernel.set_args(key_buf, value_buf, count, sobol);
            kernel.launch(context, count);
            context.finish();
            std::vector<glm::vec4> values(count);
            value_buf.read(values);
            std::size_t differing = 0;
            for (std::uint32_t i = 0; i < count; ++i) {
                const glm::uvec4 k = keys[i];
                const glm::vec4 expected =
                    sobol != 0 ? dev::gc_sobol_rand4(k.x, k.y, k.z, k.w) : dev::gc_rand4(k.x, k.y, k.z, k.w);
                if (values[i] != expected) ++differing;
                for (int c = 0; c < 4; ++c) {
                    ASSERT_GE(values[i][c], 0.0f);
                    ASSERT_LT(values[i][c], 1.0f);
                }
            }
            std::printf("[rng] %s, %s: %u keys, %zu differ from the host\n", device.device_name.c_str(),
                        sobol != 0 ? "sobol" : "independent", count, differing);
            EXPECT_EQ(differing, 0u) << device.device_name << (sobol != 0 ? ", sobol" : ", independent");
        }
    }
}

TEST(DeviceSampling, TrigAndHemisphereEqualHost)
{
    const std::vector<cl::DeviceInfo> devices = devices_or_skip();
    if (devices.empty()) GTEST_SKIP() << "no OpenCL device";
    // Random pairs plus the quarter turns and the ends of [0, 1).
    std::vector<glm::vec2> inputs;
    test::Rng rng(7);
    for (std::uint32_t i = 0; i < 8192; ++i)
        inputs.push_back({static_cast<float>(rng.below(1u << 24)) / 16777216.0f,
                          static_cast<float>(rng.below(1u << 24)) / 16777216.0f});
    for (const float t : {0.0f, 0.125f, 0.25f, 0.375f, 0.5f, 0.625f, 0.75f, 0.875f, 1.0f, 0.99999994f})
        inputs.push_back({t, t});
    const auto count = static_cast<std::uint32_t>(inputs.size());
    for (const cl::DeviceInfo& device : devices) {
        const cl::Context context(device);
        const cl::Program program(context, "test/sampling_probe.cl");
        auto input_buf = cl::Buffer<glm::vec2>::create(context, count, CL_MEM_READ_ONLY, "sampling inputs");
        auto turns_buf = cl::Buffer<glm::vec4>::create(context, count, CL_MEM_WRITE_ONLY, "trig values");
        auto hemisphere_buf = cl::Buffer<glm::vec4>::create(context, count, CL_MEM_WRITE_ONLY, "hemisphere samples");
        input_buf.write(inputs);
        cl::Kernel kernel = program.kernel("sampling_probe");
        kernel.set_args(input_buf, turns_buf, hemisphere_buf, count);
        kernel.launch(context, count);
        context.finish();
        std::vector<glm::vec4> turns(count);
        std::vector<glm::vec4> hemisphere(count);
        turns_buf.read(turns);
        hemisphere_buf.read(hemisphere);
        std::size_t differing = 0;
        for (std::uint32_t i = 0; i < count; ++i) {
            const glm::vec2 u = inputs[i];
            const glm::vec4 expected_trig(dev::gc_cos_sin_turns(u.x),
                                          dev::gc_cos_sin_quarter((2.0f * u.y - 1.0f) * (0.25f * GC_PI)));
            const glm::vec4 expected_dir(dev::gc_sample_cosine_hemisphere(u.x, u.y), 0.0f);
            if (turns[i] != expected_trig || hemisphere[i] != expected_dir) ++differing;
        }
        std::printf("[sampling] %s: %u inputs, %zu differ from the host (bit for bit)\n", device.device_name.c_str(),
                    count, differing);
        EXPECT_EQ(differing, 0u) << device.device_name;
    }
}

// kernels/test/packet_probe.cl: the same vertex with 8 and 16 vertices per work-item in vector
// lanes gives the bits of one vertex per work-item, on every device, including vertices on the
// light's plane (division by zero) and normals along -z (the frame's special case). This is
// the premise of explicit SIMD across paths on CPUs: the image would not change.
TEST(DevicePacketProbe, VectorLanesGiveTheScalarBits)
{
    const std::vector<cl::DeviceInfo> devices = devices_or_skip();
    if (devices.empty()) GTEST_SKIP() << "no OpenCL device";
    constexpr std::uint32_t count = 4096;  // a multiple of 16
    std::vector<std::vector<float>> inputs(9, std::vector<float>(count));
    test::Rng rng(11);
    for (std::uint32_t i = 0; i < count; ++i) {
        const Point3 p = rng.point(Bounds3{Point3(-1.0f, -1.0f, -1.0f), Point3(1.0f, 1.0f, 1.0f)});
        const Vec3 n = i % 7 == 0 ? Vec3(0.0f, 0.0f, -1.0f) : rng.direction();
        const float py = i % 11 == 0 ? 1.98f : p.y;  // on the light's plane
        const float values[9] = {p.x, py, p.z, n.x, n.y, n.z, 0.5f, 0.6f, 0.7f};
        for (int k = 0; k < 9; ++k) inputs[static_cast<std::size_t>(k)][i] = values[k];
    }
    for (const cl::DeviceInfo& device : devices) {
        const cl::Context context(device);
        const cl::Program program(context, "test/packet_probe.cl");
        std::vector<cl::Buffer<float>> in;
        for (const std::vector<float>& v : inputs) in.push_back(cl::read_only_buffer(context, v, "probe input"));
        std::vector<std::vector<float>> results;  // per form, the six outputs one after the other
        for (const auto& [name, lanes] : {std::pair<const char*, std::uint32_t>{"packet_probe_x1", 1u},
                                          {"packet_probe_x8", 8u}, {"packet_probe_x16", 16u}}) {
            std::vector<cl::Buffer<float>> out;
            for (int k = 0; k < 6; ++k) out.push_back(cl::Buffer<float>::create(context, count, CL_MEM_WRITE_ONLY, "probe output"));
            cl::Kernel kernel = program.kernel(name);
            kernel.set_args(in[0], in[1], in[2], in[3], in[4], in[5], in[6], in[7], in[8], out[0], out[1], out[2],
                            out[3], out[4], out[5], 77u, count);
            kernel.launch(context, count / lanes);
            context.finish();
            std::vector<float> all(6 * count);
            for (std::size_t k = 0; k < 6; ++k) out[k].read(std::span<float>(all.data() + k * count, count));
            results.push_back(std::move(all));
        }
        // NaN payloads are not part of an image, so two NaNs count as equal.
        std::size_t differing = 0, non_finite = 0;
        for (std::size_t i = 0; i < results[0].size(); ++i) {
            const float x = results[0][i];
            non_finite += std::isfinite(x) ? 0 : 1;
            for (std::size_t f = 1; f < results.size(); ++f) {
                const float y = results[f][i];
                const bool same = std::memcmp(&x, &y, sizeof x) == 0 || (std::isnan(x) && std::isnan(y));
                differing += same ? 0 : 1;
            }
        }
        std::printf("[packet] %s: %zu outputs of float8 and float16 lanes against one vertex per work-item "
                    "(%zu of them non-finite), %zu differ in their bits\n",
                    device.device_name.c_str(), 2 * results[0].size(), 2 * non_finite, differing);
        EXPECT_EQ(differing, 0u) << device.device_name;
    }
}

// gc_queue.h's work-group reservation (used by the wavefront's shade stage): for several
// counts and group sizes, including partial last groups and groups with nothing to push, each
// queue gets every pushing work-item exactly once and its counter says how many.
TEST(DeviceQueue, WorkGroupReservationPushesEachItemOnce)
{
    const std::vector<cl::DeviceInfo> devices = devices_or_skip();
    if (devices.empty()) GTEST_SKIP() << "no OpenCL device";
    for (const cl::DeviceInfo& device : devices) {
        const cl::Context context(device);
        const cl::Program program(context, "test/queue_probe.cl");
        cl::Kernel kernel = program.kernel("queue_probe");
        for (const std::uint32_t count : {1u, 2u, 127u, 1000u, 4099u}) {
            for (const std::size_t local : {std::size_t{1}, std::size_t{16}, std::size_t{64}}) {
                auto queue0 = cl::Buffer<std::uint32_t>::create(context, count, CL_MEM_READ_WRITE, "queue 0");
                auto queue1 = cl::Buffer<std::uint32_t>::create(context, count, CL_MEM_READ_WRITE, "queue 1");
                auto counters = cl::Buffer<std::uint32_t>::create(context, 2, CL_MEM_READ_WRITE, "queue counters");
                const std::vector<std::uint32_t> sentinel(count, 0xffffffffu);
                queue0.write(sentinel);
                queue1.write(sentinel);
                counters.write(std::vector<std::uint32_t>{0u, 0u});
                kernel.set_args(queue0, queue1, counters, count);
                kernel.launch(context, count, local);
                context.finish();
                std::vector<std::uint32_t> got0(count), got1(count), counts(2);
                queue0.read(got0);
                queue1.read(got1);
                counters.read(counts);
                const auto check = [&](const std::vector<std::uint32_t>& got, std::uint32_t n, std::uint32_t step) {
                    const std::uint32_t expected = (count + step - 1) / step;  // items 0, step, 2 step, ...
                    EXPECT_EQ(n, expected) << device.device_name << ": count " << count << ", local " << local;
                    std::vector<std::uint32_t> seen(count, 0);
                    std::size_t wrong = 0;
                    for (std::uint32_t k = 0; k < std::min(n, count); ++k) {
                        if (got[k] >= count || got[k] % step != 0) ++wrong;
                        else ++seen[got[k]];
                    }
                    for (std::uint32_t i = 0; i < count; i += step) wrong += seen[i] == 1 ? 0 : 1;
                    EXPECT_EQ(wrong, 0u) << device.device_name << ": count " << count << ", local " << local
                                         << ", every " << step;
                    return wrong;
                };
                const std::size_t wrong = check(got0, counts[0], 3) + check(got1, counts[1], 5);
                if (count == 4099u && local == 64)
                    std::printf("[queue] %s: %u items in groups of %zu: %u and %u pushed, %zu misplaced\n",
                                device.device_name.c_str(), count, local, counts[0], counts[1], wrong);
            }
        }
    }
}

}  // namespace
}  // namespace gc
