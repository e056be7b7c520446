// One frame on several devices (host/render/multi_device.h): sample ranges rendered apart and
// added in chunk order have the bits of the one-call frame; N devices of one kind have the bits
// of one; a frame of one chunk has the bits of a plain Renderer::render. Devices of one kind:
// every device of the first device's name and platform (POCL_DEVICES="pthread pthread" gives
// two), else the same device twice (two contexts, two threads: the scheduler is the same).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <map>
#include <thread>

#include "host/render/multi_device.h"
#include "host/render/session.h"
#include "host/util/error.h"
#include "tests/cl/cl_test_util.h"

namespace gc {
namespace {

namespace fs = std::filesystem;

SceneRequest cornell_box()
{
    SceneRequest request;
    request.path = fs::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Original.obj";
    return request;
}

RenderSettings small_path()
{
    RenderSettings s;
    s.width = 24;
    s.height = 20;
    s.max_depth = 5;
    s.samples_per_pass = 3;  // several passes per chunk, cut across chunk ends
    return s;
}

bool same_bits(const FilmSums& a, const FilmSums& b)
{
    return a.sums.size() == b.sums.size() &&
           std::memcmp(a.sums.data(), b.sums.data(), a.sums.size() * sizeof(glm::vec4)) == 0 &&
           a.sample_counts == b.sample_counts;
}

class MultiDeviceTest : public cl::test::DeviceTest {
protected:
    void SetUp() override
    {
        cl::test::DeviceTest::SetUp();
        if (IsSkipped()) return;
        prepared = prepare_scene(cornell_box());
        const cl::DeviceInfo& first = context->device();
        for (const cl::DeviceInfo& d : devices)
            if (d.device_name == first.device_name && d.platform_name == first.platform_name) same_kind.push_back(d);
        if (same_kind.size() < 2) same_kind = {first, first};
    }

    FilmSums frame(const std::vector<cl::DeviceInfo>& on, const ChunkPlan& plan, FrameOutcome* outcome = nullptr)
    {
        FrameResult r = render_frame(on, prepared, small_path(), {}, plan, {});
        EXPECT_EQ(r.end_sample, plan.end_sample);
        if (outcome) *outcome = r.outcome;
        return std::move(r.sums);
    }

    PreparedScene prepared;
    std::vector<cl::DeviceInfo> same_kind;
};

TEST_F(MultiDeviceTest, OneChunkIsThePlainRender)
{
    Renderer renderer(*context, prepared.scene, prepared.bvh, prepared.camera, small_path());
    renderer.render(0, 10);
    FrameOutcome outcome;
    const FilmSums one = frame({context->device()}, ChunkPlan::for_range(0, 10, 16), &outcome);
    EXPECT_TRUE(same_bits(one, renderer.sums()));
    EXPECT_EQ(outcome.devices.at(0).probe_seconds, 0.0) << "a device alone has no one to compare its rate with";
    EXPECT_EQ(mean_film(one), renderer.film());
}

TEST_F(MultiDeviceTest, SplitRangesAddUpToTheFrame)
{
    const cl::DeviceInfo device = context->device();
    const FilmSums whole = frame({device}, ChunkPlan::for_range(0, 40, 8));

    // The same frame from three ranges rendered apart, chunks kept, added in chunk order.
    const ChunkPlan plan = ChunkPlan::for_range(0, 40, 8);
    FrameAccumulator parts(plan);
    for (auto [a, b] : {std::pair{24u, 40u}, std::pair{0u, 8u}, std::pair{8u, 24u}})
        render_chunks({device}, prepared, small_path(), {}, ChunkPlan::for_range(a, b, 8), {},
                      [&](const ChunkRange& range, FilmSums&& sums, bool complete) {
                          ASSERT_TRUE(complete);
                          parts.add(range, std::move(sums));
                      });
    std::uint32_t end = 0;
    EXPECT_TRUE(same_bits(parts.finish(&end), whole));
    EXPECT_EQ(end, 40u);

    // A split differs from the sequential sum of one render over the same samples only by
    // rounding: the test would see a wrong grouping.
    Renderer renderer(*context, prepared.scene, prepared.bvh, prepared.camera, small_path());
    renderer.render(0, 40);
    EXPECT_FALSE(same_bits(renderer.sums(), whole));
}

// A CPU device beside others probes its rate (Renderer::estimate_seconds_per_sample) before
// its first chunk: the probe leaves the pixels picked, the pass plan and the next sample as
// they were, so the chunk after it has the bits it has without one.
TEST_F(MultiDeviceTest, ARateProbeLeavesTheRendererAsItWas)
{
    Renderer plain(*context, prepared.scene, prepared.bvh, prepared.camera, small_path());
    Renderer probed(*context, prepared.scene, prepared.bvh, prepared.camera, small_path());
    const std::vector<std::uint32_t> picked = {1, 30, 31, 200, 479};
    for (Renderer* r : {&plain, &probed}) {
        r->select_pixels(picked);
        r->clear(7);
    }
    const double seconds = probed.estimate_seconds_per_sample(2);
    std::printf("  probe: %.3g s per sample of %zu pixels\n", seconds, picked.size());
    EXPECT_GT(seconds, 0.0);
    EXPECT_EQ(probed.next_sample(), 7u);
    EXPECT_EQ(probed.samples_done(), 0u);
    for (Renderer* r : {&plain, &probed}) r->render_samples(10);  // samples_per_pass 3: one pass of 3
    EXPECT_EQ(probed.samples_done(), 3u) << "the pass plan changed";
    EXPECT_TRUE(same_bits(probed.sums(), plain.sums()));

    for (Renderer* r : {&plain, &probed}) r->select_all_pixels();
    EXPECT_GT(probed.estimate_seconds_per_sample(1u << 16), 0.0);
    for (Renderer* r : {&plain, &probed}) r->render(0, 6);
    EXPECT_TRUE(same_bits(probed.sums(), plain.sums()));

    RenderSettings whitted = small_path();
    whitted.integrator = IntegratorKind::Whitted;
    Renderer other(*context, prepared.scene, prepared.bvh, prepared.camera, whitted);
    EXPECT_THROW(other.estimate_seconds_per_sample(16), UsageError);
}

TEST_F(MultiDeviceTest, SeveralDevicesOfOneKindGiveTheBitsOfOne)
{
    const ChunkPlan plan = ChunkPlan::for_range(0, 45, 4);
    const FilmSums one = frame({same_kind[0]}, plan);
    FrameOutcome outcome;
    const FilmSums two = frame(same_kind, plan, &outcome);
    EXPECT_TRUE(same_bits(one, two));
    std::uint32_t chunks = 0;
    for (const DeviceReport& d : outcome.devices) {
        std::printf("  %s: %u chunks (%u backups), %llu spp, probe %.3f s, busy %.3f s\n", d.name.c_str(), d.chunks,
                    d.backups, static_cast<unsigned long long>(d.samples), d.probe_seconds, d.busy_seconds);
        chunks += d.chunks;
        EXPECT_TRUE(d.failure.empty()) << d.failure;
        // Beside another device a CPU device probes its rate first. (Whether one then leaves
        // depends on the load of the machine: these passes take a millisecond.)
        if (!d.is_gpu) {
            EXPECT_GT(d.probe_seconds, 0.0);
        }
    }
    EXPECT_EQ(chunks, plan.chunk_count());
    const std::vector<cl::DeviceInfo> three = {same_kind[0], same_kind[1], same_kind[0]};
    EXPECT_TRUE(same_bits(one, frame(three, plan)));
}

// Rendering starts once every device is set up: a device ready early waits for one whose
// set-up takes longer (here held up 0.3 s in on_device_ready) instead of rendering beside it.
TEST_F(MultiDeviceTest, RenderingStartsWhenEveryDeviceIsSetUp)
{
    FrameControl control;
    control.on_device_ready = [](std::size_t device) {
        if (device == 0) std::this_thread::sleep_for(std::chrono::milliseconds(300));
    };
    const ChunkPlan plan = ChunkPlan::for_range(0, 16, 4);
    const FrameResult r = render_frame(same_kind, prepared, small_path(), {}, plan, control);
    const FrameOutcome& outcome = r.outcome;
    ASSERT_EQ(outcome.devices.size(), 2u);
    const double frame_start = outcome.seconds_with_setup - outcome.seconds;
    std::printf("  devices ready at %.3f s and %.3f s; rendering from %.3f s to %.3f s\n",
                outcome.devices[0].ready_at, outcome.devices[1].ready_at, frame_start, outcome.seconds_with_setup);
    EXPECT_GE(outcome.devices[0].ready_at, outcome.devices[0].setup_seconds + 0.3);
    EXPECT_GE(frame_start, outcome.devices[0].ready_at);
    EXPECT_GE(frame_start, outcome.devices[1].ready_at);
    EXPECT_TRUE(same_bits(r.sums, frame({same_kind[0]}, plan)));
}

TEST_F(MultiDeviceTest, ADeadlineKeepsTheLongestPrefix)
{
    RenderSettings settings = small_path();
    FrameControl control;
    int passes = 0;
    control.cancelled = [&] { return ++passes >= 5; };
    const ChunkPlan plan = ChunkPlan::for_range(0, 400, 4);
    const FrameResult cut = render_frame({context->device()}, prepared, settings, {}, plan, control);
    EXPECT_TRUE(cut.outcome.cancelled);
    ASSERT_GT(cut.end_sample, 0u);
    ASSERT_LT(cut.end_sample, 400u);
    // The cut frame is the frame of that many samples.
    EXPECT_TRUE(same_bits(cut.sums, frame({context->device()}, ChunkPlan::for_range(0, cut.end_sample, 4))));
}

TEST_F(MultiDeviceTest, AFailingDeviceDropsOutAndTheOthersFinishTheFrame)
{
    cl::DeviceInfo broken = context->device();
    broken.id = nullptr;  // no such device: its context cannot be made
    broken.device_name = "broken device";
    const ChunkPlan plan = ChunkPlan::for_range(0, 24, 4);
    FrameOutcome outcome;
    const FilmSums with_broken = frame({broken, context->device()}, plan, &outcome);
    EXPECT_TRUE(same_bits(with_broken, frame({context->device()}, plan)));
    ASSERT_EQ(outcome.devices.size(), 2u);
    EXPECT_FALSE(outcome.devices[0].failure.empty());
    EXPECT_EQ(outcome.devices[0].chunks, 0u);
    EXPECT_EQ(outcome.devices[1].chunks, plan.chunk_count());
    std::printf("  broken device: %s\n", outcome.devices[0].failure.c_str());

    // Every device broken: the frame fails with the device's error.
    EXPECT_THROW(render_frame({broken}, prepared, small_path(), {}, plan, {}), Error);
}

TEST(AskSize, GpusTakeMoreThanCpus)
{
    EXPECT_EQ(ask_size(false, 100, 2), 1u);
    EXPECT_EQ(ask_size(true, 100, 2), 8u);
    EXPECT_EQ(ask_size(true, 10, 2), 1u);
    EXPECT_EQ(ask_size(true, 0, 2), 1u);
}

// A GPU 50x faster than the CPU that holds the last chunk: with the CPU's rate measured, from
// its progress, and before either is known (a CPU's first chunk must be backed up too).
TEST(BackupGain, AFastIdleDeviceBacksUpASlowHolder)
{
    const double gpu = 0.001;
    const double cpu = 0.05;
    RunningChunk c;
    c.count = 128;
    c.holder_seconds_per_sample = cpu;
    c.done = 28;
    EXPECT_NEAR(backup_gain(gpu, c), cpu * 100 - gpu * 128, 1e-9);
    c.holder_seconds_per_sample = 0.0;
    c.elapsed_seconds = 28 * cpu;
    EXPECT_NEAR(backup_gain(gpu, c), cpu * 100 - gpu * 128, 1e-9);
    c.done = 0;
    c.elapsed_seconds = 2.4;
    EXPECT_NEAR(backup_gain(gpu, c), 2.4 - gpu * 128, 1e-9);
    // Nothing to gain: the holder is as fast, or this device's own rate is not known yet.
    c.holder_seconds_per_sample = gpu;
    c.done = 100;
    EXPECT_EQ(backup_gain(gpu, c), 0.0);
    EXPECT_EQ(backup_gain(0.0, c), 0.0);
}

// A CPU at 1/50 of a GPU's rate leaves; one at a third of it, or with either rate unknown, stays;
// the faster device never leaves.
TEST(AddsTooLittle, OnlyADeviceUnderATenthOfTheOthersLeaves)
{
    EXPECT_TRUE(adds_too_little(20.0, 1000.0));
    EXPECT_FALSE(adds_too_little(1000.0, 20.0));
    EXPECT_FALSE(adds_too_little(330.0, 1000.0));
    EXPECT_FALSE(adds_too_little(0.0, 1000.0));
    EXPECT_FALSE(adds_too_little(20.0, 0.0));
    EXPECT_TRUE(adds_too_little(99.0, 1000.0));
    EXPECT_FALSE(adds_too_little(100.0, 1000.0));
}

}  // namespace
}  // namespace gc
