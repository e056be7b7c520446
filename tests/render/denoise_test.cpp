// Denoising (host/image/denoise.h with host/render/denoise_guides.h) on the Cornell box: the
// denoised low-spp render is closer to a high-spp reference than the noisy input. Skips when
// there is no OpenCL device or Open Image Denoise is not installed (tools/install-deps.sh);
// the missing-library error is tested without either.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "host/image/compare.h"
#include "host/image/denoise.h"
#include "host/render/denoise_guides.h"
#include "host/render/session.h"
#include "host/util/error.h"
#include "tests/cl/cl_test_util.h"
#include "tests/render/cornell_request.h"

namespace gc {
namespace {

namespace fs = std::filesystem;

TEST(Denoise, AMissingLibraryIsADeviceErrorThatSaysHowToInstallIt)
{
    DenoiseOptions options;
    options.library = "/nonexistent/libOpenImageDenoise.so.2";
    EXPECT_FALSE(denoiser_available(options));
    try {
        denoise(Film(4, 4), nullptr, nullptr, options);
        ADD_FAILURE() << "no DeviceError";
    } catch (const DeviceError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("/nonexistent/libOpenImageDenoise.so.2"), std::string::npos) << what;
        EXPECT_NE(what.find("tools/install-deps.sh"), std::string::npos) << what;
    }
}

TEST(Denoise, GuidesMustMatchTheImage)
{
    const Film color(4, 4), small(2, 2);
    EXPECT_THROW(denoise(color, &small, nullptr), UsageError);
    EXPECT_THROW(denoise(color, nullptr, &color), UsageError);  // normal needs albedo
}

class DenoiseRender : public cl::test::DeviceTest {
protected:
    void SetUp() override
    {
        std::string why;
        if (!denoiser_available({}, &why)) GTEST_SKIP() << why;
        cl::test::DeviceTest::SetUp();
        if (IsSkipped()) return;
        const PreparedScene prepared = prepare_scene(test::cornell_request("CornellBox-Original.obj"));
        scene = std::make_shared<DeviceScene>(DeviceScene::upload(*context, prepared.scene, prepared.bvh));
        camera = prepared.camera;
    }

    std::unique_ptr<Renderer> path(std::uint32_t spp) const
    {
        RenderSettings s;
        s.width = 64;
        s.height = 64;
        s.spp = spp;
        s.max_depth = 6;
        auto r = std::make_unique<Renderer>(*context, scene, camera, s);
        r->render(0, spp);
        return r;
    }

    std::shared_ptr<DeviceScene> scene;
    Camera camera;
};

TEST_F(DenoiseRender, TheDenoisedImageIsCloserToTheReferenceThanTheNoisyOne)
{
    const Film reference = path(2048)->film();
    const auto noisy = path(16);
    const Film raw_256 = path(256)->film();
    const DenoiseGuides guides = render_denoise_guides(*noisy);
    const Film denoised = denoise(noisy->film(), &guides.albedo, &guides.normal);
    const Film colour_only = denoise(noisy->film(), nullptr, nullptr);

    const double e_noisy = compare_images(noisy->film(), reference).rel_mse;
    const double e_256 = compare_images(raw_256, reference).rel_mse;
    const double e_denoised = compare_images(denoised, reference).rel_mse;
    const double e_colour_only = compare_images(colour_only, reference).rel_mse;
    std::printf("rel MSE against 2048 spp, 64x64: 16 spp %.5f, 256 spp %.5f, 16 spp denoised %.5f "
                "(colour only %.5f)\n", e_noisy, e_256, e_denoised, e_colour_only);
    EXPECT_LT(e_denoised, 0.5 * e_noisy);
    EXPECT_LT(e_colour_only, e_noisy);
    // The alpha channel is the colour's.
    EXPECT_EQ(denoised.at(3, 3).a, 1.0f);
}

}  // namespace
}  // namespace gc

namespace gc {
namespace {

// The guides look through the Cornell sphere scene's mirror and glass balls: where the plain
// albedo AOV shows the mirror ball's near-black Kd, the guide shows the room it reflects.
class GuideRender : public cl::test::DeviceTest {};

TEST_F(GuideRender, GuidesSeeThroughMirrorsAndGlass)
{
    if (IsSkipped()) return;
    const PreparedScene prepared = prepare_scene(test::cornell_request("CornellBox-Sphere.obj"));
    auto scene = std::make_shared<DeviceScene>(DeviceScene::upload(*context, prepared.scene, prepared.bvh));
    auto aov = [&](AovKind kind) {
        RenderSettings s;
        s.width = 48;
        s.height = 48;
        s.integrator = IntegratorKind::Aov;
        s.aov = kind;
        Renderer r(*context, scene, prepared.camera, s);
        r.render(0, 4);
        return r.film();
    };
    const Film plain = aov(AovKind::Albedo), guide = aov(AovKind::GuideAlbedo);
    const Film normal = aov(AovKind::Normal), guide_normal = aov(AovKind::GuideNormal);
    int dark_plain = 0, seen_through = 0, same = 0, normals_differ = 0;
    for (std::uint32_t y = 0; y < plain.height(); ++y)
        for (std::uint32_t x = 0; x < plain.width(); ++x) {
            const Rgba p = plain.at(x, y), g = guide.at(x, y);
            if (p.r < 0.02f && p.g < 0.02f && p.b < 0.02f && p.r > 0.0f) {
                ++dark_plain;
                if (g.r + g.g + g.b > 0.1f) ++seen_through;
            } else if (p == g) {
                ++same;
            }
            const Rgba n = normal.at(x, y), gn = guide_normal.at(x, y);
            if (std::fabs(n.r - gn.r) + std::fabs(n.g - gn.g) + std::fabs(n.b - gn.b) > 0.5f) ++normals_differ;
        }
    std::printf("spheres' pixels %d, of which the guide sees through %d; unchanged elsewhere %d of %d; normals "
                "that differ %d\n", dark_plain, seen_through, same, int(plain.pixel_count()) - dark_plain, normals_differ);
    EXPECT_GT(dark_plain, 50);
    EXPECT_GT(seen_through, dark_plain * 6 / 10);  // the mirror also shows the open front: nothing
    EXPECT_GT(normals_differ, dark_plain / 2);
    // Elsewhere (diffuse walls) the guide is the plain albedo, bit for bit.
    EXPECT_GT(same, (int(plain.pixel_count()) - dark_plain) * 8 / 10);
}

}  // namespace
}  // namespace gc
