// glTF metallic-roughness materials (GC_MAT_PBR: GGX, textures, normal maps) against Mitsuba 3's
// `principled` BSDF (tests/data/refs/*-pbr.exr, made with tools/reference/make_reference.py
// --pbr; the command is in each NAME.json).
//
// The two BSDFs are not the same model, so this is not a within-noise test like
// reference_test.cpp: principled's diffuse lobe is Disney's (retro-reflection that grows with
// roughness, not weighted by 1 - F) and its dielectric Fresnel is exact rather than Schlick's.
// The check is the acceptance figure, relative MSE mean((t - r)^2 / (r^2 + 1e-2)):
//
//   rel MSE <= tolerance + 2 * P,   P = (1/spp + 1/spp_ref) * mean(var / (r^2 + 1e-2))
//
// P is the noise an unbiased render at the test's spp adds (from our measured per-sample
// variance), so the bound equals the acceptance tolerance at high spp and scales it to the
// modest spp used here. Measured at 1024 spp (128x128, PoCL): avocado (its textures reduced to
// 256x256) 1.03e-3, textured box 4.59e-3 (tolerances below). Tolerance 5e-3 is the acceptance;
// the textured box gets 8e-3, widened for one documented convention difference: it is a
// roughness-1 dielectric, where Disney's diffuse is ~11% brighter than glTF's Lambert (1 - F)
// (on the box's pixels: geocold-cl / Mitsuba-principled = 0.896, geocold-cl / Mitsuba-diffuse
// (the Lambert reference box-textured.exr) = 1.00 +- 0.01).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "host/image/compare.h"
#include "host/image/image_io.h"
#include "host/scene/load.h"
#include "tests/cl/cl_test_util.h"
#include "tests/validation/validation_util.h"

namespace gc {
namespace {

namespace fs = std::filesystem;

struct PbrCase {
    const char* name;
    std::uint32_t spp;
    double tolerance; // rel MSE at high spp (see the header comment)
};

void PrintTo(const PbrCase& c, std::ostream* os) { *os << c.name; }

Point3 json_point(const nlohmann::json& j) { return {j.at(0).get<float>(), j.at(1).get<float>(), j.at(2).get<float>()}; }

class PbrReferenceTest : public cl::test::DeviceTest, public ::testing::WithParamInterface<PbrCase> {};

TEST_P(PbrReferenceTest, MatchesMitsubaPrincipled)
{
    GC_SKIP_WITHOUT_EXR_READER();
    const PbrCase c = GetParam();
    const fs::path json_path = fs::path(GC_TEST_SOURCE_DIR) / "tests/data/refs" / (std::string(c.name) + ".json");
    std::ifstream in(json_path);
    ASSERT_TRUE(in) << json_path;
    const nlohmann::json j = nlohmann::json::parse(in);
    const fs::path scene_path = json_path.parent_path() / j.at("scene").get<std::string>();
    ASSERT_TRUE(fs::exists(scene_path)) << scene_path;

    Camera camera;
    const nlohmann::json& cam = j.at("camera");
    camera.look_from = json_point(cam.at("look_from"));
    camera.look_at = json_point(cam.at("look_at"));
    const Point3 up = json_point(cam.at("up"));
    camera.up = Vec3(up.x, up.y, up.z);
    camera.vfov_degrees = cam.at("fov").get<float>();
    RenderSettings settings;
    settings.width = cam.at("res").at(0).get<int>();
    settings.height = cam.at("res").at(1).get<int>();
    settings.max_depth = j.at("max_depth").get<std::uint32_t>();
    if (!j.at("env").is_null()) settings.env_radiance = json_point(j.at("env")).glm();
    settings.integrator = IntegratorKind::Path;
    settings.seed = 1;
    settings.spp = c.spp;
    const std::uint32_t ref_spp = j.at("spp").get<std::uint32_t>();
    const Film ref = read_image(json_path.parent_path() / j.at("image").get<std::string>());

    const Scene scene = load_scene(scene_path);
    const validation::Rendered got = validation::render(*context, scene, camera, settings);
    ASSERT_EQ(got.mean.width(), ref.width());
    ASSERT_EQ(got.mean.height(), ref.height());

    const ImageDifference d = compare_images(got.mean, ref);
    double predicted = 0.0;
    double sum_t[3] = {0, 0, 0};
    double sum_r[3] = {0, 0, 0};
    for (std::uint32_t y = 0; y < ref.height(); ++y)
        for (std::uint32_t x = 0; x < ref.width(); ++x)
            for (int k = 0; k < 3; ++k) {
                const double r = ref.pixel(x, y)[k];
                predicted += (1.0 / c.spp + 1.0 / ref_spp) * got.variance.pixel(x, y)[k] / (r * r + 1e-2);
                sum_t[k] += got.mean.pixel(x, y)[k];
                sum_r[k] += r;
            }
    predicted /= 3.0 * ref.width() * ref.height();
    const double bound = c.tolerance + 2.0 * predicted;
    std::printf("%s: %ux%u, %u spp (ref %u spp, Mitsuba principled), %.1f s on %s\n", c.name, got.mean.width(),
                got.mean.height(), c.spp, ref_spp, got.seconds, context->device().device_name.c_str());
    std::printf("  rel MSE %.3e, bound %.3e (= tolerance %.1e + 2 x noise %.3e); image mean ratio R G B %.4f %.4f "
                "%.4f; nonfinite %zu\n",
                d.rel_mse, bound, c.tolerance, predicted, sum_t[0] / sum_r[0], sum_t[1] / sum_r[1], sum_t[2] / sum_r[2],
                d.nonfinite);
    EXPECT_EQ(d.nonfinite, 0u);
    EXPECT_LE(d.rel_mse, bound);
    if (HasFailure()) {
        const ImageMetadata meta{context->device().device_name, "path", scene_path.string(), c.spp, got.seconds, 1};
        write_image(validation::failure_path(std::string(c.name) + "-test.exr"), got.mean, meta);
        write_image(validation::failure_path(std::string(c.name) + "-heat.exr"), difference_heatmap(got.mean, ref), meta);
    }
}

// ~1-2 M samples each: a few seconds on PoCL with 2 cores.
INSTANTIATE_TEST_SUITE_P(Refs, PbrReferenceTest,
                         ::testing::Values(PbrCase{"avocado-pbr", 128, 5e-3}, PbrCase{"box-textured-pbr", 64, 8e-3}),
                         [](const ::testing::TestParamInfo<PbrCase>& param_info) {
                             std::string name = param_info.param.name;
                             for (char& ch : name)
                                 if (ch == '-') ch = '_';
                             return name;
                         });

}  // namespace
}  // namespace gc
