// The library's front door (host/render/session.h, renderer.h, render_loop.h) on an OpenCL
// device: sample ranges that add up, edits between renders without a new upload or program,
// and the render loop's deadline and cancellation. Skips when there is no OpenCL device.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "host/render/render_loop.h"
#include "host/render/session.h"
#include "host/util/error.h"
#include "tests/cl/cl_test_util.h"
#include "tests/render/cornell_request.h"

namespace gc {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

RenderSettings small_path(std::uint32_t spp)
{
    RenderSettings s;
    s.width = 24;
    s.height = 20;
    s.spp = spp;
    s.max_depth = 5;
    return s;
}

bool same_bits(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b)
{
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec4)) == 0;
}

bool same_bits(const FilmSums& a, const FilmSums& b)
{
    return same_bits(a.sums, b.sums) && same_bits(a.squares, b.squares) && a.sample_counts == b.sample_counts;
}

double mean_red(const Film& film)
{
    double sum = 0.0;
    for (std::uint32_t y = 0; y < film.height(); ++y)
        for (std::uint32_t x = 0; x < film.width(); ++x) sum += film.at(x, y).r;
    return sum / (double(film.width()) * film.height());
}

class SessionTest : public cl::test::DeviceTest {
protected:
    void SetUp() override
    {
        cl::test::DeviceTest::SetUp();
        if (IsSkipped()) return;
        prepared = prepare_scene(test::cornell_request());
        scene = std::make_shared<DeviceScene>(DeviceScene::upload(*context, prepared.scene, prepared.bvh));
    }

    PreparedScene prepared;
    std::shared_ptr<DeviceScene> scene;
};

TEST_F(SessionTest, SampleRangesRenderedInTurnGiveTheBitsOfOneRange)
{
    for (PathKernelForm form : {PathKernelForm::Megakernel, PathKernelForm::Wavefront}) {
        RenderSetup setup;
        setup.tuning.path_kernel = form;
        Renderer whole(*context, scene, prepared.camera, small_path(64), setup);
        whole.render(0, 64);
        Renderer halves(*context, scene, prepared.camera, small_path(64), setup);
        halves.render(0, 32);
        halves.render(32, 32);
        const FilmSums a = whole.sums(), b = halves.sums();
        const bool same = same_bits(a, b);
        std::printf("%s: [0, 64) against [0, 32) + [32, 64): sums %s, %u samples per pixel\n",
                    form == PathKernelForm::Megakernel ? "megakernel" : "wavefront", same ? "identical" : "DIFFER",
                    b.sample_counts.empty() ? 0u : b.sample_counts[0]);
        EXPECT_TRUE(same);
        ASSERT_EQ(b.sample_counts.size(), std::size_t(24 * 20));
        EXPECT_EQ(b.sample_counts[0], 64u);
        EXPECT_EQ(b.sums[0].w, 64.0f);  // alpha counts the samples

        // A range is a range: samples [32, 64) alone are not samples [0, 32).
        Renderer second(*context, scene, prepared.camera, small_path(32), setup);
        second.render(32, 32);
        Renderer first(*context, scene, prepared.camera, small_path(32), setup);
        first.render(0, 32);
        EXPECT_FALSE(same_bits(first.sums(), second.sums()));
    }
}

TEST_F(SessionTest, MaterialEditReRendersWithoutANewUploadOrProgram)
{
    Session session(context->device(), prepared, small_path(16));
    session.render();
    const Film before = session.renderer().film();
    const cl::Program* program = &session.renderer().program();
    const std::uint64_t bytes = session.renderer().device_scene().bytes();

    Scene edited = prepared.scene;
    for (Material& m : edited.materials)
        if (m.name == "leftWall") m.albedo = glm::vec3(0.05f, 0.1f, 0.8f);  // red wall to blue
    auto start = Clock::now();
    session.device_scene().update_materials(session.context(), edited);
    const double update_seconds = seconds_since(start);
    start = Clock::now();
    const RenderOutcome outcome = session.render();
    const double render_seconds = seconds_since(start);
    const Film after = session.renderer().film();

    // The same bits as the edited scene uploaded afresh, with its own BVH and program.
    start = Clock::now();
    const FlatBvh bvh = build_bvh(edited);
    const double bvh_seconds = seconds_since(start);
    Renderer fresh(session.context(), edited, bvh, prepared.camera, small_path(16));
    fresh.render(0, 16);
    std::printf("material update %.4f s, re-render of 16 spp %.4f s; for comparison a BVH build %.4f s and the "
                "program build %.4f s (%s)\n",
                update_seconds, render_seconds, bvh_seconds, fresh.program().build_seconds(),
                fresh.program().from_cache() ? "from the cache" : "compiled");
    std::printf("mean red: %.4f before, %.4f after the edit\n", mean_red(before), mean_red(after));

    EXPECT_EQ(outcome.samples, 16u);  // the film restarted
    EXPECT_EQ(program, &session.renderer().program()) << "the edit changed no kernel feature: same program";
    EXPECT_EQ(bytes, session.renderer().device_scene().bytes());
    EXPECT_LT(mean_red(after), 0.9 * mean_red(before));
    EXPECT_TRUE(same_bits(session.renderer().sums().sums, fresh.sums().sums));
}

TEST_F(SessionTest, EmissionEditMovesTheLights)
{
    // Turning the ceiling light off and the tall box on changes the emitters the kernels
    // sample, not only the materials.
    Renderer renderer(*context, scene, prepared.camera, small_path(8));
    Scene edited = prepared.scene;
    for (Material& m : edited.materials) {
        if (m.name == "light") m.emission = glm::vec3(0.0f);
        if (m.name == "tallBox") m.emission = glm::vec3(4.0f);
    }
    scene->update_materials(*context, edited);
    renderer.render(0, 8);
    Renderer fresh(*context, edited, build_bvh(edited), prepared.camera, small_path(8));
    fresh.render(0, 8);
    std::printf("emitters after the edit: %u\n", scene->emitter_count);
    EXPECT_TRUE(same_bits(renderer.sums().sums, fresh.sums().sums));
}

TEST_F(SessionTest, UvTransformEditMakesNewTextureViews)
{
    // A material edit that adds a KHR_texture_transform: the device scene re-makes its texture
    // views (the texels stay), and the render equals the edited scene uploaded afresh.
    SceneRequest request;
    request.path = fs::path(GC_TEST_SOURCE_DIR) / "tests/data/scenes/box-textured/BoxTextured.gltf";
    const PreparedScene box = prepare_scene(request);
    RenderSettings lit = small_path(4);  // the box has no light of its own: a white sky
    lit.env_radiance = glm::vec3(1.0f);
    auto device_box = std::make_shared<DeviceScene>(DeviceScene::upload(*context, box.scene, box.bvh));
    Renderer renderer(*context, device_box, box.camera, lit);
    renderer.render(0, 4);
    Scene edited = box.scene;
    ASSERT_GE(edited.materials[0].albedo_texture, 0);
    edited.materials[0].albedo_uv.offset = {0.25f, 0.5f};
    edited.materials[0].albedo_uv.rotation = 0.7f;
    const std::uint32_t views_before = device_box->texture_count;
    device_box->update_materials(*context, edited);
    EXPECT_EQ(device_box->texture_count, views_before + 1);
    renderer.render(0, 4);
    Renderer fresh(*context, edited, build_bvh(edited), box.camera, lit);
    fresh.render(0, 4);
    EXPECT_TRUE(same_bits(renderer.sums(), fresh.sums()));
    EXPECT_FALSE(same_bits(renderer.sums().sums, [&] {
        Renderer plain(*context, box.scene, box.bvh, box.camera, lit);
        plain.render(0, 4);
        return plain.sums().sums;
    }())) << "the transform changed nothing";
}

TEST_F(SessionTest, CameraMoveRestartsTheFilm)
{
    Renderer moved(*context, scene, prepared.camera, small_path(4));
    moved.render(0, 4);
    Camera closer = prepared.camera;
    closer.look_from = Point3(0.2f, 1.1f, 2.5f);
    moved.set_camera(closer);
    EXPECT_EQ(moved.samples_done(), 0u);
    moved.render(0, 4);
    Renderer fresh(*context, scene, closer, small_path(4));
    fresh.render(0, 4);
    EXPECT_TRUE(same_bits(moved.sums(), fresh.sums()));
}

TEST_F(SessionTest, CancellationStopsAfterAPassWithTheFilmIntact)
{
    RenderSettings s = small_path(1000);
    s.samples_per_pass = 1;
    Renderer renderer(*context, scene, prepared.camera, s);
    RenderControl control;
    std::uint32_t reports = 0;
    control.on_pass = [&](std::uint32_t) { ++reports; };
    control.cancelled = [&] { return reports >= 3; };
    const RenderOutcome outcome = render_to(renderer, s.spp, control);
    std::printf("cancelled after %u passes: %u samples\n", reports, outcome.samples);
    EXPECT_TRUE(outcome.cancelled);
    EXPECT_FALSE(outcome.timed_out);
    EXPECT_EQ(outcome.samples, 3u);
    EXPECT_GT(mean_red(renderer.film()), 0.0);
}

TEST_F(SessionTest, TimeLimitStopsShortOfTheSampleCount)
{
    RenderSettings s = small_path(100000);
    s.samples_per_pass = 1;
    Renderer renderer(*context, scene, prepared.camera, s);
    RenderControl control;
    control.time_limit_seconds = 0.05;
    const RenderOutcome outcome = render_to(renderer, s.spp, control);
    std::printf("time limit 0.05 s: %u samples in %.3f s\n", outcome.samples, outcome.seconds);
    EXPECT_TRUE(outcome.timed_out);
    EXPECT_GE(outcome.samples, 1u);
    EXPECT_LT(outcome.samples, s.spp);
}

TEST_F(SessionTest, ARenderThatNamesAnotherEnvironmentMapIsRefused)
{
    RenderSettings s = small_path(1);
    s.env_map_path = "sky.exr";
    try {
        Renderer renderer(*context, scene, prepared.camera, s);
        FAIL() << "a renderer accepted a scene uploaded without its environment map";
    } catch (const UsageError& e) {
        std::printf("%s\n", e.what());
        EXPECT_NE(std::string(e.what()).find("sky.exr"), std::string::npos);
    }
}

TEST_F(SessionTest, AMaterialUpdateOfAnotherSceneIsRefused)
{
    Scene other = prepared.scene;
    other.materials.pop_back();
    EXPECT_THROW(scene->update_materials(*context, other), UsageError);
}

}  // namespace
}  // namespace gc
