// The same render twice on one device is bit-identical (the wavefront scheduler has no
// floating-point atomics and fixed reduction orders); a different seed is not, which shows
// the comparison can fail.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "gc_packet_lanes.h"
#include "host/render/device_bvh.h"
#include "host/render/megakernel_path.h"
#include "host/render/wavefront_path.h"
#include "host/scene/load.h"
#include "tests/cl/cl_test_util.h"
#include "tests/render/alpha_scenes.h"
#include "tests/validation/validation_util.h"

namespace gc {
namespace {

bool bit_identical(const Film& a, const Film& b)
{
    return a.width() == b.width() && a.height() == b.height() &&
           std::memcmp(a.data().data(), b.data().data(), a.data().size() * sizeof(float)) == 0;
}

Scene load_cornell(const char* file)
{
    return load_scene(std::filesystem::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box" / file);
}

class DeterminismTest : public cl::test::DeviceTest {};

TEST_F(DeterminismTest, SameRenderTwiceIsBitIdentical)
{
    // The mirror box: diffuse, mirror, NEE and Russian roulette all on the paths.
    const Scene scene = load_cornell("CornellBox-Mirror.obj");
    const Camera camera = validation::cornell_camera();
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

// The path integrator in `form`, the rest of the tuning left to the device.
RenderSetup path_kernel(PathKernelForm form)
{
    RenderSetup setup;
    setup.tuning.path_kernel = form;
    return setup;
}

// A 40x30 path render, small enough to run every grouping on every device.
RenderSettings small_path_render(std::uint32_t spp, std::uint32_t seed)
{
    RenderSettings s;
    s.integrator = IntegratorKind::Path;
    s.width = 40;
    s.height = 30;
    s.spp = spp;
    s.seed = seed;
    return s;
}

bool is_megakernel(const Renderer& renderer)
{
    return dynamic_cast<const MegakernelPathIntegrator*>(&renderer.integrator()) != nullptr;
}

// Renders spp samples through render_samples, in passes as the renderer plans them (or as
// its settings' samples_per_pass fixes them); returns the samples of each pass.
std::vector<std::uint32_t> render_in_passes(Renderer& renderer, std::uint32_t spp)
{
    std::vector<std::uint32_t> passes;
    while (renderer.samples_done() < spp) passes.push_back(renderer.render_samples(spp - renderer.samples_done()));
    return passes;
}

// " 3 3 3 2": the passes, for the tests' output.
std::string shown(const std::vector<std::uint32_t>& passes)
{
    std::string text;
    for (std::uint32_t p : passes) text += " " + std::to_string(p);
    return text;
}

// Renders s.spp samples through render_samples (grouped as the renderer plans them) and
// checks the films against one sample per pass; returns the samples of each pass.
std::vector<std::uint32_t> expect_grouping_keeps_bits(const cl::Context& context, const Scene& scene,
                                                      const Camera& camera, const RenderSettings& s,
                                                      const RenderSetup& setup)
{
    RenderSettings one_per_pass = s;
    one_per_pass.samples_per_pass = 1;
    const validation::Rendered single = validation::render(context, scene, camera, one_per_pass, setup);

    const FlatBvh bvh = build_bvh(scene);
    Renderer grouped(context, scene, bvh, camera, s, setup);
    const std::vector<std::uint32_t> passes = render_in_passes(grouped, s.spp);
    const bool mean_same = bit_identical(single.mean, grouped.film());
    const bool variance_same = bit_identical(single.variance, grouped.variance());
    std::printf("%s, %u pixels per launch: samples per pass:%s; mean films %s, variance films %s\n",
                is_megakernel(grouped) ? "megakernel" : "wavefront", grouped.batch_pixels(), shown(passes).c_str(),
                mean_same ? "identical" : "DIFFER", variance_same ? "identical" : "DIFFER");
    EXPECT_TRUE(mean_same);
    EXPECT_TRUE(variance_same);
    return passes;
}

TEST_F(DeterminismTest, SamplesGroupedPerPassGiveTheSameBits)
{
    // Several samples per pixel in one pass (Renderer::render_samples): accumulate.cl and the
    // megakernel add them in sample order, so the films must equal one-sample-per-pass
    // rendering bit for bit, whatever the grouping.
    const Scene scene = load_cornell("CornellBox-Sphere.obj");
    const Camera camera = validation::cornell_camera();
    RenderSettings s = small_path_render(11, 5);
    s.wavefront_size = 4000;  // the wavefront holds 3 samples of the 1200 pixels
    s.samples_per_pass = 3;   // and the megakernel is told 3: passes of 3, 3, 3, 2 either way
    for (const PathKernelForm form : {PathKernelForm::Wavefront, PathKernelForm::Megakernel}) {
        const std::vector<std::uint32_t> passes =
            expect_grouping_keeps_bits(*context, scene, camera, s, path_kernel(form));
        EXPECT_EQ(passes, (std::vector<std::uint32_t>{3, 3, 3, 2}))
            << (form == PathKernelForm::Megakernel ? "megakernel" : "wavefront");
    }
}

TEST_F(DeterminismTest, WavefrontLaunchesNarrowerThanTheirQueuesGiveTheSameBits)
{
    // After the first bounce, GPUs launch the wavefront's extend, shade and shadow kernels with
    // fewer work-items than the queues may hold, and each work-item loops over its queue in
    // steps of the launch's width (wavefront_launches.h). Forced here down to one per
    // compute unit (a work-group or a few: far below the 3 x 1200 paths of a pass on any
    // device), every path must still be traced and shaded exactly once: the films equal those
    // of one work-item per queue entry.
    const Scene scene = load_cornell("CornellBox-Sphere.obj");
    const Camera camera = validation::cornell_camera();
    RenderSettings s = small_path_render(6, 7);
    s.rr_depth = 2;
    s.wavefront_size = 4000;
    validation::Rendered rendered[2];
    const std::uint32_t items_per_unit[2] = {0, 1};
    for (int i = 0; i < 2; ++i) {
        RenderSetup setup = path_kernel(PathKernelForm::Wavefront);
        setup.tuning.wavefront_items_per_unit = items_per_unit[i];
        rendered[i] = validation::render(*context, scene, camera, s, setup);
    }
    const bool mean_same = bit_identical(rendered[0].mean, rendered[1].mean);
    const bool variance_same = bit_identical(rendered[0].variance, rendered[1].variance);
    std::printf("one work-item per entry against launches of %u (rounded up to whole work-groups) after the first "
                "bounce: mean films %s, variance films %s\n",
                wavefront_launch_size(3600, context->device().compute_units), mean_same ? "identical" : "DIFFER",
                variance_same ? "identical" : "DIFFER");
    EXPECT_TRUE(mean_same);
    EXPECT_TRUE(variance_same);
}

TEST_F(DeterminismTest, QueueLengthsCopiedOnTheDeviceEqualThoseReadBack)
{
    // The lengths that size the next batch's launches are copied aside on the device as a
    // batch runs (GPUs) and read after the pass; CPUs read each bounce's back as it ends. Both
    // must be the batch's true lengths, depth by depth: a copy from the wrong counter or into
    // the wrong slot would size every launch from another queue.
    const Scene scene = load_cornell("CornellBox-Sphere.obj");
    const Camera camera = validation::cornell_camera();
    RenderSettings s = small_path_render(1, 9);
    s.rr_depth = 2;  // queues that shrink from depth to depth
    s.max_depth = 6;
    std::vector<std::uint32_t> lengths[2];
    for (int i = 0; i < 2; ++i) {
        RenderSetup setup = path_kernel(PathKernelForm::Wavefront);
        setup.tuning.wavefront_sync_counts = i == 0;
        const FlatBvh bvh = build_bvh(scene);
        Renderer renderer(*context, scene, bvh, camera, s, setup);
        renderer.render_sample();
        const auto& wavefront = dynamic_cast<const WavefrontPathIntegrator&>(renderer.integrator());
        lengths[i].assign(wavefront.last_queue_lengths().begin(), wavefront.last_queue_lengths().end());
    }
    std::printf("rays queued for the next depth / shadow rays, depth by depth (read back | copied on the device):\n");
    for (std::size_t d = 0; d < lengths[0].size() / 2; ++d)
        std::printf("  depth %zu: %u / %u | %u / %u\n", d, lengths[0][2 * d], lengths[0][2 * d + 1], lengths[1][2 * d],
                    lengths[1][2 * d + 1]);
    ASSERT_EQ(lengths[0].size(), 2u * s.max_depth);
    EXPECT_EQ(lengths[0], lengths[1]);
    // Most camera rays hit the box and go on; Russian roulette ends some at each bounce.
    EXPECT_GT(lengths[0][0], 1200u / 4);
    EXPECT_GT(lengths[0][2], 0u);
    EXPECT_LT(lengths[0][2], lengths[0][0]);
}

TEST_F(DeterminismTest, MegakernelSamplesGroupedOverPixelBatchesGiveTheSameBits)
{
    // The CPU form with an image larger than one launch: each launch's work-items run their
    // pixels' 4 samples back to back, batch after batch. Left to the planner too (its passes
    // grow from 1 by at most doubling), the grouping must not change a bit.
    const RenderSetup megakernel = path_kernel(PathKernelForm::Megakernel);
    const Scene scene = load_cornell("CornellBox-Sphere.obj");
    const Camera camera = validation::cornell_camera();
    RenderSettings s = small_path_render(10, 3);
    s.wavefront_size = 500;  // launches of 500, 500 and 200 pixels
    s.samples_per_pass = 4;
    const std::vector<std::uint32_t> fixed = expect_grouping_keeps_bits(*context, scene, camera, s, megakernel);
    EXPECT_EQ(fixed, (std::vector<std::uint32_t>{4, 4, 2}));
    s.samples_per_pass = 0;
    const std::vector<std::uint32_t> planned = expect_grouping_keeps_bits(*context, scene, camera, s, megakernel);
    ASSERT_FALSE(planned.empty());
    EXPECT_EQ(planned.front(), 1u);
    for (std::size_t i = 1; i < planned.size(); ++i) EXPECT_LE(planned[i], 2 * planned[i - 1]);
}

TEST_F(DeterminismTest, MegakernelEqualsWavefront)
{
    // The two forms of the path integrator (wavefront.cl on GPUs, megakernel.cl on CPUs) make
    // the same calls per path with the same random numbers: same bits on one device. The glass
    // sphere box exercises refraction, Russian roulette and NEE.
    const Scene scene = load_cornell("CornellBox-Sphere.obj");
    const Camera camera = validation::cornell_camera();
    RenderSettings s = small_path_render(5, 9);
    s.rr_depth = 2;
    s.wavefront_size = 1000;  // several pixel batches per sample
    const validation::Rendered wavefront =
        validation::render(*context, scene, camera, s, path_kernel(PathKernelForm::Wavefront));
    const validation::Rendered megakernel =
        validation::render(*context, scene, camera, s, path_kernel(PathKernelForm::Megakernel));
    const bool mean_same = bit_identical(wavefront.mean, megakernel.mean);
    const bool variance_same = bit_identical(wavefront.variance, megakernel.variance);
    std::printf("wavefront %.3f s, megakernel %.3f s; mean films %s, variance films %s\n", wavefront.seconds,
                megakernel.seconds, mean_same ? "identical" : "DIFFER", variance_same ? "identical" : "DIFFER");
    EXPECT_TRUE(mean_same);
    EXPECT_TRUE(variance_same);
}

// The megakernel against the wavefront with `s`, on the context's device, each rendering
// its samples in passes of up to s.samples_per_pass (Renderer::render_samples), so that the
// megakernel's work-items trace several samples per pass.
// Returns the megakernel's pixels per work-item in its last pass.
std::uint32_t expect_megakernel_equals_wavefront(const cl::Context& context, const Scene& scene, const Camera& camera,
                                                 const RenderSettings& s)
{
    const FlatBvh bvh = build_bvh(scene);
    Film mean[2];
    Film variance[2];
    std::vector<std::uint32_t> megakernel_passes;
    std::uint32_t pixels_per_item = 0;
    const PathKernelForm forms[2] = {PathKernelForm::Wavefront, PathKernelForm::Megakernel};
    for (int i = 0; i < 2; ++i) {
        Renderer renderer(context, scene, bvh, camera, s, path_kernel(forms[i]));
        const std::vector<std::uint32_t> passes = render_in_passes(renderer, s.spp);
        if (is_megakernel(renderer)) {
            megakernel_passes = passes;
            pixels_per_item = renderer.pixels_per_item();
        }
        mean[i] = renderer.film();
        variance[i] = renderer.variance();
    }
    const bool mean_same = bit_identical(mean[0], mean[1]);
    const bool variance_same = bit_identical(variance[0], variance[1]);
    std::printf("%u spp, the megakernel's passes:%s, %u pixel(s) per work-item; mean films %s, variance films %s\n",
                s.spp, shown(megakernel_passes).c_str(), pixels_per_item, mean_same ? "identical" : "DIFFER",
                variance_same ? "identical" : "DIFFER");
    EXPECT_TRUE(mean_same);
    EXPECT_TRUE(variance_same);
    return pixels_per_item;
}

TEST_F(DeterminismTest, MegakernelCameraPacketsEqualWavefront)
{
    // On CPUs with the BVH8 the megakernel traces a pixel's camera rays as packets of six to
    // eight (gc_packet8.h): 29 samples, at most 16 per pass, are passes of 16 (packets of 8
    // and 8) and 13 (7 and 6, with idle lanes). The wavefront traces every camera ray alone.
    // Same bits.
    const Scene scene = load_cornell("CornellBox-Sphere.obj");
    RenderSettings s = small_path_render(29, 21);
    s.samples_per_pass = 16;
    expect_megakernel_equals_wavefront(*context, scene, validation::cornell_camera(), s);
}

TEST_F(DeterminismTest, MegakernelPacketsOfNeighbouringPixelsEqualWavefront)
{
    // Passes of one to four samples: on the BVH8 a work-item takes eight, four, two or two
    // neighbouring pixels (gc_packet_lanes.h) and traces their camera rays as one packet. The
    // image is 43 pixels wide (items straddle rows) and launches hold 100 pixels (the last item
    // of a launch has fewer pixels, and the last launch one pixel). Same bits as the wavefront.
    const Scene scene = load_cornell("CornellBox-Sphere.obj");
    RenderSettings s = small_path_render(0, 17);
    s.width = 43;
    s.height = 7;
    s.wavefront_size = 100;
    const bool wide8 = bvh_layout_for(context->device()) == BvhLayout::Wide8;
    for (std::uint32_t per_pass : {1u, 2u, 3u, 4u}) {
        s.samples_per_pass = per_pass;
        s.spp = 2 * per_pass;
        const std::uint32_t pixels = expect_megakernel_equals_wavefront(*context, scene, validation::cornell_camera(), s);
        EXPECT_EQ(pixels, wide8 ? dev::gc_megakernel_pixels_per_item(per_pass) : 1u) << per_pass << " per pass";
    }
    if (wide8) {
        EXPECT_EQ(dev::gc_megakernel_pixels_per_item(1), 8u);
        EXPECT_EQ(dev::gc_megakernel_pixels_per_item(3), 2u);
        EXPECT_EQ(dev::gc_megakernel_pixels_per_item(5), 1u);
    }
}

TEST_F(DeterminismTest, MegakernelEqualsWavefrontThroughAlphaMask)
{
    // The camera looks at a glTF alpha MASK quad whose left half is cut away (the backstop
    // shows through): the packet traversal's alpha test must cut the same hits away as the
    // single-ray one's.
    const Scene scene = test::half_cut_quad();
    Camera camera;
    camera.look_from = Point3(0.3f, 0.2f, 2.5f);
    camera.look_at = Point3(0.0f, 0.0f, 0.0f);
    camera.vfov_degrees = 60.0f;
    RenderSettings s = small_path_render(12, 4);
    s.samples_per_pass = 12;  // two packets of six camera rays
    s.env_radiance = glm::vec3(1.0f);
    expect_megakernel_equals_wavefront(*context, scene, camera, s);
}

}  // namespace
}  // namespace gc
