// A chunk's sums taken off the device while it goes on (host/render/chunk_handoff.h): the
// delivered sums are the film's bits at the hand-off, whatever the renderer does after it,
// and a delivery's error comes back from wait().
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "host/render/chunk_handoff.h"
#include "host/render/session.h"
#include "tests/cl/cl_test_util.h"

namespace gc {
namespace {

class ChunkHandoffTest : public cl::test::DeviceTest {
protected:
    void SetUp() override
    {
        cl::test::DeviceTest::SetUp();
        if (IsSkipped()) return;
        SceneRequest request;
        request.path = std::filesystem::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Original.obj";
        prepared = prepare_scene(request);
        settings.width = 24;
        settings.height = 20;
        settings.max_depth = 4;
    }

    PreparedScene prepared;
    RenderSettings settings;
};

bool same_bytes(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b)
{
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec4)) == 0;
}

TEST_F(ChunkHandoffTest, DeliversTheFilmAsItWasAtTheHandOff)
{
    Session session(context->device(), prepared, settings);
    Renderer& renderer = session.renderer();
    renderer.render(0, 4);
    const FilmSums expected = renderer.sums(true);
    ChunkHandoff handoff(session.context(), renderer, true);
    FilmSums delivered;
    handoff.hand_off(renderer, [&](FilmSums&& sums) { delivered = std::move(sums); });
    // The next chunk starts at once, on the same film.
    renderer.clear(4);
    renderer.render(4, 3);
    handoff.wait();
    EXPECT_EQ(delivered.width, 24u);
    EXPECT_EQ(delivered.height, 20u);
    EXPECT_TRUE(same_bytes(delivered.sums, expected.sums));
    EXPECT_TRUE(same_bytes(delivered.squares, expected.squares));
    EXPECT_EQ(delivered.sample_counts, expected.sample_counts);
    EXPECT_EQ(delivered.sample_counts.front(), 4u);
    EXPECT_FALSE(same_bytes(renderer.sums(true).sums, expected.sums)) << "the renderer went on with other samples";

    // Without squares: only the radiance sums come back.
    ChunkHandoff sums_only(session.context(), renderer, false);
    const FilmSums now = renderer.sums(false);
    FilmSums second;
    sums_only.hand_off(renderer, [&](FilmSums&& sums) { second = std::move(sums); });
    sums_only.wait();
    EXPECT_TRUE(second.squares.empty());
    EXPECT_TRUE(same_bytes(second.sums, now.sums));
    EXPECT_EQ(second.sample_counts.front(), 3u);
}

TEST_F(ChunkHandoffTest, ADeliverysErrorComesBackOnce)
{
    Session session(context->device(), prepared, settings);
    Renderer& renderer = session.renderer();
    renderer.render(0, 1);
    ChunkHandoff handoff(session.context(), renderer, false);
    handoff.hand_off(renderer, [](FilmSums&&) { throw std::runtime_error("the sink is full"); });
    EXPECT_THROW(handoff.wait(), std::runtime_error);
    EXPECT_NO_THROW(handoff.wait()) << "the error is reported once";
    int delivered = 0;
    handoff.hand_off(renderer, [&](FilmSums&&) { ++delivered; });
    handoff.wait();
    EXPECT_EQ(delivered, 1);
}

}  // namespace
}  // namespace gc
