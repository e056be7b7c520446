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

}  // namespace
}  // namespace gc
