// host/render/kernel_features: which features a scene's materials and lights switch on, the
// options that carry them to the kernels, and GEOCOLD_KERNEL_FEATURES. That the specialised
// programs render the same bits as the full ones is tests/validation/kernel_features_test.cpp.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <vector>

#include "host/render/kernel_features.h"
#include "host/util/error.h"

namespace gc {
namespace {

dev::GcMaterial material(std::uint32_t type)
{
    dev::GcMaterial m{};
    m.type = type;
    m.albedo_texture = m.metallic_roughness_texture = m.normal_texture = m.emission_texture = GC_INVALID;
    return m;
}

TEST(KernelFeatures, LambertOnlySceneTurnsEverythingElseOff)
{
    const std::vector<dev::GcMaterial> materials{material(GC_MAT_LAMBERT), material(GC_MAT_LAMBERT)};
    const KernelFeatures f = kernel_features(materials, 0, false);
    const std::string options = program_options(f);
    std::printf("Lambert only: '%s'\n", options.c_str());
    EXPECT_FALSE(f.textures || f.normal_maps || f.alpha_mask || f.alpha_blend || f.point_lights || f.env_map);
    EXPECT_EQ(f.material_types, 1u << GC_MAT_LAMBERT);
    EXPECT_EQ(options, "-D GC_USE_TEXTURES=0 -D GC_USE_NORMAL_MAPS=0 -D GC_USE_ALPHA_MASK=0 -D GC_USE_ALPHA_BLEND=0 "
                       "-D GC_USE_POINT_LIGHTS=0 -D GC_USE_ENV_MAP=0 -D GC_USE_CLEARCOAT=0 -D GC_USE_SPECULAR=0 "
                       "-D GC_USE_SHEEN=0 -D GC_USE_ROUGH_TRANSMISSION=0 -D GC_USE_VOLUME=0 -D GC_USE_MATERIALS=" +
                           std::to_string(1u << GC_MAT_LAMBERT) + "u");
}

TEST(KernelFeatures, EachFeatureIsSeen)
{
    std::vector<dev::GcMaterial> materials{material(GC_MAT_PBR), material(GC_MAT_DIELECTRIC), material(GC_MAT_MIRROR)};
    materials[0].emission_texture = 3;  // any texture slot counts
    const KernelFeatures textured = kernel_features(materials, 0, false);
    EXPECT_TRUE(textured.textures);
    EXPECT_FALSE(textured.normal_maps);
    EXPECT_EQ(textured.material_types, (1u << GC_MAT_PBR) | (1u << GC_MAT_DIELECTRIC) | (1u << GC_MAT_MIRROR));

    materials[1].normal_texture = 0;
    materials[2].flags = GC_MATF_ALPHA_MASK;
    materials[0].flags = GC_MATF_ALPHA_BLEND | GC_MATF_TWO_SIDED | GC_MATF_CLEARCOAT | GC_MATF_SPECULAR | GC_MATF_SHEEN |
                        GC_MATF_ROUGH_TRANSMISSION | GC_MATF_VOLUME;
    const KernelFeatures f = kernel_features(materials, 2, true);
    EXPECT_TRUE(f.textures && f.normal_maps && f.alpha_mask && f.alpha_blend && f.point_lights && f.env_map);
    EXPECT_TRUE(f.clearcoat && f.specular && f.sheen && f.rough_transmission && f.volume);
    // Only the material types are left to specialise.
    EXPECT_EQ(program_options(f), "-D GC_USE_MATERIALS=" + std::to_string(f.material_types) + "u");
}

TEST(KernelFeatures, LayerTexturesCountOnlyWithTheirLayer)
{
    // The kernels read a KHR_materials_* layer's textures only when its flag is set.
    std::vector<dev::GcMaterial> materials{material(GC_MAT_PBR)};
    materials[0].coat_texture = materials[0].sheen_color_texture = materials[0].specular_texture = 2;
    materials[0].coat_roughness_texture = materials[0].specular_color_texture = materials[0].sheen_roughness_texture = GC_INVALID;
    EXPECT_FALSE(kernel_features(materials, 0, false).textures);
    for (std::uint32_t flag : {GC_MATF_CLEARCOAT, GC_MATF_SPECULAR, GC_MATF_SHEEN}) {
        materials[0].flags = flag;
        const KernelFeatures f = kernel_features(materials, 0, false);
        EXPECT_TRUE(f.textures) << flag;
        EXPECT_EQ(f.clearcoat, flag == GC_MATF_CLEARCOAT);
        EXPECT_EQ(f.specular, flag == GC_MATF_SPECULAR);
        EXPECT_EQ(f.sheen, flag == GC_MATF_SHEEN);
    }
}

TEST(KernelFeatures, ATransmissionTextureCountsOnlyWithTransmission)
{
    std::vector<dev::GcMaterial> materials{material(GC_MAT_PBR)};
    materials[0].transmission_texture = 0;
    EXPECT_FALSE(kernel_features(materials, 0, false).textures) << "transmission 0: the texture is not read";
    materials[0].pbr.w = 0.5f;
    EXPECT_TRUE(kernel_features(materials, 0, false).textures);
}

TEST(KernelFeatures, AllBuildsTheFullProgram)
{
    const std::vector<dev::GcMaterial> materials{material(GC_MAT_LAMBERT)};
    const KernelFeatures all = kernel_features(materials, 0, false, KernelFeatureSet::All);
    const KernelFeatures scene = kernel_features(materials, 0, false, KernelFeatureSet::Scene);
    EXPECT_EQ(all, KernelFeatures{});
    EXPECT_EQ(program_options(all), "");
    EXPECT_NE(program_options(scene), "");
}

}  // namespace
}  // namespace gc
