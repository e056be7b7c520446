// Denoising (host/image/denoise.h with host/render/denoise_guides.h) on the Cornell box: the
// denoised low-spp render is closer to a high-spp reference than the noisy input. Skips when
// there is no OpenCL device or Open Image Denoise is not installed (tools/install-deps.sh);
// the missing-library error is tested without either.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <memory>

#include "host/image/compare.h"
#include "host/image/denoise.h"
#include "host/render/denoise_guides.h"
#include "host/render/session.h"
#include "host/util/error.h"
#include "tests/cl/cl_test_util.h"

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
        SceneRequest request;
        request.path = fs::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Original.obj";
        request.camera.look_from = Point3(0, 1, 3.9f);
        request.camera.look_at = Point3(0, 1, 0);
        request.camera.fov = 39.3077f;
        const PreparedScene prepared = prepare_scene(request);
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
