// The unlit-scene warning: given exactly when nothing can light the render.
#include <gtest/gtest.h>

#include "host/app/lighting_check.h"

namespace gc {
namespace {

// One grey triangle, nothing emissive, no lights.
Scene unlit_triangle()
{
    Scene s;
    s.positions = {Point3(0, 0, 0), Point3(1, 0, 0), Point3(0, 1, 0)};
    s.normals = {Normal3(0, 0, 1), Normal3(0, 0, 1), Normal3(0, 0, 1)};
    s.material_ids = {0};
    s.has_vertex_normals = {0};
    s.materials.resize(1);
    s.source_path = "triangle.obj";
    return s;
}

TEST(LightingCheck, UnlitSceneUnderBlackEnvironmentIsWarnedAbout)
{
    const auto warning = unlit_scene_warning(unlit_triangle(), RenderSettings{});
    ASSERT_TRUE(warning.has_value());
    std::printf("  warning: %s\n", warning->c_str());
    EXPECT_NE(warning->find("triangle.obj"), std::string::npos);
    EXPECT_NE(warning->find("--env"), std::string::npos);

    RenderSettings whitted;
    whitted.integrator = IntegratorKind::Whitted;
    EXPECT_TRUE(unlit_scene_warning(unlit_triangle(), whitted).has_value());
}

TEST(LightingCheck, AnyLightSourceSilencesIt)
{
    Scene emissive = unlit_triangle();
    emissive.materials[0].emission = glm::vec3(0.0f, 0.0f, 2.0f);
    EXPECT_FALSE(unlit_scene_warning(emissive, RenderSettings{}).has_value());

    Scene point_lit = unlit_triangle();
    point_lit.point_lights.push_back(PointLight{Point3(0, 0, 1), glm::vec3(1.0f)});
    EXPECT_FALSE(unlit_scene_warning(point_lit, RenderSettings{}).has_value());

    RenderSettings env;
    env.env_radiance = glm::vec3(0.0f, 0.1f, 0.0f);
    EXPECT_FALSE(unlit_scene_warning(unlit_triangle(), env).has_value());

    RenderSettings aov;
    aov.integrator = IntegratorKind::Aov;
    EXPECT_FALSE(unlit_scene_warning(unlit_triangle(), aov).has_value());
}

TEST(LightingCheck, EnvironmentMapScaledToZeroLightsNothing)
{
    RenderSettings map;
    map.env_map_path = "sky.exr";
    map.env_radiance = glm::vec3(0.0f);
    EXPECT_TRUE(unlit_scene_warning(unlit_triangle(), map).has_value());
    map.env_radiance = glm::vec3(1.0f);
    EXPECT_FALSE(unlit_scene_warning(unlit_triangle(), map).has_value());
}

}  // namespace
}  // namespace gc
