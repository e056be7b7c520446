// glTF alphaMode MASK in traversal (kernels/shared/gc_alpha.h): a quad whose base-colour
// texture is alpha 0 on its left half and alpha 1 on its right half lets closest-hit and
// shadow (any-hit) rays through the left half only, in the host reference (BVH and brute
// force) and in the path tracer's own extend.cl / shadow.cl kernels on every OpenCL device;
// and end to end, a light behind a fully cut-away quad lights the floor exactly as it does
// with the quad removed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "host/bvh/bvh.h"
#include "host/bvh/traverse_host.h"
#include "host/cl/buffer.h"
#include "host/cl/kernel.h"
#include "host/cl/program.h"
#include "host/math/to_device.h"
#include "host/render/device_bvh.h"
#include "host/render/scene_convert.h"
#include "tests/cl/cl_test_util.h"
#include "tests/render/alpha_scenes.h"
#include "tests/validation/validation_util.h"

namespace gc {
namespace {

using test::add_quad;
using test::half_cut_quad;

// Rays straight down -z through a grid over the quad, away from the x = 0 seam. t_max = 1.5
// ends them between the quad (t = 1) and the backstop (t = 2), as a shadow ray would.
std::vector<Ray> grid_rays(float t_max)
{
    std::vector<Ray> rays;
    for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j) {
            const float x = -0.95f + 1.9f * static_cast<float>(i) / 15.0f;
            const float y = -0.95f + 1.9f * static_cast<float>(j) / 15.0f;
            if (std::fabs(x) < 0.05f) continue;
            Ray r;
            r.origin = Point3(x, y, 1.0f);
            r.direction = Vec3(0, 0, -1);
            r.tmin = 0.0f;
            r.tmax = t_max;
            rays.push_back(r);
        }
    return rays;
}

struct DeviceAlpha {
    BigArray<dev::GcTriangleAttribs> attribs;
    std::vector<dev::GcMaterial> materials;
    DeviceTextures textures;
    AlphaBuffers view() const { return {attribs.data(), materials.data(), textures.textures.data(), textures.texels.data()}; }
};

DeviceAlpha device_alpha(const Scene& s)
{
    return {make_triangle_attribs(s), make_materials(s), make_textures(s)};
}

bool through_cut_out(const Ray& r) { return r.origin.x < 0.0f; }

TEST(AlphaMask, HostReferenceSkipsCutOut)
{
    const Scene scene = half_cut_quad();
    const FlatBvh bvh = build_bvh(scene);
    const WideBvh wide = widen(bvh);
    const DeviceAlpha alpha = device_alpha(scene);
    std::size_t through = 0, blocked = 0;
    for (const Ray& r : grid_rays(GC_FLOAT_MAX)) {
        const dev::GcHit bvh_hit = trace_closest(bvh, r, alpha.view());
        const dev::GcHit brute = trace_brute_force(scene, r, alpha.view());
        const dev::GcHit wide_hit = trace_closest(wide, r, alpha.view());
        ASSERT_EQ(wide_hit.prim, bvh_hit.prim);
        ASSERT_EQ(wide_hit.t, bvh_hit.t);
        ASSERT_EQ(wide_hit.u, bvh_hit.u);
        ASSERT_EQ(wide_hit.v, bvh_hit.v);
        ASSERT_EQ(bvh_hit.prim, brute.prim);
        ASSERT_EQ(bvh_hit.t, brute.t);
        ASSERT_EQ(bvh_hit.u, brute.u);
        ASSERT_EQ(bvh_hit.v, brute.v);
        if (through_cut_out(r)) {
            ++through;
            EXPECT_GE(bvh_hit.prim, 2u) << "x = " << r.origin.x << ": should reach the backstop";
            EXPECT_EQ(bvh_hit.t, 2.0f);
        } else {
            ++blocked;
            EXPECT_LT(bvh_hit.prim, 2u) << "x = " << r.origin.x << ": should stop on the opaque half";
            EXPECT_EQ(bvh_hit.t, 1.0f);
        }
        // Without the hook (trace.cl's traversal) the whole quad is opaque.
        EXPECT_LT(trace_closest(bvh, r).prim, 2u);
    }
    for (const Ray& r : grid_rays(1.5f)) {
        EXPECT_EQ(trace_any(bvh, r, alpha.view()), !through_cut_out(r)) << r.origin.x;
        EXPECT_EQ(trace_any(wide, r, alpha.view()), !through_cut_out(r)) << "BVH4, x = " << r.origin.x;
    }
    std::printf("[alpha] host: %zu rays through the cut-out, %zu on the opaque half; BVH2 == BVH4 == brute force\n", through,
                blocked);
    EXPECT_GT(through, 50u);
    EXPECT_GT(blocked, 50u);
}

class AlphaMaskDevice : public cl::test::DeviceTest {};

// extend.cl (closest hit) and shadow.cl (any hit) themselves, against the host reference,
// over both BVH layouts.
void expect_kernels_skip_cut_out(const cl::Context& ctx, BvhLayout layout)
{
    const Scene scene = half_cut_quad();
    const FlatBvh bvh = build_bvh(scene);
    const DeviceAlpha alpha = device_alpha(scene);
    const std::vector<Ray> rays = grid_rays(GC_FLOAT_MAX);
    const std::vector<Ray> shadow_rays = grid_rays(1.5f);
    const auto n = static_cast<std::uint32_t>(rays.size());

    dev::GcRenderParams params{};
    params.pixel_count = n;
    params.samples_in_pass = 1;
    std::vector<dev::GcRay> device_rays;
    std::vector<dev::GcShadowRay> device_shadows;
    std::vector<std::uint32_t> queue;
    for (std::uint32_t i = 0; i < n; ++i) {
        device_rays.push_back(to_device(rays[i]));
        dev::GcShadowRay s{};
        s.ray = to_device(shadow_rays[i]);
        s.contribution = dev::float4(1.0f, 1.0f, 1.0f, 0.0f);
        s.slot = i;
        device_shadows.push_back(s);
        queue.push_back(i);
    }
    std::vector<std::uint32_t> counters(GC_COUNTER_COUNT, 0u);
    counters[GC_COUNTER_RAYS_A] = n;
    counters[GC_COUNTER_SHADOW] = n;
    std::vector<dev::GcPathState> paths(n, dev::GcPathState{});

    auto make = [&](const auto& data, const char* name) {
        using T = typename std::decay_t<decltype(data)>::value_type;
        auto buf = cl::Buffer<T>::create(ctx, data.size(), CL_MEM_READ_WRITE, name);
        buf.write(std::span<const T>(data));
        return buf;
    };
    const DeviceBvh device_bvh = DeviceBvh::upload(ctx, bvh, layout);
    const cl_mem nodes = device_bvh.nodes();
    const cl_mem tris = device_bvh.triangles();
    auto attribs = make(alpha.attribs, "attribs");
    auto materials = make(alpha.materials, "materials");
    auto textures = make(alpha.textures.textures, "textures");
    auto texels = make(alpha.textures.texels, "texels");
    auto ray_buf = make(device_rays, "rays");
    auto shadow_buf = make(device_shadows, "shadow rays");
    auto queue_buf = make(queue, "queue");
    auto counter_buf = make(counters, "counters");
    auto path_buf = make(paths, "paths");
    auto hit_buf = cl::Buffer<dev::GcHit>::create(ctx, n, CL_MEM_READ_WRITE, "hits");

    const cl::Program extend_program(ctx, "extend.cl", program_options(layout));
    cl::Kernel extend = extend_program.kernel("extend");
    extend.set_args(params, nodes, tris, attribs, materials, textures, texels, ray_buf, hit_buf, queue_buf, counter_buf,
                    GC_COUNTER_RAYS_A);
    extend.launch(ctx, n);
    const cl::Program shadow_program(ctx, "shadow.cl", program_options(layout));
    cl::Kernel shadow = shadow_program.kernel("shadow");
    shadow.set_args(params, nodes, tris, attribs, materials, textures, texels, shadow_buf, path_buf, counter_buf);
    shadow.launch(ctx, n);
    ctx.finish();
    std::vector<dev::GcHit> hits(n);
    hit_buf.read(std::span<dev::GcHit>(hits));
    path_buf.read(std::span<dev::GcPathState>(paths));

    std::size_t closest_mismatches = 0, any_mismatches = 0, through = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const dev::GcHit expected = trace_brute_force(scene, rays[i], alpha.view());
        if (hits[i].prim != expected.prim || hits[i].t != expected.t || hits[i].u != expected.u ||
            hits[i].v != expected.v)
            ++closest_mismatches;
        const bool unoccluded = paths[i].radiance.x == 1.0f;
        if (unoccluded != !trace_any(bvh, shadow_rays[i], alpha.view())) ++any_mismatches;
        if (unoccluded != through_cut_out(shadow_rays[i])) ++any_mismatches;
        if (through_cut_out(rays[i])) {
            ++through;
            EXPECT_GE(hits[i].prim, 2u);
        }
    }
    std::printf("[alpha] %s, %s: %u rays (%zu through the cut-out), closest-hit mismatches %zu, any-hit mismatches %zu\n",
                ctx.device().device_name.c_str(), layout_name(layout), n, through, closest_mismatches, any_mismatches);
    EXPECT_EQ(closest_mismatches, 0u) << layout_name(layout);
    EXPECT_EQ(any_mismatches, 0u) << layout_name(layout);
}

TEST_F(AlphaMaskDevice, ExtendAndShadowKernelsSkipCutOut)
{
    for (const BvhLayout layout : {BvhLayout::Binary, BvhLayout::Wide, BvhLayout::Wide8}) expect_kernels_skip_cut_out(*context, layout);
}

// Floor (y = 0, Lambert 0.5) lit by a small downward-facing emitter at y = 1; a MASK quad at
// y = 0.5 between them whose factor alpha 0 is below its cutoff everywhere.
Scene lit_floor(bool cut_out_quad, bool quad_opaque)
{
    Scene s;
    Material floor;
    floor.albedo = glm::vec3(0.5f);
    Material light;
    light.albedo = glm::vec3(0.0f);
    light.emission = glm::vec3(10.0f);
    Material quad;
    quad.albedo = glm::vec3(0.2f, 0.3f, 0.9f); // unlike the floor, so an AOV shows which one is seen
    quad.alpha_mode = AlphaMode::Mask;
    quad.alpha_cutoff = 0.5f;
    quad.opacity = quad_opaque ? 1.0f : 0.0f;
    s.materials = {floor, light, quad};
    add_quad(s, Point3(-2, 0, 2), Point3(2, 0, 2), Point3(2, 0, -2), Point3(-2, 0, -2), 0);
    add_quad(s, Point3(-0.1f, 1, -0.1f), Point3(0.1f, 1, -0.1f), Point3(0.1f, 1, 0.1f), Point3(-0.1f, 1, 0.1f), 1);
    // Last, so the other triangles keep their indices (and the path tracer its decisions).
    if (cut_out_quad) add_quad(s, Point3(-2, 0.5f, 2), Point3(2, 0.5f, 2), Point3(2, 0.5f, -2), Point3(-2, 0.5f, -2), 2);
    return s;
}

// Irradiance at the origin from the square emitter above: midpoint rule over the light of
// Le cos(theta) cos(theta') / r^2 = Le h^2 / r^4 for a parallel emitter at height h.
double analytic_irradiance(double le, double half, double h)
{
    const int n = 400;
    double e = 0.0;
    const double da = (2.0 * half / n) * (2.0 * half / n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double x = -half + (i + 0.5) * 2.0 * half / n, z = -half + (j + 0.5) * 2.0 * half / n;
            const double r2 = x * x + z * z + h * h;
            e += le * h * h / (r2 * r2) * da;
        }
    return e;
}

struct FloorStats {
    double mean = 0.0, sigma = 0.0;
    Film film;
};

FloorStats render_floor(const cl::Context& ctx, const Scene& scene)
{
    Camera camera;
    camera.look_from = Point3(0, 0.3f, 0); // below the quad: camera rays never meet it
    camera.look_at = Point3(0, 0, 0);
    camera.up = Vec3(0, 0, -1);
    camera.vfov_degrees = 4.0f;
    RenderSettings s;
    s.integrator = IntegratorKind::Path;
    s.width = 16;
    s.height = 16;
    s.spp = 64;
    s.seed = 5;
    s.max_depth = 2; // direct light only: camera -> floor -> light
    const validation::Rendered r = validation::render(ctx, scene, camera, s);
    FloorStats out;
    double var = 0.0;
    const int count = s.width * s.height;
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
            out.mean += r.mean.at(x, y).r / count;
            var += r.variance.at(x, y).r / s.spp / count;
        }
    out.sigma = std::sqrt(var / count);
    out.film = r.mean;
    return out;
}

TEST_F(AlphaMaskDevice, LightBehindCutOutLightsFloor)
{
    const FloorStats open = render_floor(*context, lit_floor(false, false));
    const FloorStats cut = render_floor(*context, lit_floor(true, false));
    const FloorStats closed = render_floor(*context, lit_floor(true, true));
    const double expected = 0.5 / std::numbers::pi * analytic_irradiance(10.0, 0.1, 1.0);
    std::printf("[alpha] floor radiance: no quad %.5f, cut-away MASK quad %.5f, opaque quad %.5f, analytic %.5f "
                "(+- %.5f)\n",
                open.mean, cut.mean, closed.mean, expected, open.sigma);
    // The cut-away quad is never hit, so every path makes the same decisions: same bits.
    std::size_t differing = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            if (open.film.at(x, y) != cut.film.at(x, y)) ++differing;
    EXPECT_EQ(differing, 0u) << "pixels that differ with the cut-away quad present";
    EXPECT_NEAR(cut.mean, expected, 0.03 * expected + 5.0 * cut.sigma);
    EXPECT_LT(closed.mean, 0.01 * expected) << "an opaque quad must shadow the floor";
}

// The AOV and Whitted integrators trace through the same alpha hook (aov.cl, whitted.cl): a
// camera above the cut-away quad sees the lit floor exactly as without the quad, and an opaque
// quad hides it.
TEST_F(AlphaMaskDevice, AovAndWhittedSeeThroughCutOut)
{
    Camera camera;
    camera.look_from = Point3(0, 3, 0);
    camera.look_at = Point3(0, 0, 0);
    camera.up = Vec3(0, 0, -1);
    camera.vfov_degrees = 20.0f;
    RenderSettings s;
    s.width = 16;
    s.height = 16;
    s.spp = 2;
    s.seed = 3;
    for (const IntegratorKind kind : {IntegratorKind::Aov, IntegratorKind::Whitted}) {
        s.integrator = kind;
        s.aov = AovKind::Albedo;
        const Film open = validation::render(*context, lit_floor(false, false), camera, s).mean;
        const Film cut = validation::render(*context, lit_floor(true, false), camera, s).mean;
        const Film closed = validation::render(*context, lit_floor(true, true), camera, s).mean;
        std::size_t cut_differs = 0, closed_differs = 0;
        for (int y = 0; y < s.height; ++y)
            for (int x = 0; x < s.width; ++x) {
                cut_differs += open.at(x, y) != cut.at(x, y);
                closed_differs += open.at(x, y) != closed.at(x, y);
            }
        std::printf("[alpha] %s: pixels differing from no quad: cut-away quad %zu, opaque quad %zu of %d\n",
                    integrator_name(kind), cut_differs, closed_differs, s.width * s.height);
        EXPECT_EQ(cut_differs, 0u) << integrator_name(kind);
        EXPECT_GT(closed_differs, 0u) << integrator_name(kind) << ": the opaque quad must show";
    }
}

}  // namespace
}  // namespace gc
