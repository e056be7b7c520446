// Canonical chunks on the host: the plan, the fixed-order addition whatever the arrival
// order, cut chunks, and the mean's arithmetic.
#include <algorithm>
#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "host/render/chunks.h"
#include "host/util/error.h"

namespace gc {
namespace {

// Sums that differ per chunk and per pixel, with values whose additions round.
FilmSums fake_chunk(std::uint32_t index, std::uint32_t count, std::uint32_t w = 5, std::uint32_t h = 3)
{
    FilmSums s;
    s.width = w;
    s.height = h;
    std::mt19937 rng(index * 7919u + 1);
    std::uniform_real_distribution<float> u(0.0f, 3.0f);
    for (std::uint32_t i = 0; i < w * h; ++i) {
        s.sums.push_back({u(rng) * 1e3f, u(rng) * 1e-3f, u(rng), float(count)});
        s.squares.push_back({u(rng), u(rng), u(rng), float(count)});
        s.sample_counts.push_back(count);
    }
    return s;
}

bool same_bits(const FilmSums& a, const FilmSums& b)
{
    return a.width == b.width && a.height == b.height && a.sums.size() == b.sums.size() &&
           std::memcmp(a.sums.data(), b.sums.data(), a.sums.size() * sizeof(glm::vec4)) == 0 &&
           a.squares.size() == b.squares.size() &&
           std::memcmp(a.squares.data(), b.squares.data(), a.squares.size() * sizeof(glm::vec4)) == 0 &&
           a.sample_counts == b.sample_counts;
}

TEST(ChunkPlan, CutsTheRangeIntoAlignedChunks)
{
    const ChunkPlan plan = ChunkPlan::for_range(0, 100, 16);
    ASSERT_EQ(plan.chunk_count(), 7u);
    EXPECT_EQ(plan.chunk(0), (ChunkRange{0, 0, 16}));
    EXPECT_EQ(plan.chunk(6), (ChunkRange{6, 96, 4}));  // the frame's last chunk is short

    const ChunkPlan part = ChunkPlan::for_range(32, 100, 16);
    ASSERT_EQ(part.chunk_count(), 5u);
    EXPECT_EQ(part.first_chunk(), 2u);
    EXPECT_EQ(part.chunk(0), (ChunkRange{2, 32, 16}));  // global ids: the frame's chunk 2
    EXPECT_EQ(part.chunk(4), plan.chunk(6));

    EXPECT_THROW(ChunkPlan::for_range(8, 100, 16), UsageError);  // does not start a chunk
    EXPECT_THROW(ChunkPlan::for_range(16, 16, 16), UsageError);
    EXPECT_THROW(ChunkPlan::for_range(0, 16, 0), UsageError);
    EXPECT_EQ(ChunkPlan::for_range(0, 64, 64).chunk_count(), 1u);
}

TEST(FrameAccumulator, AnyArrivalOrderGivesTheBitsOfChunkOrder)
{
    const ChunkPlan plan = ChunkPlan::for_range(0, 100, 16);
    FilmSums expected = fake_chunk(0, 16);
    for (std::uint32_t n = 1; n < plan.chunk_count(); ++n) add_sums(expected, fake_chunk(n, plan.chunk(n).count));

    std::vector<std::uint32_t> order(plan.chunk_count());
    for (std::uint32_t n = 0; n < order.size(); ++n) order[n] = n;
    std::mt19937 rng(5);
    for (int round = 0; round < 20; ++round) {
        std::shuffle(order.begin(), order.end(), rng);
        FrameAccumulator frame(plan);
        for (std::uint32_t n : order) {
            frame.add(plan.chunk(n), fake_chunk(n, plan.chunk(n).count));
            if (n == order.front()) frame.add(plan.chunk(n), fake_chunk(99, 1));  // a backup's late copy: dropped
        }
        EXPECT_EQ(frame.samples_folded(), 100u);
        std::uint32_t end = 0;
        EXPECT_TRUE(same_bits(frame.finish(&end), expected)) << "round " << round;
        EXPECT_EQ(end, 100u);
    }

    // Another grouping gives other bits: c0 + (c1 + c2) is not (c0 + c1) + c2.
    FilmSums tail = fake_chunk(1, 16);
    add_sums(tail, fake_chunk(2, 16));
    FilmSums other = fake_chunk(0, 16);
    add_sums(other, tail);
    for (std::uint32_t n = 3; n < plan.chunk_count(); ++n) add_sums(other, fake_chunk(n, plan.chunk(n).count));
    EXPECT_FALSE(same_bits(other, expected));
}

TEST(FrameAccumulator, ACutChunkEndsTheFrameOnlyWhenItIsNext)
{
    const ChunkPlan plan = ChunkPlan::for_range(0, 64, 16);
    FrameAccumulator frame(plan);
    frame.add(plan.chunk(0), fake_chunk(0, 16));
    frame.add(plan.chunk(2), fake_chunk(2, 16));           // waits: chunk 1 is not in
    frame.add_truncated({1, 16, 5}, fake_chunk(1, 5));      // chunk 1 cut after 5 samples
    frame.add_truncated({3, 48, 7}, fake_chunk(3, 7));      // not next: dropped
    std::uint32_t end = 0;
    const FilmSums got = frame.finish(&end);
    EXPECT_EQ(end, 21u);  // samples [0, 21): the frame of 21 spp, whose chunk 1 is [16, 21)
    FilmSums expected = fake_chunk(0, 16);
    add_sums(expected, fake_chunk(1, 5));
    EXPECT_TRUE(same_bits(got, expected));
}

// A frame started from its first chunks already folded (a checkpoint) and continued has the
// bits of the frame added from chunk 0; folded() is the prefix a checkpoint writes.
TEST(FrameAccumulator, StartsFromAFoldedPrefix)
{
    const ChunkPlan plan = ChunkPlan::for_range(0, 100, 16);
    FilmSums expected = fake_chunk(0, 16);
    for (std::uint32_t n = 1; n < plan.chunk_count(); ++n) add_sums(expected, fake_chunk(n, plan.chunk(n).count));

    FrameAccumulator first(plan);
    for (std::uint32_t n : {0u, 2u, 1u}) first.add(plan.chunk(n), fake_chunk(n, 16));
    std::uint32_t chunks = 0;
    FilmSums prefix = first.folded(&chunks);
    EXPECT_EQ(chunks, 3u);

    FrameAccumulator resumed(plan);
    resumed.start_with(std::move(prefix), chunks);
    EXPECT_EQ(resumed.samples_folded(), 48u);
    EXPECT_EQ(resumed.next_chunk(), 3u);
    for (std::uint32_t n = plan.chunk_count(); n-- > 3;) resumed.add(plan.chunk(n), fake_chunk(n, plan.chunk(n).count));
    std::uint32_t end = 0;
    EXPECT_TRUE(same_bits(resumed.finish(&end), expected));
    EXPECT_EQ(end, 100u);
}

TEST(SampleVariance, IsTheUnbiasedVariancePerPixel)
{
    // Samples 1, 2, 6 in red: mean 3, variance (4 + 1 + 9) / 2 = 7. One sample: 0.
    FilmSums s;
    s.width = 2;
    s.height = 1;
    s.sums = {{9.0f, 0.0f, 0.0f, 3.0f}, {5.0f, 0.0f, 0.0f, 1.0f}};
    s.squares = {{41.0f, 0.0f, 0.0f, 3.0f}, {25.0f, 0.0f, 0.0f, 1.0f}};
    s.sample_counts = {3, 1};
    const Film v = sample_variance(s);
    std::printf("  variance of {1, 2, 6}: %g (expected 7)\n", v.at(0, 0).r);
    EXPECT_FLOAT_EQ(v.at(0, 0).r, 7.0f);
    EXPECT_EQ(v.at(0, 0).g, 0.0f);
    EXPECT_EQ(v.at(1, 0).r, 0.0f);
    s.squares.clear();
    EXPECT_THROW(sample_variance(s), UsageError);
}

TEST(MeanFilm, DividesBySampleCount)
{
    FilmSums s = fake_chunk(3, 7, 2, 1);
    const Film f = mean_film(s);
    const float inv = 1.0f / 7.0f;
    EXPECT_EQ(f.at(1, 0).r, s.sums[1].x * inv);
    EXPECT_EQ(f.at(0, 0).b, s.sums[0].z * inv);
    EXPECT_EQ(f.at(0, 0).a, 1.0f);
}

}  // namespace
}  // namespace gc
