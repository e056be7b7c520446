// The hashes a merge compares (host/render/frame_hash.h): everything that changes an image
// must change one of them, so partials of different scenes or options are never added.
#include <gtest/gtest.h>

#include "host/render/frame_hash.h"

namespace gc {
namespace {

Scene one_triangle()
{
    Scene scene;
    for (const Point3& p : {Point3(0, 0, 0), Point3(1, 0, 0), Point3(0, 1, 0)}) {
        scene.positions.push_back(p);
        scene.normals.push_back(Normal3(0, 0, 1));
    }
    scene.material_ids.push_back(0);
    scene.has_vertex_normals.push_back(0);
    scene.materials.emplace_back();
    return scene;
}

TEST(FrameHash, SameSceneSameHash)
{
    EXPECT_EQ(scene_content_hash(one_triangle()), scene_content_hash(one_triangle()));
}

// An instanced scene hashes its meshes and its instances: a moved or added instance, or
// another mesh drawn, is another scene.
TEST(FrameHash, EveryInstanceChangesTheInstancedSceneHash)
{
    InstancedScene s;
    s.meshes = one_triangle();
    s.mesh_ranges.push_back({0, 1});
    s.instances.push_back({0, glm::mat4(1.0f)});
    s.instances.push_back({0, glm::mat4(2.0f)});
    s.instances[1].object_to_world[3][3] = 1.0f;
    const std::uint64_t plain = scene_content_hash(s);
    EXPECT_EQ(plain, scene_content_hash(InstancedScene(s)));
    EXPECT_NE(plain, scene_content_hash(s.meshes));
    InstancedScene moved = s;
    moved.instances[1].object_to_world[3][0] = 0.5f;
    InstancedScene added = s;
    added.instances.push_back(s.instances[0]);
    InstancedScene recoloured = s;
    recoloured.meshes.materials[0].albedo = glm::vec3(0.1f);
    for (const InstancedScene* other : {&moved, &added, &recoloured}) EXPECT_NE(plain, scene_content_hash(*other));
}

TEST(FrameHash, EveryUvTransformSlotChangesTheSceneHash)
{
    const std::uint64_t plain = scene_content_hash(one_triangle());
    for (UvTransform Material::*slot : {&Material::albedo_uv, &Material::metallic_roughness_uv, &Material::normal_uv,
                                        &Material::emission_uv}) {
        Scene scene = one_triangle();
        (scene.materials[0].*slot).rotation = 0.5f;
        EXPECT_NE(scene_content_hash(scene), plain);
    }
}

TEST(FrameHash, TheLensChangesTheOptionsHash)
{
    const RenderSettings settings;
    Camera camera;
    const std::uint64_t pinhole = render_options_hash(settings, camera, 64);
    EXPECT_EQ(render_options_hash(settings, camera, 64), pinhole);
    camera.aperture_radius = 0.05f;
    const std::uint64_t lens = render_options_hash(settings, camera, 64);
    EXPECT_NE(lens, pinhole);
    camera.focus_distance = 3.0f;
    EXPECT_NE(render_options_hash(settings, camera, 64), lens);
    EXPECT_NE(render_options_hash(settings, Camera{}, 32), pinhole);  // the chunk size too
}

// Partials of one frame must not mix samplers: the Sobol sampler changes the hash, and the
// independent one leaves the hash partials written before samplers existed had.
TEST(FrameHash, TheSamplerChangesTheOptionsHash)
{
    RenderSettings settings;
    settings.sampler = SamplerKind::Independent;
    const Camera camera;
    const std::uint64_t independent = render_options_hash(settings, camera, 64);
    settings.sampler = SamplerKind::Sobol;
    EXPECT_NE(render_options_hash(settings, camera, 64), independent);
}

}  // namespace
}  // namespace gc
