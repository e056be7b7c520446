// The path and Whitted integrators on instanced scenes (megakernel.cl and whitted.cl with
// GC_SCENE_INSTANCED, gc_scene_trace.h, gc_instance_attribs.h, DeviceScene::upload_instanced),
// on each OpenCL device:
//  - a glTF whose nodes reuse a floor, a cube (moved, turned 30 degrees, mirrored) and an area
//    light (moved, mirrored) renders as the same file loaded flat (load_gltf). Metric: relative
//    MSE of the instanced image against the flat one, printed, next to the flat image's own
//    noise (relative MSE of two flat renders with different seeds); the instanced one must be
//    under a fiftieth of that noise, so a light sampled on the wrong side, a normal or a tangent
//    in the wrong space, or a missing instance all fail it;
//  - two renders of the instanced scene give the same bits, and the wavefront form the
//    megakernel's;
//  - the AOVs (the denoiser's guides among them) trace the instances as well;
//  - the meshes' device bytes do not change with the number of instances.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "host/render/session.h"
#include "tests/cl/cl_test_util.h"
#include "tests/render/reused_meshes_gltf.h"

namespace gc {
namespace {

using test::write_reused_meshes_gltf;

SceneRequest request_for(const std::filesystem::path& path, bool keep_instances)
{
    SceneRequest r;
    r.path = path;
    r.keep_instances = keep_instances;
    // A placed camera: the framing of a turned cube's box differs from its triangles'.
    r.camera.look_from = Point3(0.5f, 3.2f, 6.5f);
    r.camera.look_at = Point3(0.0f, 0.6f, 0.0f);
    r.camera.fov = 45.0f;
    return r;
}

RenderSettings settings_with_seed(std::uint32_t seed, IntegratorKind integrator = IntegratorKind::Path)
{
    RenderSettings s;
    s.width = 64;
    s.height = 48;
    s.spp = 64;
    s.max_depth = 5;
    s.seed = seed;
    s.integrator = integrator;
    return s;
}

struct Rendered {
    std::vector<glm::vec4> sums;
    bool instanced = false;  // what the session uploaded
    std::uint32_t emitters = 0;
    float emitter_power = 0.0f;
};

Rendered render(const cl::DeviceInfo& device, const PreparedScene& prepared, std::uint32_t seed,
                IntegratorKind integrator = IntegratorKind::Path, PathKernelForm form = PathKernelForm::Auto)
{
    RenderSetup setup;
    setup.tuning.path_kernel = form;
    Session session(device, prepared, settings_with_seed(seed, integrator), setup);
    session.render();
    const DeviceScene& scene = session.device_scene();
    return {session.renderer().sums(false).sums, scene.instanced(), scene.emitter_count, scene.summary.emitter_power};
}

// Mean over pixels and channels of (a - b)^2 / (b^2 + 0.01), on the per-pixel means.
double rel_mse(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b)
{
    double sum = 0.0;
    for (std::size_t p = 0; p < a.size(); ++p)
        for (int c = 0; c < 3; ++c) {
            const double x = a[p][c] / a[p].w, y = b[p][c] / b[p].w;
            sum += (x - y) * (x - y) / (y * y + 0.01);
        }
    return sum / (3.0 * double(a.size()));
}

double mean_value(const std::vector<glm::vec4>& a)
{
    double sum = 0.0;
    for (const glm::vec4& v : a) sum += (v.x + v.y + v.z) / (3.0 * v.w);
    return sum / double(a.size());
}

class InstancedRender : public cl::test::DeviceTest {};

TEST_F(InstancedRender, ReusedGltfMeshesRenderAsTheFlatLoad)
{
    cl::test::TempDir dir;
    const std::filesystem::path file = write_reused_meshes_gltf(dir.path());
    const PreparedScene instanced = prepare_scene(request_for(file, true));
    const PreparedScene flat = prepare_scene(request_for(file, false));
    ASSERT_TRUE(instanced.instances);
    ASSERT_FALSE(flat.instances);
    EXPECT_EQ(instanced.instances->scene.mesh_ranges.size(), 3u);
    EXPECT_EQ(instanced.instances->scene.instances.size(), 6u);
    EXPECT_EQ(instanced.scene.triangle_count(), 2u + 12u + 2u);
    EXPECT_EQ(flat.scene.triangle_count(), 2u + 3u * 12u + 2u * 2u);
    for (const cl::DeviceInfo& device : devices)
        for (const IntegratorKind integrator : {IntegratorKind::Path, IntegratorKind::Whitted}) {
            const Rendered inst = render(device, instanced, 1, integrator);
            const Rendered inst_again = render(device, instanced, 1, integrator);
            const Rendered reference = render(device, flat, 1, integrator);
            const Rendered other_seed = render(device, flat, 2, integrator);
            const double error = rel_mse(inst.sums, reference.sums);
            const double noise = rel_mse(other_seed.sums, reference.sums);
            const bool same_bits =
                std::memcmp(inst.sums.data(), inst_again.sums.data(), inst.sums.size() * sizeof(glm::vec4)) == 0;
            std::printf("[instanced %s] %s: emitters %u (flat %u), power %.6g (flat %.6g); mean %.5f (flat %.5f); "
                        "rel MSE against the flat load %.3g, flat noise (seed 2 vs 1) %.3g, bound %.3g; run to run "
                        "%s\n",
                        integrator_name(integrator), device.device_name.c_str(), inst.emitters, reference.emitters,
                        double(inst.emitter_power), double(reference.emitter_power), mean_value(inst.sums),
                        mean_value(reference.sums), error, noise, 0.02 * noise, same_bits ? "same bits" : "DIFFER");
            EXPECT_TRUE(inst.instanced) << "the integrator did not keep the instances";
            EXPECT_FALSE(reference.instanced);
            EXPECT_EQ(inst.emitters, reference.emitters);
            EXPECT_NEAR(inst.emitter_power, reference.emitter_power, 1e-5 * reference.emitter_power);
            EXPECT_GT(mean_value(reference.sums), 0.02) << "the scene should be lit";
            EXPECT_GT(noise, 0.0);
            EXPECT_LT(error, 0.02 * noise) << device.device_name << ", " << integrator_name(integrator);
            EXPECT_TRUE(same_bits) << device.device_name;
        }
}

// The path integrator's two forms give the same bits on one device (tests/validation), an
// instanced scene included: the wavefront's queued hits carry their instance.
TEST_F(InstancedRender, WavefrontEqualsMegakernel)
{
    cl::test::TempDir dir;
    const PreparedScene instanced = prepare_scene(request_for(write_reused_meshes_gltf(dir.path()), true));
    for (const cl::DeviceInfo& device : devices) {
        const Rendered mega = render(device, instanced, 3, IntegratorKind::Path, PathKernelForm::Megakernel);
        const Rendered wave = render(device, instanced, 3, IntegratorKind::Path, PathKernelForm::Wavefront);
        std::size_t differ = 0;
        for (std::size_t i = 0; i < mega.sums.size(); ++i) differ += mega.sums[i] != wave.sums[i] ? 1 : 0;
        std::printf("[instanced wavefront] %s: %zu of %zu pixels differ from the megakernel's (mean %.5f)\n",
                    device.device_name.c_str(), differ, mega.sums.size(), mean_value(wave.sums));
        EXPECT_TRUE(wave.instanced);
        EXPECT_EQ(differ, 0u) << device.device_name;
        EXPECT_GT(mean_value(wave.sums), 0.02);
    }
}

// The AOVs, the denoiser's guides among them, trace the instances too: each equals the flat
// load's to 1e-5 (normals are renormalised after the instance's transform; depth, albedo and
// primitive ids of these transforms agree exactly but for edge pixels).
TEST_F(InstancedRender, AovsTraceTheInstances)
{
    cl::test::TempDir dir;
    const std::filesystem::path file = write_reused_meshes_gltf(dir.path());
    const PreparedScene instanced = prepare_scene(request_for(file, true));
    const PreparedScene flat = prepare_scene(request_for(file, false));
    for (const AovKind kind : {AovKind::Albedo, AovKind::Normal, AovKind::Depth, AovKind::GuideAlbedo,
                               AovKind::GuideNormal}) {
        RenderSettings aov = settings_with_seed(1, IntegratorKind::Aov);
        aov.aov = kind;
        aov.spp = 1;
        Session a(context->device(), instanced, aov);
        Session b(context->device(), flat, aov);
        EXPECT_TRUE(a.device_scene().instanced());
        a.render();
        b.render();
        const std::vector<glm::vec4> x = a.renderer().sums(false).sums, y = b.renderer().sums(false).sums;
        std::size_t off = 0, covered = 0;
        for (std::size_t i = 0; i < x.size(); ++i) {
            covered += y[i].x != 0.0f || y[i].y != 0.0f || y[i].z != 0.0f;
            for (int c = 0; c < 3; ++c) off += std::fabs(x[i][c] - y[i][c]) > 1e-5f * std::max(1.0f, std::fabs(y[i][c]));
        }
        std::printf("[instanced aov] %s: %zu of %zu pixels on geometry; %zu channel values differ from the flat "
                    "load's by more than 1e-5\n",
                    aov_name(kind), covered, x.size(), off);
        EXPECT_GT(covered, x.size() / 4);
        EXPECT_LE(off, x.size() / 100) << aov_name(kind);
    }
}

TEST_F(InstancedRender, MeshBytesDoNotGrowWithInstances)
{
    cl::test::TempDir dir;
    const PreparedScene base = prepare_scene(request_for(write_reused_meshes_gltf(dir.path()), true));
    std::uint64_t mesh_bytes[2] = {};
    std::uint64_t instance_bytes[2] = {};
    const std::size_t counts[2] = {64, 4096};
    for (int k = 0; k < 2; ++k) {
        InstancedScene many = base.instances->scene;
        many.instances.clear();
        for (std::size_t i = 0; i < counts[k]; ++i) {
            Instance inst;
            inst.mesh = 1;  // the cube: no emitters, so the shading data stays the meshes'
            inst.object_to_world[3] = glm::vec4(float(i % 64) * 2.0f, 0.0f, float(i / 64) * 2.0f, 1.0f);
            many.instances.push_back(inst);
        }
        const InstanceBvhParts parts = build_instance_bvh(many);
        const DeviceScene scene = DeviceScene::upload_instanced(*context, many, parts);
        instance_bytes[k] = scene.instance_level.tlas.bytes() + scene.instance_level.instances.bytes();
        mesh_bytes[k] = scene.bytes() - instance_bytes[k];
    }
    const double per_instance = double(instance_bytes[1] - instance_bytes[0]) / double(counts[1] - counts[0]);
    std::printf("[instanced bytes] %zu instances: meshes %llu B, instances %llu B; %zu instances: meshes %llu B, "
                "instances %llu B (%.1f B per added instance)\n",
                counts[0], (unsigned long long)mesh_bytes[0], (unsigned long long)instance_bytes[0], counts[1],
                (unsigned long long)mesh_bytes[1], (unsigned long long)instance_bytes[1], per_instance);
    EXPECT_EQ(mesh_bytes[0], mesh_bytes[1]);
    EXPECT_GT(per_instance, 64.0);
    EXPECT_LT(per_instance, 160.0);
}

}  // namespace
}  // namespace gc
