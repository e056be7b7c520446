// The same render twice on one device is bit-identical (the wavefront scheduler has no
// floating-point atomics and fixed reduction orders); a different seed is not, which shows
// the comparison can fail.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>

#include "host/scene/load.h"
#include "tests/cl/cl_test_util.h"
#include "tests/validation/validation_util.h"

namespace gc {
namespace {

bool bit_identical(const Film& a, const Film& b)
{
    return a.width() == b.width() && a.height() == b.height() &&
           std::memcmp(a.data().data(), b.data().data(), a.data().size() * sizeof(float)) == 0;
}

class DeterminismTest : public cl::test::DeviceTest {};

TEST_F(DeterminismTest, SameRenderTwiceIsBitIdentical)
{
    // The mirror box: diffuse, mirror, NEE and Russian roulette all on the paths.
    const Scene scene =
        load_scene(std::filesystem::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Mirror.obj");
    Camera camera;
    camera.look_from = Point3(0, 1, 3.9f);
    camera.look_at = Point3(0, 1, 0);
    camera.vfov_degrees = 39.3077f;
    RenderSettings s;
    s.integrator = IntegratorKind::Path;
    s.width = 48;
    s.height = 40;  // not a multiple of common work-group sizes
    s.spp = 6;
    s.seed = 11;
    s.wavefront_size = 1000;  // several passes per sample, a partial last one
    const validation::Rendered a = validation::render(*context, scene, camera, s);
    const validation::Rendered b = validation::render(*context, scene, camera, s);
    s.seed = 12;
    const validation::Rendered other = validation::render(*context, scene, camera, s);

    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.mean.data().size(); ++i)
        differing += std::memcmp(&a.mean.data()[i], &b.mean.data()[i], sizeof(float)) != 0;
    std::printf("same seed: %zu of %zu floats differ (mean and variance films %s); other seed: %s\n", differing,
                a.mean.data().size(), bit_identical(a.variance, b.variance) ? "identical" : "DIFFER",
                bit_identical(a.mean, other.mean) ? "identical (!)" : "differs");
    EXPECT_TRUE(bit_identical(a.mean, b.mean));
    EXPECT_TRUE(bit_identical(a.variance, b.variance));
    EXPECT_FALSE(bit_identical(a.mean, other.mean));
}

}  // namespace
}  // namespace gc
