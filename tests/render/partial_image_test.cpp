// Partial images: the EXR round trip (bit for bit), and merge's checks: overlaps, gaps and
// mismatched hashes are refused, naming the files and the missing sample ranges.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "host/render/partial_image.h"
#include "host/util/error.h"

namespace gc {
namespace {

namespace fs = std::filesystem;

fs::path out_dir()
{
    const fs::path dir = fs::path(GC_TEST_OUTPUT_DIR) / "partial_image_test";
    fs::create_directories(dir);
    return dir;
}

PartialChunk chunk(const ChunkRange& range, std::uint32_t w, std::uint32_t h)
{
    PartialChunk c;
    c.range = range;
    c.sums.width = w;
    c.sums.height = h;
    std::mt19937 rng(range.index + 11);
    std::uniform_real_distribution<float> u(0.0f, 5.0f);
    for (std::uint32_t i = 0; i < w * h; ++i) {
        c.sums.sums.push_back({u(rng), u(rng) * 1e-5f, u(rng) * 1e5f, float(range.count)});
        c.sums.sample_counts.push_back(range.count);
    }
    return c;
}

PartialImage part(std::uint32_t first, std::uint32_t end, std::uint32_t size = 8, std::uint32_t w = 7, std::uint32_t h = 4)
{
    PartialImage p;
    p.width = w;
    p.height = h;
    p.scene_hash = "0123456789abcdef";
    p.options_hash = "fedcba9876543210";
    p.seed = 3;
    p.chunk_samples = size;
    p.first_sample = first;
    p.end_sample = end;
    p.device = "test device";
    p.integrator = "path";
    p.scene = "scene.obj";
    const ChunkPlan plan = ChunkPlan::for_range(first, end, size);
    for (std::uint32_t n = 0; n < plan.chunk_count(); ++n) p.chunks.push_back(chunk(plan.chunk(n), w, h));
    return p;
}

std::string message_of(const std::function<void()>& f)
{
    try {
        f();
    } catch (const std::exception& e) {
        return e.what();
    }
    return "(no exception)";
}

TEST(PartialImage, RoundTripsBitForBit)
{
    const fs::path path = out_dir() / "round.exr";
    const PartialImage written = part(16, 36);
    write_partial_image(path, written);
    const PartialImage read = read_partial_image(path);
    EXPECT_EQ(read.width, 7u);
    EXPECT_EQ(read.height, 4u);
    EXPECT_EQ(read.scene_hash, written.scene_hash);
    EXPECT_EQ(read.options_hash, written.options_hash);
    EXPECT_EQ(read.seed, 3u);
    EXPECT_EQ(read.chunk_samples, 8u);
    EXPECT_EQ(read.first_sample, 16u);
    EXPECT_EQ(read.end_sample, 36u);
    EXPECT_EQ(read.device, "test device");
    ASSERT_EQ(read.chunks.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(read.chunks[i].range, written.chunks[i].range);
        ASSERT_EQ(read.chunks[i].sums.sums.size(), written.chunks[i].sums.sums.size());
        EXPECT_EQ(std::memcmp(read.chunks[i].sums.sums.data(), written.chunks[i].sums.sums.data(),
                              written.chunks[i].sums.sums.size() * sizeof(glm::vec4)),
                  0);
        EXPECT_EQ(read.chunks[i].sums.sample_counts, written.chunks[i].sums.sample_counts);
    }
    EXPECT_EQ(read.chunks[2].range, (ChunkRange{4, 32, 4}));
}

TEST(PartialImage, MergeAddsInChunkOrderWhateverTheFileOrder)
{
    const fs::path dir = out_dir();
    write_partial_image(dir / "a.exr", part(0, 16));
    write_partial_image(dir / "b.exr", part(16, 24));
    write_partial_image(dir / "c.exr", part(24, 30));
    const PartialImage whole = part(0, 30);
    FilmSums expected = whole.chunks[0].sums;
    for (std::size_t i = 1; i < whole.chunks.size(); ++i) add_sums(expected, whole.chunks[i].sums);

    const MergedFrame m = merge_partial_images({dir / "c.exr", dir / "a.exr", dir / "b.exr"}, 30u);
    EXPECT_EQ(m.spp, 30u);
    EXPECT_EQ(std::memcmp(m.sums.sums.data(), expected.sums.data(), expected.sums.size() * sizeof(glm::vec4)), 0);
    EXPECT_EQ(m.sums.sample_counts, expected.sample_counts);
}

TEST(PartialImage, MergeRefusesGapsOverlapsAndOtherFrames)
{
    const fs::path dir = out_dir();
    write_partial_image(dir / "p0.exr", part(0, 16));
    write_partial_image(dir / "p1.exr", part(16, 20));   // ends early: 20:24 missing
    write_partial_image(dir / "p3.exr", part(24, 40));
    write_partial_image(dir / "p0b.exr", part(8, 16));

    std::string why = message_of([&] { merge_partial_images({dir / "p0.exr", dir / "p1.exr", dir / "p3.exr"}, 48u); });
    EXPECT_NE(why.find("missing: 20:24, 40:48"), std::string::npos) << why;
    EXPECT_THROW(merge_partial_images({dir / "p3.exr"}), IncompleteError);
    why = message_of([&] { merge_partial_images({dir / "p3.exr"}); });
    EXPECT_NE(why.find("missing: 0:24"), std::string::npos) << why;

    why = message_of([&] { merge_partial_images({dir / "p0.exr", dir / "p0b.exr"}); });
    EXPECT_NE(why.find("p0.exr' and '"), std::string::npos) << why;
    EXPECT_NE(why.find("p0b.exr' overlap: both hold chunk 1 (samples 8:16)"), std::string::npos) << why;

    PartialImage other = part(16, 24);
    other.scene_hash = "1111111111111111";
    write_partial_image(dir / "other.exr", other);
    why = message_of([&] { merge_partial_images({dir / "p0.exr", dir / "other.exr"}); });
    EXPECT_NE(why.find("other.exr': its scene hash (1111111111111111) differs"), std::string::npos) << why;
    PartialImage seed = part(16, 24);
    seed.seed = 4;
    write_partial_image(dir / "seed.exr", seed);
    EXPECT_THROW(merge_partial_images({dir / "p0.exr", dir / "seed.exr"}), InputError);
}

// A checkpoint's folded run: chunks 0..2 added in chunk order as one layer. It round-trips,
// merges with the chunks after it into the bits of the frame, and counts as all of its chunks
// when another file holds one of them.
TEST(PartialImage, AFoldedRunFromChunkZeroMergesLikeItsChunks)
{
    const fs::path dir = out_dir();
    const PartialImage whole = part(0, 40);
    PartialImage run = part(0, 40);
    run.chunks.resize(1);
    for (std::size_t i = 1; i < 3; ++i) add_sums(run.chunks[0].sums, whole.chunks[i].sums);
    run.chunks[0].range = ChunkRange{0, 0, 24};
    run.chunks[0].folded_chunks = 3;
    write_partial_image(dir / "run.exr", run);
    const PartialImage read = read_partial_image(dir / "run.exr");
    ASSERT_EQ(read.chunks.size(), 1u);
    EXPECT_EQ(read.chunks[0].range, (ChunkRange{0, 0, 24}));
    EXPECT_EQ(read.chunks[0].folded_chunks, 3u);
    EXPECT_EQ(read.chunks[0].last_index(), 2u);

    write_partial_image(dir / "rest.exr", part(24, 40));
    FilmSums expected = whole.chunks[0].sums;
    for (std::size_t i = 1; i < whole.chunks.size(); ++i) add_sums(expected, whole.chunks[i].sums);
    const MergedFrame m = merge_partial_images({dir / "rest.exr", dir / "run.exr"}, 40u);
    EXPECT_EQ(m.spp, 40u);
    EXPECT_EQ(std::memcmp(m.sums.sums.data(), expected.sums.data(), expected.sums.size() * sizeof(glm::vec4)), 0);

    write_partial_image(dir / "chunk2.exr", part(16, 24));
    const std::string why = message_of([&] { merge_partial_images({dir / "run.exr", dir / "chunk2.exr"}); });
    EXPECT_NE(why.find("chunk2.exr' overlap: both hold chunk 2 (samples 16:24)"), std::string::npos) << why;

    // A folded run must start at chunk 0: elsewhere its sum is not a step of the frame's.
    PartialImage late = part(8, 40);
    late.chunks.resize(1);
    late.chunks[0].range = ChunkRange{1, 8, 16};
    late.chunks[0].folded_chunks = 2;
    write_partial_image(dir / "late.exr", late);
    const std::string late_why = message_of([&] { read_partial_image(dir / "late.exr"); });
    EXPECT_NE(late_why.find("late.exr': the folded chunks '1-2' do not run from chunk 0"), std::string::npos)
        << late_why;
}

TEST(PartialImage, BadFilesAreInputErrorsNamingTheFile)
{
    const fs::path dir = out_dir();
    write_partial_image(dir / "good.exr", part(0, 16));
    std::ifstream in(dir / "good.exr", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());

    const auto bad = [&](const std::string& name, const std::string& content, const std::string& expected) {
        std::ofstream(dir / name, std::ios::binary) << content;
        const std::string why = message_of([&] { read_partial_image(dir / name); });
        EXPECT_NE(why.find(name), std::string::npos) << why;
        EXPECT_NE(why.find(expected), std::string::npos) << why;
    };
    bad("truncated.exr", bytes.substr(0, bytes.size() - 100), "truncated");
    bad("header-cut.exr", bytes.substr(0, 200), "truncated");
    bad("not-exr.exr", "P6\n1 1\n255\nabc", "not an OpenEXR file");
    std::string renamed = bytes;
    const std::size_t at = renamed.find("chunk1.N");
    ASSERT_NE(at, std::string::npos);
    renamed[at + 7] = 'M';  // chunk1.M: the count channel of chunk 1 is gone
    bad("channels.exr", renamed, "channel 'chunk1.N' is missing");
    EXPECT_THROW(read_partial_image(dir / "no-such-file.exr"), InputError);
}

}  // namespace
}  // namespace gc
