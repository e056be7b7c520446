#include "tools/bench/rays.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "gc_camera.h"
#include "gc_intersect.h"
#include "gc_sampling.h"
#include "gc_traverse.h"
#include "host/bvh/traverse_host.h"
#include "host/render/scene_convert.h"

namespace gc::bench {
namespace {

// Counter-based random numbers in [0, 1): a 64-bit mix of (index, dimension).
float random01(std::uint64_t index, std::uint32_t dim)
{
    std::uint64_t x = index * 0x9e3779b97f4a7c15ull + (std::uint64_t{dim} << 40) + 0x632be59bd9b4e019ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    x ^= x >> 31;
    return static_cast<float>(x >> 40) * (1.0f / 16777216.0f);
}

glm::vec3 to_glm(const dev::float4& v) { return {v.x, v.y, v.z}; }

// Duff et al. 2017, "Building an Orthonormal Basis, Revisited".
void basis(const glm::vec3& n, glm::vec3& t, glm::vec3& b)
{
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float c = n.x * n.y * a;
    t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

}  // namespace

void parallel_for(std::size_t count, int threads, std::size_t chunk,
                  const std::function<void(std::size_t, std::size_t)>& fn)
{
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        for (;;) {
            const std::size_t begin = next.fetch_add(chunk);
            if (begin >= count) return;
            fn(begin, std::min(count, begin + chunk));
        }
    };
    // No more threads than chunks: a thread's start costs more than a small chunk's work.
    const std::size_t chunks = (count + chunk - 1) / std::max<std::size_t>(chunk, 1);
    const auto spawned = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), chunks));
    std::vector<std::thread> pool;
    for (int i = 1; i < spawned; ++i) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
}

RaySet make_rays(const Scene& scene, const FlatBvh& bvh, const Camera& camera, int width, int height, int threads)
{
    RaySet set;
    const dev::GcCamera cam = make_camera(camera, width, height);
    const auto w = static_cast<std::uint32_t>(width);
    const auto h = static_cast<std::uint32_t>(height);
    set.primary.resize(std::size_t{w} * h);
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x) set.primary[std::size_t{y} * w + x] = dev::gc_camera_ray(cam, w, h, x, y, 0.5f, 0.5f);

    std::vector<dev::GcHit> hits(set.primary.size());
    parallel_for(hits.size(), threads, 1024, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const dev::GcRay& r = set.primary[i];
            Ray ray;
            ray.origin = Point3(r.org_tmin.x, r.org_tmin.y, r.org_tmin.z);
            ray.direction = Vec3(r.dir_tmax.x, r.dir_tmax.y, r.dir_tmax.z);
            ray.tmin = r.org_tmin.w;
            ray.tmax = r.dir_tmax.w;
            hits[i] = trace_closest(bvh, ray);
        }
    });

    const Bounds3 bounds = scene.bounds();
    const Vec3 extent = bounds.diagonal();
    const float size = std::max({extent.x, extent.y, extent.z});
    const float offset = 1e-4f * size; // lifts secondary origins off the surface they start on
    const std::vector<dev::GcEmitter> emitters = make_emitters(scene);

    for (std::size_t i = 0; i < hits.size(); ++i) {
        const dev::GcHit& hit = hits[i];
        if (hit.prim == GC_INVALID) continue;
        const dev::GcRay& r = set.primary[i];
        const glm::vec3 o = to_glm(r.org_tmin);
        const glm::vec3 d = to_glm(r.dir_tmax);
        const glm::vec3 v0 = scene.vertex(hit.prim, 0).glm();
        const glm::vec3 v1 = scene.vertex(hit.prim, 1).glm();
        const glm::vec3 v2 = scene.vertex(hit.prim, 2).glm();
        glm::vec3 n = glm::cross(v1 - v0, v2 - v0);
        const float len = glm::length(n);
        if (!(len > 0.0f)) continue;
        n /= len;
        if (glm::dot(n, d) > 0.0f) n = -n;
        const glm::vec3 p = o + hit.t * d + offset * n;

        glm::vec3 t;
        glm::vec3 b;
        basis(n, t, b);
        const dev::float3 l = dev::gc_sample_cosine_hemisphere(random01(i, 0), random01(i, 1));
        const glm::vec3 dir = glm::normalize(l.x * t + l.y * b + l.z * n);
        set.diffuse.push_back(dev::gc_make_ray(p, dir, 0.0f, GC_RAY_UNBOUNDED));

        glm::vec3 target;
        const float u0 = random01(i, 2);
        const float u1 = random01(i, 3);
        if (!emitters.empty()) {
            const auto e = std::min(emitters.size() - 1, static_cast<std::size_t>(random01(i, 4) * float(emitters.size())));
            const dev::float3 bary = dev::gc_sample_uniform_triangle(u0, u1);
            target = bary.x * to_glm(emitters[e].v0) + bary.y * to_glm(emitters[e].v1) + bary.z * to_glm(emitters[e].v2);
        } else {
            const glm::vec3 c = bounds.centroid().glm();
            target = glm::vec3(c.x + (u0 - 0.5f) * 0.5f * extent.x, bounds.hi.y + 0.5f * size,
                               c.z + (u1 - 0.5f) * 0.5f * extent.z);
        }
        // Unnormalised direction: t = 1 is the light point; stop just short of it.
        set.shadow.push_back(dev::gc_make_ray(p, target - p, 0.0f, 0.999f));
    }
    return set;
}

TraversalCost traversal_cost(const FlatBvh& bvh, const std::vector<dev::GcRay>& rays, bool any_hit,
                             std::size_t sample)
{
    // The same ordered traversal as gc_trace_impl (kernels/shared/gc_traverse.h), counting.
    TraversalCost cost;
    const std::size_t n = std::min(sample, rays.size());
    if (n == 0) return cost;
    std::uint64_t inner = 0;
    std::uint64_t leaves = 0;
    std::uint64_t tests = 0;
    for (std::size_t k = 0; k < n; ++k) {
        // Spread over the whole set: a primary set's first rays are the image's top rows,
        // which on the dragon and the 5.2M scene are all background (0 nodes visited).
        const dev::GcRay& ray = rays[k * rays.size() / n];
        if (!dev::gc_ray_is_valid(ray)) continue;
        float t_best = ray.dir_tmax.w;
        std::uint32_t best_prim = GC_INVALID;
        std::uint32_t stack_node[GC_BVH_STACK_SIZE];
        float stack_entry[GC_BVH_STACK_SIZE];
        std::uint32_t sp = 0;
        dev::GcBvhNode node = bvh.nodes[0];
        const dev::GcRayPre r = dev::gc_ray_with_margin(dev::gc_ray_precompute(ray), GC_XYZ(node.lo), GC_XYZ(node.hi));
        if (!(dev::gc_intersect_aabb_pre(r, t_best, GC_XYZ(node.lo), GC_XYZ(node.hi)) < GC_AABB_MISS)) continue;
        bool done = false;
        for (;;) {
            if (dev::gc_node_is_leaf(node)) {
                ++leaves;
                const std::uint32_t first = dev::gc_node_first(node);
                const std::uint32_t end = first + dev::gc_node_count(node);
                for (std::uint32_t i = first; i < end && !done; ++i) {
                    ++tests;
                    const dev::GcTriangle& tri = bvh.triangles[i];
                    const dev::GcHit h = dev::gc_intersect_triangle(r, GC_XYZ(tri.v0), GC_XYZ(tri.v1), GC_XYZ(tri.v2), t_best);
                    const std::uint32_t prim = dev::gc_triangle_prim(tri);
                    if (h.prim == GC_INVALID || prim == GC_INVALID) continue;
                    if (h.t < t_best || prim < best_prim) {
                        t_best = h.t;
                        best_prim = prim;
                        if (any_hit) done = true;
                    }
                }
                if (done) break;
            } else {
                ++inner;
                const std::uint32_t first = dev::gc_node_first(node);
                const dev::GcBvhNode& c0 = bvh.nodes[first];
                const dev::GcBvhNode& c1 = bvh.nodes[first + 1];
                const float e0 = dev::gc_intersect_aabb_pre(r, t_best, GC_XYZ(c0.lo), GC_XYZ(c0.hi));
                const float e1 = dev::gc_intersect_aabb_pre(r, t_best, GC_XYZ(c1.lo), GC_XYZ(c1.hi));
                const bool hit0 = e0 < GC_AABB_MISS;
                const bool hit1 = e1 < GC_AABB_MISS;
                if (hit0 && hit1) {
                    const bool swap = e1 < e0;
                    node = swap ? c1 : c0;
                    if (sp < GC_BVH_STACK_SIZE) {
                        stack_node[sp] = swap ? first : first + 1;
                        stack_entry[sp] = swap ? e0 : e1;
                        ++sp;
                    }
                    continue;
                }
                if (hit0 || hit1) {
                    node = hit0 ? c0 : c1;
                    continue;
                }
            }
            bool found = false;
            while (sp > 0 && !found) {
                --sp;
                found = dev::gc_aabb_entry_within(stack_entry[sp], t_best);
            }
            if (!found) break;
            node = bvh.nodes[stack_node[sp]];
        }
    }
    cost.inner_visits = double(inner) / double(n);
    cost.leaf_visits = double(leaves) / double(n);
    cost.triangle_tests = double(tests) / double(n);
    return cost;
}

}  // namespace gc::bench
