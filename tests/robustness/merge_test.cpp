// Partial images and merge, end to end through the real geocold-cl: partials rendered apart
// (and a frame on two PoCL devices) merge to the bits of the one-process frame; merge refuses
// gaps, overlaps, other frames and damaged files, naming them, exits non-zero and writes nothing.
#include <filesystem>

#include <gtest/gtest.h>

#include "process.h"

namespace gc::test {
namespace {

namespace fs = std::filesystem;

const fs::path k_cornell = fs::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Original.obj";

std::vector<std::string> render_args(const std::vector<std::string>& extra)
{
    std::vector<std::string> args = {k_cornell.string(), "--quiet", "--device", "cpu", "--res", "24x16",
                                     "--chunk-samples", "4", "--max-depth", "4"};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
}

RunResult run(const std::vector<std::string>& args, const RunOptions& options = cli_options())
{
    const RunResult r = run_process(cli_path(), args, options);
    std::string what = "geocold-cl";
    for (const std::string& a : args) what += " " + a;
    std::printf("  %s -> %s (%.2f s)\n%s", what.c_str(), r.describe().c_str(), r.seconds, r.err.c_str());
    return r;
}

class Merge : public ::testing::Test {
protected:
    void SetUp() override
    {
        if (!have_cpu_device()) GTEST_SKIP() << "no CPU OpenCL device";
    }
    TempDir dir;
};

TEST_F(Merge, PartialsMergeToTheFrameBitForBit)
{
    ASSERT_EQ(run(render_args({"--spp", "14", "-o", (dir / "frame.pfm").string()})).exit_code, 0);
    ASSERT_EQ(run(render_args({"--samples", "8:14", "-o", (dir / "part-b.exr").string()})).exit_code, 0);
    ASSERT_EQ(run(render_args({"--samples", "0:8", "-o", (dir / "part-a.exr").string()})).exit_code, 0);
    const RunResult m = run({"merge", (dir / "part-b.exr").string(), (dir / "part-a.exr").string(), "--spp", "14",
                             "-o", (dir / "merged.pfm").string()});
    ASSERT_EQ(m.exit_code, 0) << m.err;
    EXPECT_EQ(read_file(dir / "merged.pfm"), read_file(dir / "frame.pfm"));

    // Two PoCL devices on one frame: the same bits again.
    RunOptions two = cli_options();
    two.env["POCL_DEVICES"] = "pthread pthread";
    const RunResult r = run({k_cornell.string(), "--quiet", "--device", "all", "--res", "24x16", "--chunk-samples", "4",
                             "--max-depth", "4", "--spp", "14", "-o", (dir / "two.pfm").string()},
                            two);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_file(dir / "two.pfm"), read_file(dir / "frame.pfm"));
}

TEST_F(Merge, RefusesWhatDoesNotAddUpAndWritesNothing)
{
    ASSERT_EQ(run(render_args({"--samples", "0:8", "-o", (dir / "a.exr").string()})).exit_code, 0);
    ASSERT_EQ(run(render_args({"--samples", "4:8", "-o", (dir / "overlap.exr").string()})).exit_code, 0);
    ASSERT_EQ(run(render_args({"--samples", "12:16", "-o", (dir / "c.exr").string()})).exit_code, 0);
    ASSERT_EQ(run(render_args({"--samples", "8:12", "--seed", "9", "-o", (dir / "seed.exr").string()})).exit_code, 0);
    ASSERT_EQ(run(render_args({"--samples", "8:12", "--res", "24x17", "-o", (dir / "size.exr").string()})).exit_code, 0);
    const std::string out = (dir / "out.pfm").string();

    RunResult r = run({"merge", (dir / "a.exr").string(), (dir / "c.exr").string(), "--spp", "20", "-o", out});
    EXPECT_EQ(r.exit_code, 7);
    EXPECT_NE(r.err.find("missing: 8:12, 16:20"), std::string::npos) << r.err;

    r = run({"merge", (dir / "a.exr").string(), (dir / "overlap.exr").string(), "-o", out});
    EXPECT_EQ(r.exit_code, 7);
    EXPECT_NE(r.err.find("overlap.exr' overlap: both hold chunk 1 (samples 4:8)"), std::string::npos) << r.err;

    r = run({"merge", (dir / "a.exr").string(), (dir / "seed.exr").string(), (dir / "c.exr").string(), "-o", out});
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_NE(r.err.find("seed.exr': its seed (9) differs"), std::string::npos) << r.err;

    r = run({"merge", (dir / "a.exr").string(), (dir / "size.exr").string(), "-o", out});
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_NE(r.err.find("size.exr': its size (24x17) differs"), std::string::npos) << r.err;

    const std::string whole = read_file(dir / "c.exr");
    write_file(dir / "truncated.exr", whole.substr(0, whole.size() / 2));
    r = run({"merge", (dir / "a.exr").string(), (dir / "truncated.exr").string(), "-o", out});
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_NE(r.err.find("partial image '" + (dir / "truncated.exr").string() + "': truncated"), std::string::npos)
        << r.err;

    std::string renamed = whole;
    const std::size_t at = renamed.find("chunk3.R");
    ASSERT_NE(at, std::string::npos);
    renamed[at + 7] = 'X';
    write_file(dir / "channels.exr", renamed);
    r = run({"merge", (dir / "a.exr").string(), (dir / "channels.exr").string(), "-o", out});
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_NE(r.err.find("channels.exr': channel 'chunk3.R' is missing"), std::string::npos) << r.err;

    r = run({"merge", "-o", out});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_FALSE(fs::exists(out));
    for (const std::string& e : dir.entries()) EXPECT_EQ(e.find("out.pfm"), std::string::npos) << e;
}

TEST_F(Merge, PartialRangesAreChecked)
{
    RunResult r = run(render_args({"--samples", "2:8", "-o", (dir / "x.exr").string()}));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("must start at a multiple of the chunk size"), std::string::npos) << r.err;
    r = run(render_args({"--samples", "0:8", "-o", (dir / "x.png").string()}));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("name it .exr"), std::string::npos) << r.err;
    r = run(render_args({"--samples", "8:8", "-o", (dir / "x.exr").string()}));
    EXPECT_EQ(r.exit_code, 2);
}

}  // namespace
}  // namespace gc::test
