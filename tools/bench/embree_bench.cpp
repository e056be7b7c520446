#include "tools/bench/embree_bench.h"

#include "host/util/error.h"
#include "host/util/host_threads.h"

#if defined(GC_HAVE_EMBREE)
#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "host/bvh/big_array.h"
#include "tools/bench/rays.h"
#include "tools/bench/timing.h"
#endif

namespace gc::bench {

#if defined(GC_HAVE_EMBREE)
namespace {

// Embree's build threads follow the bench's cap (--threads), so both sides get the same cores.
RTCDevice new_device()
{
    const std::string config = "threads=" + std::to_string(host_thread_count());
    RTCDevice device = rtcNewDevice(config.c_str());
    if (!device) throw DeviceError("Embree: rtcNewDevice failed (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
    return device;
}

RTCBounds empty_bounds()
{
    RTCBounds b{};
    b.lower_x = b.lower_y = b.lower_z = std::numeric_limits<float>::infinity();
    b.upper_x = b.upper_y = b.upper_z = -std::numeric_limits<float>::infinity();
    return b;
}

// Grows `into` by a box with Embree's field names (RTCBounds or RTCBuildPrimitive).
template <class Box>
void grow(RTCBounds& into, const Box& b)
{
    into.lower_x = std::min(into.lower_x, b.lower_x);
    into.lower_y = std::min(into.lower_y, b.lower_y);
    into.lower_z = std::min(into.lower_z, b.lower_z);
    into.upper_x = std::max(into.upper_x, b.upper_x);
    into.upper_y = std::max(into.upper_y, b.upper_y);
    into.upper_z = std::max(into.upper_z, b.upper_z);
}

// rtcBuildBVH callbacks: nodes live in Embree's thread-local allocator, freed with the RTCBVH.
struct Node {
    bool leaf;
};
struct Inner : Node {
    RTCBounds bounds[2];
    Node* child[2];
};
struct Leaf : Node {
    std::uint32_t count;
};

void* create_node(RTCThreadLocalAllocator alloc, unsigned int, void*)
{
    auto* node = static_cast<Inner*>(rtcThreadLocalAlloc(alloc, sizeof(Inner), 16));
    node->leaf = false;
    node->child[0] = node->child[1] = nullptr;
    return node;
}

void set_children(void* node, void** children, unsigned int count, void*)
{
    auto* inner = static_cast<Inner*>(node);
    for (unsigned int i = 0; i < count && i < 2; ++i) inner->child[i] = static_cast<Node*>(children[i]);
}

void set_bounds(void* node, const RTCBounds** bounds, unsigned int count, void*)
{
    auto* inner = static_cast<Inner*>(node);
    for (unsigned int i = 0; i < count && i < 2; ++i) inner->bounds[i] = *bounds[i];
}

void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive*, size_t count, void*)
{
    auto* leaf = static_cast<Leaf*>(rtcThreadLocalAlloc(alloc, sizeof(Leaf), 16));
    leaf->leaf = true;
    leaf->count = static_cast<std::uint32_t>(count);
    return leaf;
}

double area(const RTCBounds& b)
{
    const double dx = double(b.upper_x) - double(b.lower_x);
    const double dy = double(b.upper_y) - double(b.lower_y);
    const double dz = double(b.upper_z) - double(b.lower_z);
    if (dx < 0.0 || dy < 0.0 || dz < 0.0) return 0.0;
    return 2.0 * (dx * dy + dy * dz + dz * dx);
}

void fill_ray(RTCRay& ray, const dev::GcRay& r)
{
    ray.org_x = r.org_tmin.x;
    ray.org_y = r.org_tmin.y;
    ray.org_z = r.org_tmin.z;
    ray.tnear = r.org_tmin.w;
    ray.dir_x = r.dir_tmax.x;
    ray.dir_y = r.dir_tmax.y;
    ray.dir_z = r.dir_tmax.z;
    ray.tfar = r.dir_tmax.w;
    ray.time = 0.0f;
    ray.mask = 0xffffffffu;
    ray.id = 0;
    ray.flags = 0;
}

// Lanes 0-15 of a 16-ray packet from rays[base, base + 16), clamped to rays[end - 1], with
// `valid` marking the lanes below `end` (the last packet of a range may be short).
void fill_ray16(RTCRay16& ray, int* valid, const std::vector<dev::GcRay>& rays, std::size_t base, std::size_t end)
{
    for (int k = 0; k < 16; ++k) {
        const std::size_t i = base + k;
        valid[k] = i < end ? -1 : 0;
        const dev::GcRay& r = rays[std::min(i, end - 1)];
        ray.org_x[k] = r.org_tmin.x;
        ray.org_y[k] = r.org_tmin.y;
        ray.org_z[k] = r.org_tmin.z;
        ray.tnear[k] = r.org_tmin.w;
        ray.dir_x[k] = r.dir_tmax.x;
        ray.dir_y[k] = r.dir_tmax.y;
        ray.dir_z[k] = r.dir_tmax.z;
        ray.tfar[k] = r.dir_tmax.w;
        ray.time[k] = 0.0f;
        ray.mask[k] = 0xffffffffu;
        ray.id[k] = 0;
        ray.flags[k] = 0;
    }
}

}  // namespace

bool embree_available() { return true; }

std::string embree_version()
{
    return std::to_string(RTC_VERSION_MAJOR) + "." + std::to_string(RTC_VERSION_MINOR) + "." +
           std::to_string(RTC_VERSION_PATCH);
}

EmbreeBuildFigures embree_build_bvh2(const Scene& scene, const BvhBuildOptions& options)
{
    const std::size_t n = scene.triangle_count();
    EmbreeBuildFigures figures;
    if (n == 0) return figures;
    RTCDevice device = new_device();
    RTCBounds root = empty_bounds();

    const auto start = Clock::now();
    // The primitive array is part of the build, as our builder's triangle-bounds pass is part
    // of ours: allocated here the way ours is (BigArray: uninitialised, on huge pages), so
    // both sides pay for first touching its pages, and made on all the bench's threads as
    // ours is (in chunks, each with its bounds, joined after). It used to be a std::vector
    // zero-filled before the clock started, which left the 5.2M-triangle scene's 168 MB of
    // fresh pages out of Embree's time but not out of ours.
    BigArray<RTCBuildPrimitive> prims(n);
    constexpr std::size_t kChunk = 16384;
    std::vector<RTCBounds> chunk_bounds((n + kChunk - 1) / kChunk);
    parallel_for(n, host_thread_count(), kChunk, [&](std::size_t begin, std::size_t end) {
        RTCBounds b = empty_bounds();
        for (std::size_t t = begin; t < end; ++t) {
            RTCBuildPrimitive& p = prims[t];
            const Point3 a = scene.vertex(t, 0);
            const Point3 v1 = scene.vertex(t, 1);
            const Point3 v2 = scene.vertex(t, 2);
            p.lower_x = std::min({a.x, v1.x, v2.x});
            p.lower_y = std::min({a.y, v1.y, v2.y});
            p.lower_z = std::min({a.z, v1.z, v2.z});
            p.upper_x = std::max({a.x, v1.x, v2.x});
            p.upper_y = std::max({a.y, v1.y, v2.y});
            p.upper_z = std::max({a.z, v1.z, v2.z});
            p.geomID = 0;
            p.primID = static_cast<unsigned>(t);
            grow(b, p);
        }
        chunk_bounds[begin / kChunk] = b;
    });
    for (const RTCBounds& b : chunk_bounds) grow(root, b);
    figures.prims_seconds = seconds_since(start);
    RTCBVH bvh = rtcNewBVH(device);
    RTCBuildArguments args = rtcDefaultBuildArguments();
    args.byteSize = sizeof(args);
    args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
    args.maxBranchingFactor = 2;
    args.maxDepth = 63; // our builder's depth limit
    args.sahBlockSize = 1;
    args.minLeafSize = 1;
    args.maxLeafSize = static_cast<unsigned>(options.max_leaf_size);
    args.traversalCost = options.traversal_cost;
    args.intersectionCost = options.intersection_cost;
    args.bvh = bvh;
    args.primitives = prims.data();
    args.primitiveCount = n;
    args.primitiveArrayCapacity = n;
    args.createNode = create_node;
    args.setNodeChildren = set_children;
    args.setNodeBounds = set_bounds;
    args.createLeaf = create_leaf;
    const Node* root_node = static_cast<const Node*>(rtcBuildBVH(&args));
    figures.bvh2_seconds = seconds_since(start);
    if (!root_node) {
        rtcReleaseBVH(bvh);
        rtcReleaseDevice(device);
        throw DeviceError("Embree: rtcBuildBVH failed (error " + std::to_string(rtcGetDeviceError(device)) + ")");
    }

    // The SAH of bvh_stats: (C_trav * sum inner SA + C_isect * sum leaf SA * count) / SA(root).
    double inner_area = 0.0;
    double leaf_area = 0.0;
    std::size_t nodes = 1;
    if (root_node->leaf) {
        leaf_area = area(root) * static_cast<const Leaf*>(root_node)->count;
    } else {
        inner_area = area(root);
        std::vector<const Inner*> stack{static_cast<const Inner*>(root_node)};
        while (!stack.empty()) {
            const Inner* node = stack.back();
            stack.pop_back();
            for (int i = 0; i < 2; ++i) {
                const Node* child = node->child[i];
                if (!child) continue;
                ++nodes;
                if (child->leaf) {
                    leaf_area += area(node->bounds[i]) * static_cast<const Leaf*>(child)->count;
                } else {
                    inner_area += area(node->bounds[i]);
                    stack.push_back(static_cast<const Inner*>(child));
                }
            }
        }
    }
    const double root_area = area(root);
    if (root_area > 0.0)
        figures.bvh2_sah = float((double(options.traversal_cost) * inner_area +
                                  double(options.intersection_cost) * leaf_area) / root_area);
    figures.bvh2_nodes = nodes;
    rtcReleaseBVH(bvh);
    rtcReleaseDevice(device);
    return figures;
}

struct EmbreeTracer::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    double commit_seconds = 0.0;
};

EmbreeTracer::EmbreeTracer(const Scene& scene) : m_impl(std::make_unique<Impl>())
{
    m_impl->device = new_device();
    const auto start = Clock::now();
    m_impl->scene = rtcNewScene(m_impl->device);
    RTCGeometry geom = rtcNewGeometry(m_impl->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    const std::size_t n = scene.triangle_count();
    auto* verts = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
    auto* index = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
    for (std::size_t i = 0; i < 3 * n; ++i) {
        verts[3 * i + 0] = scene.positions[i].x;
        verts[3 * i + 1] = scene.positions[i].y;
        verts[3 * i + 2] = scene.positions[i].z;
        index[i] = static_cast<unsigned>(i);
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(m_impl->scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(m_impl->scene);
    m_impl->commit_seconds = seconds_since(start);
}

EmbreeTracer::~EmbreeTracer()
{
    if (m_impl->scene) rtcReleaseScene(m_impl->scene);
    if (m_impl->device) rtcReleaseDevice(m_impl->device);
}

double EmbreeTracer::commit_seconds() const { return m_impl->commit_seconds; }

double EmbreeTracer::closest(const std::vector<dev::GcRay>& rays, int threads, int width,
                             std::vector<std::uint32_t>& prims) const
{
    prims.assign(rays.size(), GC_INVALID);
    RTCScene scene = m_impl->scene;
    const auto start = Clock::now();
    if (width == 16) {
        parallel_for(rays.size(), threads, 4096, [&](std::size_t begin, std::size_t end) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            for (std::size_t base = begin; base < end; base += 16) {
                alignas(64) RTCRayHit16 rh;
                alignas(64) int valid[16];
                fill_ray16(rh.ray, valid, rays, base, end);
                for (int k = 0; k < 16; ++k) {
                    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                    rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
                }
                rtcIntersect16(valid, scene, &context, &rh);
                for (int k = 0; k < 16 && base + k < end; ++k)
                    prims[base + k] = rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID ? GC_INVALID : rh.hit.primID[k];
            }
        });
    } else {
        parallel_for(rays.size(), threads, 4096, [&](std::size_t begin, std::size_t end) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            for (std::size_t i = begin; i < end; ++i) {
                RTCRayHit rh;
                fill_ray(rh.ray, rays[i]);
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(scene, &context, &rh);
                prims[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? GC_INVALID : rh.hit.primID;
            }
        });
    }
    return seconds_since(start);
}

double EmbreeTracer::occluded(const std::vector<dev::GcRay>& rays, int threads, int width,
                              std::vector<std::uint32_t>& flags) const
{
    flags.assign(rays.size(), 0u);
    RTCScene scene = m_impl->scene;
    const auto start = Clock::now();
    if (width == 16) {
        parallel_for(rays.size(), threads, 4096, [&](std::size_t begin, std::size_t end) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            for (std::size_t base = begin; base < end; base += 16) {
                alignas(64) RTCRay16 ray;
                alignas(64) int valid[16];
                fill_ray16(ray, valid, rays, base, end);
                rtcOccluded16(valid, scene, &context, &ray);
                // An occluded ray's tfar becomes -inf.
                for (int k = 0; k < 16 && base + k < end; ++k) flags[base + k] = ray.tfar[k] < 0.0f ? 1u : 0u;
            }
        });
    } else {
        parallel_for(rays.size(), threads, 4096, [&](std::size_t begin, std::size_t end) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            for (std::size_t i = begin; i < end; ++i) {
                RTCRay ray;
                fill_ray(ray, rays[i]);
                rtcOccluded1(scene, &context, &ray);
                flags[i] = ray.tfar < 0.0f ? 1u : 0u;
            }
        });
    }
    return seconds_since(start);
}

#else  // no Embree: stubs

bool embree_available() { return false; }
std::string embree_version() { return ""; }
EmbreeBuildFigures embree_build_bvh2(const Scene&, const BvhBuildOptions&)
{
    throw DeviceError("geocold-bench was built without Embree");
}
struct EmbreeTracer::Impl {};
EmbreeTracer::EmbreeTracer(const Scene&) { throw DeviceError("geocold-bench was built without Embree"); }
EmbreeTracer::~EmbreeTracer() = default;
double EmbreeTracer::commit_seconds() const { return 0.0; }
double EmbreeTracer::closest(const std::vector<dev::GcRay>&, int, int, std::vector<std::uint32_t>&) const { return 0.0; }
double EmbreeTracer::occluded(const std::vector<dev::GcRay>&, int, int, std::vector<std::uint32_t>&) const { return 0.0; }

#endif

}  // namespace gc::bench
