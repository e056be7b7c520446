// KHR_materials_* layers rendered on the device. transmissionTexture: R times
// transmissionFactor (gc_material_eval.h); on the rough absorbing glass cube of
// tests/data/scenes/rough-glass-volume, a texture of ones keeps the untextured image's bits,
// and a texture that turns transmission down over part of the cube changes those pixels.
// Sheen (whose lobe the host tests check, tests/bsdf/pbr_layers_test.cpp): the sheened
// spheres' program builds and runs, brightens them at grazing angles and stays finite.
// clearcoatNormalTexture on Khronos' ClearCoatTest: the coat normal maps change the coated
// spheres, and nothing but the coat (with the coat factor at 0 the maps change no bit).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

#include "host/bvh/bvh.h"
#include "host/render/renderer.h"
#include "host/scene/load.h"
#include "tests/cl/cl_test_util.h"

namespace gc {
namespace {

std::uint32_t red(std::uint32_t r) { return r | 0xff000000u; }

class MaterialLayersRenderTest : public cl::test::DeviceTest {
protected:
    void SetUp() override
    {
        cl::test::DeviceTest::SetUp();
        if (IsSkipped()) return;
        scene = load_scene(std::filesystem::path(GC_TEST_SOURCE_DIR) /
                           "tests/data/scenes/rough-glass-volume/RoughGlassVolume.gltf");
        for (std::size_t i = 0; i < scene.materials.size(); ++i)
            if (scene.materials[i].transmission > 0.0f) glass = static_cast<int>(i);
        ASSERT_GE(glass, 0);
    }

    // The image with the glass's transmission textured by 2 x 2 texels of these R values
    // (none: untextured).
    std::vector<glm::vec4> render(const std::vector<std::uint32_t>& r_values)
    {
        Scene s = scene;
        if (!r_values.empty()) {
            Texture t;
            t.name = "transmission";
            t.width = t.height = 2;
            t.srgb = false;
            t.nearest = true;
            for (std::uint32_t r : r_values) t.texels.push_back(red(r));
            s.textures.push_back(t);
            s.materials[static_cast<std::size_t>(glass)].layers.transmission_texture.texture =
                static_cast<int>(s.textures.size() - 1);
        }
        RenderSettings settings;
        settings.width = 40;
        settings.height = 32;
        settings.max_depth = 8;
        settings.env_radiance = glm::vec3(1.0f);
        Camera camera;
        camera.look_from = Point3(0.0f, 1.2f, 3.0f);
        camera.look_at = Point3(0.0f, 0.4f, 0.0f);
        camera.vfov_degrees = 40.0f;
        Renderer renderer(*context, s, build_bvh(s), camera, settings);
        renderer.render(0, 8);
        return renderer.sums(false).sums;
    }

    Scene scene;
    int glass = -1;
};

TEST_F(MaterialLayersRenderTest, OnesKeepTheBitsAndZerosChangeThePixels)
{
    const std::vector<glm::vec4> plain = render({});
    const std::vector<glm::vec4> ones = render({255, 255, 255, 255});
    EXPECT_EQ(0, std::memcmp(plain.data(), ones.data(), plain.size() * sizeof(glm::vec4)))
        << "R = 255 is 1.0: the factor times one is the factor";
    const std::vector<glm::vec4> half = render({0, 255, 0, 255});
    std::size_t changed = 0;
    for (std::size_t i = 0; i < plain.size(); ++i) changed += plain[i] != half[i] ? 1 : 0;
    std::printf("pixels changed by a texture of zeros on half the cube: %zu of %zu\n", changed, plain.size());
    EXPECT_GT(changed, plain.size() / 20);
}

// The image of `s` from +z, back by 1.2 times its extent, under a white sky.
std::vector<glm::vec4> framed_image(const cl::Context& context, const Scene& s, std::uint32_t spp)
{
    RenderSettings settings;
    settings.width = 48;
    settings.height = 48;
    settings.env_radiance = glm::vec3(1.0f);
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const Point3& p : s.positions) {
        lo = glm::min(lo, glm::vec3(p.x, p.y, p.z));
        hi = glm::max(hi, glm::vec3(p.x, p.y, p.z));
    }
    Camera camera;
    camera.look_at = Point3(0.5f * (lo + hi));
    camera.look_from = Point3(0.5f * (lo + hi) + glm::vec3(0.0f, 0.0f, 1.2f * glm::length(hi - lo)));
    camera.vfov_degrees = 40.0f;
    Renderer renderer(context, s, build_bvh(s), camera, settings);
    renderer.render(0, spp);
    return renderer.sums(false).sums;
}

TEST_F(MaterialLayersRenderTest, CoatNormalMapsChangeTheCoatAlone)
{
    const Scene loaded = load_scene(std::filesystem::path(GC_TEST_SOURCE_DIR) /
                                    "tests/data/scenes/ClearCoatTest/ClearCoatTest.gltf");
    auto without_coat_normals = [](Scene s) {
        for (Material& m : s.materials) m.layers.clearcoat_normal_texture = TextureRef{};
        return s;
    };
    auto without_coat = [](Scene s) {
        for (Material& m : s.materials)
            if (m.layers.clearcoat_normal_texture.texture >= 0) m.layers.clearcoat = 0.0f;
        return s;
    };
    int mapped = 0;
    for (const Material& m : loaded.materials) mapped += m.layers.clearcoat_normal_texture.texture >= 0 ? 1 : 0;
    ASSERT_EQ(mapped, 2);
    const std::vector<glm::vec4> with = framed_image(*context, loaded, 8);
    const std::vector<glm::vec4> without = framed_image(*context, without_coat_normals(loaded), 8);
    std::size_t changed = 0, non_finite = 0;
    for (std::size_t i = 0; i < with.size(); ++i) {
        changed += with[i] != without[i] ? 1 : 0;
        non_finite += std::isfinite(with[i].x + with[i].y + with[i].z) ? 0 : 1;
    }
    const std::vector<glm::vec4> uncoated = framed_image(*context, without_coat(loaded), 8);
    const std::vector<glm::vec4> uncoated_unmapped = framed_image(*context, without_coat_normals(without_coat(loaded)), 8);
    const bool same = std::memcmp(uncoated.data(), uncoated_unmapped.data(), uncoated.size() * sizeof(glm::vec4)) == 0;
    std::printf("coat normal maps on %d materials change %zu of %zu pixels (%zu non-finite); with those coats at 0 "
                "the maps change %s\n",
                mapped, changed, with.size(), non_finite, same ? "no bit" : "BITS");
    EXPECT_GT(changed, with.size() / 50);
    EXPECT_EQ(non_finite, 0u);
    EXPECT_TRUE(same);
}

// A white sheen on every PBR sphere of tests/data/scenes/material-layers under a white sky:
// the sheened program builds and runs, the spheres' pixels change and nothing is non-finite.
// A red sheen scales the layers beneath as the white one does (by max(colour) E), so the two
// differ only through the sheen lobe itself: a pixel's green must differ somewhere.
TEST_F(MaterialLayersRenderTest, SheenRendersOnTheDevice)
{
    const Scene plain = load_scene(std::filesystem::path(GC_TEST_SOURCE_DIR) /
                                   "tests/data/scenes/material-layers/MaterialLayers.gltf");
    Scene sheened = plain;
    int layered = 0;
    for (Material& m : sheened.materials)
        if (m.type == MaterialType::Pbr) {
            m.layers.sheen_on = true;
            m.layers.sheen_color = glm::vec3(1.0f);
            m.layers.sheen_roughness = 0.4f;
            ++layered;
        }
    ASSERT_GT(layered, 0);
    const auto image = [&](const Scene& s) { return framed_image(*context, s, 16); };
    const std::vector<glm::vec4> without = image(plain);
    const std::vector<glm::vec4> with = image(sheened);
    Scene red = sheened;
    for (Material& m : red.materials)
        if (m.layers.sheen_on) m.layers.sheen_color = glm::vec3(1.0f, 0.0f, 0.0f);
    const std::vector<glm::vec4> with_red = image(red);
    std::size_t greener = 0;
    for (std::size_t i = 0; i < with.size(); ++i) greener += with[i].y > with_red[i].y ? 1 : 0;
    std::size_t changed = 0, non_finite = 0;
    for (std::size_t i = 0; i < with.size(); ++i) {
        changed += with[i] != without[i] ? 1 : 0;
        non_finite += std::isfinite(with[i].x + with[i].y + with[i].z) ? 0 : 1;
    }
    std::printf("a white sheen on %d materials changed %zu of %zu pixels; %zu non-finite\n", layered, changed,
                with.size(), non_finite);
    EXPECT_GT(changed, with.size() / 20);
    EXPECT_EQ(non_finite, 0u);
    std::printf("the white sheen's green exceeds the red sheen's in %zu pixels\n", greener);
    EXPECT_GT(greener, with.size() / 20);
}

}  // namespace
}  // namespace gc
