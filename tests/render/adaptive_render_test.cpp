// Adaptive frames (host/render/adaptive.h) on OpenCL devices, on the Cornell box with the mirror
// and glass spheres, whose caustic under the glass sphere is far noisier than the walls:
//   - the same bits run to run, and on two devices of one kind (POCL_DEVICES="pthread pthread"
//     gives two; else the same device twice) as on one;
//   - every pixel has the bits of a uniform frame of its own sample count, in both forms of the
//     path integrator: a tile that never stops is the uniform render's, bit for bit;
//   - at equal total samples, a lower relative MSE against the Mitsuba reference
//     (tests/data/refs/cornell-sphere.exr) than a uniform frame.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>

#include "host/image/compare.h"
#include "host/image/image_io.h"
#include "host/render/adaptive.h"
#include "host/render/multi_device.h"
#include "host/util/error.h"
#include "tests/cl/cl_test_util.h"
#include "tests/render/cornell_request.h"

namespace gc {
namespace {

constexpr std::uint32_t k_chunk = 16;

// Two PoCL CPU devices unless the caller chose otherwise: PoCL reads this at the process's
// first OpenCL call, which comes after static initialisation.
const bool k_two_pocl_devices = ::setenv("POCL_DEVICES", "pthread pthread", /*overwrite=*/0) == 0;

RenderSettings small_frame()
{
    RenderSettings s;
    s.width = 40;
    s.height = 32;
    s.spp = 64;
    s.max_depth = 8;
    s.samples_per_pass = 5;  // passes cut across chunk ends
    s.noise_threshold = 0.2;
    return s;
}

bool same_bits(const FilmSums& a, const FilmSums& b)
{
    return a.width == b.width && a.height == b.height && a.sums.size() == b.sums.size() &&
           a.squares.size() == b.squares.size() && a.sample_counts == b.sample_counts &&
           std::memcmp(a.sums.data(), b.sums.data(), a.sums.size() * sizeof(glm::vec4)) == 0 &&
           std::memcmp(a.squares.data(), b.squares.data(), a.squares.size() * sizeof(glm::vec4)) == 0;
}

// Pixels by sample count, printed: where the work went.
std::map<std::uint32_t, std::size_t> count_histogram(const FilmSums& frame)
{
    std::map<std::uint32_t, std::size_t> pixels;
    for (std::uint32_t n : frame.sample_counts) ++pixels[n];
    std::printf("  pixels by sample count:");
    for (const auto& [n, count] : pixels) std::printf(" %u spp: %zu;", n, count);
    std::printf(" mean %.2f spp\n", double(total_samples(frame)) / double(frame.sample_counts.size()));
    return pixels;
}

class AdaptiveRenderTest : public cl::test::DeviceTest {
protected:
    void SetUp() override
    {
        cl::test::DeviceTest::SetUp();
        if (IsSkipped()) return;
        prepared = prepare_scene(test::cornell_request("CornellBox-Sphere.obj"));
        const cl::DeviceInfo& first = context->device();
        for (const cl::DeviceInfo& d : devices)
            if (d.device_name == first.device_name && d.platform_name == first.platform_name) same_kind.push_back(d);
        if (same_kind.size() < 2) same_kind = {first, first};
    }

    FilmSums adaptive(const std::vector<cl::DeviceInfo>& on, const RenderSettings& settings,
                      const RenderSetup& setup = {})
    {
        const FrameResult r =
            render_frame(on, prepared, settings, setup, ChunkPlan::for_range(0, settings.spp, k_chunk), {},
                         adaptive_rounds(settings.noise_threshold, settings.spp, k_chunk));
        EXPECT_FALSE(r.outcome.cancelled || r.outcome.timed_out);
        return r.sums;
    }

    FilmSums uniform(RenderSettings settings, std::uint32_t spp, const RenderSetup& setup = {})
    {
        settings.noise_threshold = 0.0;
        settings.spp = spp;
        return render_frame({context->device()}, prepared, settings, setup, ChunkPlan::for_range(0, spp, k_chunk), {})
            .sums;
    }

    PreparedScene prepared;
    std::vector<cl::DeviceInfo> same_kind;
};

TEST_F(AdaptiveRenderTest, SameBitsRunToRunAndOnTwoDevices)
{
    const RenderSettings settings = small_frame();
    const FilmSums first = adaptive({context->device()}, settings);
    const auto histogram = count_histogram(first);
    // Not a uniform frame in disguise: some tiles stopped early and some went to the cap.
    EXPECT_GT(histogram.size(), 1u);
    EXPECT_TRUE(histogram.count(settings.spp)) << "no tile reached the cap";
    EXPECT_TRUE(same_bits(adaptive({context->device()}, settings), first)) << "run to run";
    EXPECT_TRUE(same_bits(adaptive(same_kind, settings), first)) << "two devices against one";
    std::printf("  devices: %s and %s (%s)\n", same_kind[0].device_name.c_str(), same_kind[1].device_name.c_str(),
                same_kind[0].id == same_kind[1].id ? "one device, two contexts" : "two devices");
}

TEST_F(AdaptiveRenderTest, EveryPixelHasTheUniformBitsOfItsSampleCount)
{
    const RenderSettings settings = small_frame();
    for (PathKernelForm form : {PathKernelForm::Megakernel, PathKernelForm::Wavefront}) {
        RenderSetup setup;
        setup.tuning.path_kernel = form;
        const FilmSums frame = adaptive({context->device()}, settings, setup);
        const auto histogram = count_histogram(frame);
        ASSERT_GT(histogram.size(), 1u);
        std::size_t compared = 0;
        std::size_t differ = 0;
        for (const auto& [count, pixels] : histogram) {
            // Stops only at a check point, or at the cap.
            const std::vector<std::uint32_t> points = adaptive_check_points(settings.spp, k_chunk);
            EXPECT_TRUE(count == settings.spp || std::count(points.begin(), points.end(), count)) << count;
            const FilmSums reference = uniform(settings, count, setup);
            for (std::size_t i = 0; i < frame.sums.size(); ++i) {
                if (frame.sample_counts[i] != count) continue;
                ++compared;
                if (std::memcmp(&frame.sums[i], &reference.sums[i], sizeof(glm::vec4)) != 0) ++differ;
            }
        }
        std::printf("  %s: %zu pixels compared with uniform frames of their sample counts, %zu differ\n",
                    form == PathKernelForm::Megakernel ? "megakernel" : "wavefront", compared, differ);
        EXPECT_EQ(compared, frame.sums.size());
        EXPECT_EQ(differ, 0u);
    }
}

// Renderer::select_pixels takes strictly ascending pixels of the image, for the path integrator
// (the others' kernels render every pixel), and counts samples only where it rendered them.
TEST_F(AdaptiveRenderTest, SelectedPixelsAreCheckedAndCounted)
{
    RenderSettings settings = small_frame();
    Renderer renderer(*context, prepared.scene, prepared.bvh, prepared.camera, settings);
    const std::uint32_t image = std::uint32_t(settings.width * settings.height);
    EXPECT_THROW(renderer.select_pixels({3, 3}), UsageError);
    EXPECT_THROW(renderer.select_pixels({5, 2}), UsageError);
    EXPECT_THROW(renderer.select_pixels({image}), UsageError);
    renderer.select_pixels({0, 7, image - 1});
    renderer.render(0, 4);
    const FilmSums sums = renderer.sums();
    for (std::uint32_t i = 0; i < image; ++i) {
        const bool listed = i == 0 || i == 7 || i == image - 1;
        EXPECT_EQ(sums.sample_counts[i], listed ? 4u : 0u) << i;
        EXPECT_EQ(sums.sums[i].w, listed ? 4.0f : 0.0f) << i;  // the kernels' own count
    }
    settings.integrator = IntegratorKind::Whitted;
    Renderer whitted(*context, prepared.scene, prepared.bvh, prepared.camera, settings);
    EXPECT_THROW(whitted.select_pixels({0}), UsageError);
}

// The rounds themselves (multi_device.h): a pick of no pixel ends the frame at its check point;
// a pick that throws stops every device and reaches the caller instead of leaving them waiting.
TEST_F(AdaptiveRenderTest, RoundsEndEarlyOrFailCleanly)
{
    RenderSettings settings = small_frame();
    const ChunkPlan plan = ChunkPlan::for_range(0, settings.spp, k_chunk);
    FrameRounds none_left;
    none_left.check_points = {16, 32};
    none_left.pixels_after = [](const FilmSums&, std::uint32_t) { return std::vector<std::uint32_t>{}; };
    const FrameResult ended = render_frame(same_kind, prepared, settings, {}, plan, {}, none_left);
    EXPECT_EQ(ended.end_sample, 16u);
    EXPECT_EQ(ended.sums.sample_counts, std::vector<std::uint32_t>(ended.sums.sums.size(), 16u));

    FrameRounds failing;
    failing.check_points = {16, 32};
    failing.pixels_after = [](const FilmSums&, std::uint32_t) -> std::vector<std::uint32_t> {
        throw InputError("no pick today");
    };
    EXPECT_THROW(render_frame(same_kind, prepared, settings, {}, plan, {}, failing), InputError);

    FrameRounds misplaced;
    misplaced.check_points = {24};  // not a chunk boundary
    misplaced.pixels_after = none_left.pixels_after;
    EXPECT_THROW(render_frame({context->device()}, prepared, settings, {}, plan, {}, misplaced), UsageError);
}

// The metric: relative MSE against the Mitsuba reference (compare_images: mean over RGB of
// (test - ref)^2 / (ref^2 + 1e-2)), of an adaptive frame and of a uniform frame with the same
// total samples (its spp the adaptive frame's mean, rounded to the nearest).
TEST_F(AdaptiveRenderTest, LowerErrorThanUniformAtEqualSamples)
{
#if !defined(GC_HAVE_OIIO)
    GTEST_SKIP() << "the reference is an EXR file and this build has no OpenImageIO";
#endif
    const Film reference = read_image(std::filesystem::path(GC_TEST_SOURCE_DIR) / "tests/data/refs/cornell-sphere.exr");
    RenderSettings settings;
    settings.width = int(reference.width());
    settings.height = int(reference.height());
    settings.max_depth = 8;  // the reference's
    settings.spp = 256;
    settings.noise_threshold = 0.1;
    const FilmSums adaptive_frame = adaptive({context->device()}, settings);
    count_histogram(adaptive_frame);
    const double pixels = double(adaptive_frame.sample_counts.size());
    const double mean_spp = double(total_samples(adaptive_frame)) / pixels;
    const std::uint32_t uniform_spp = std::uint32_t(std::lround(mean_spp));
    const FilmSums uniform_frame = uniform(settings, uniform_spp);

    const double adaptive_error = compare_images(mean_film(adaptive_frame), reference).rel_mse;
    const double uniform_error = compare_images(mean_film(uniform_frame), reference).rel_mse;
    std::printf("  rel MSE against Mitsuba: adaptive %.6f (threshold %.2f, mean %.2f spp, cap %u), "
                "uniform %.6f (%u spp); ratio %.3f\n",
                adaptive_error, settings.noise_threshold, mean_spp, settings.spp, uniform_error, uniform_spp,
                adaptive_error / uniform_error);
    EXPECT_LT(mean_spp, 0.8 * settings.spp) << "too few tiles stopped for the comparison to mean much";
    EXPECT_LT(adaptive_error, uniform_error);
}

}  // namespace
}  // namespace gc
