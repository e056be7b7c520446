// --checkpoint-every and --resume end to end through the real geocold-cl: a render resumed
// from its checkpoint (a finished one, one written mid-render, the one Ctrl-C or SIGTERM
// leaves, a --samples 0:B partial) has the bits of the render done in one go; a checkpoint of another
// frame, or a damaged one, is refused naming the file and what differs, and nothing is written.
#include <csignal>
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>

#include "process.h"

namespace gc::test {
namespace {

namespace fs = std::filesystem;

const fs::path k_cornell = fs::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Original.obj";

std::vector<std::string> render_args(const std::vector<std::string>& extra, const fs::path& scene = k_cornell)
{
    std::vector<std::string> args = {scene.string(), "--device", "cpu", "--res", "24x16",
                                     "--chunk-samples", "16", "--max-depth", "4"};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
}

RunResult run(const std::vector<std::string>& args)
{
    const RunResult r = run_process(cli_path(), args, cli_options());
    std::string what = "geocold-cl";
    for (const std::string& a : args) what += " " + a;
    std::printf("  %s -> %s (%.2f s)\n%s", what.c_str(), r.describe().c_str(), r.seconds, r.err.c_str());
    return r;
}

// The metric: bytes that differ between two PFM files (float for float; PFM has no metadata).
std::size_t differing_bytes(const fs::path& a, const fs::path& b)
{
    const std::string x = read_file(a), y = read_file(b);
    std::size_t n = x.size() > y.size() ? x.size() - y.size() : y.size() - x.size();
    for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) n += x[i] != y[i];
    std::printf("  %s vs %s: %zu of %zu bytes differ\n", a.filename().c_str(), b.filename().c_str(), n, x.size());
    return n;
}

class ResumeCli : public ::testing::Test {
protected:
    void SetUp() override
    {
        if (!have_cpu_device()) GTEST_SKIP() << "no CPU OpenCL device";
    }
    TempDir dir;
};

TEST_F(ResumeCli, GoesOnToMoreSamplesBitForBit)
{
    ASSERT_EQ(run(render_args({"--spp", "160", "-o", (dir / "direct.pfm").string()})).exit_code, 0);

    // A finished render of 96 spp, its checkpoint resumed to 160.
    const RunResult first = run(render_args({"--spp", "96", "--checkpoint-every", "1000", "-o", (dir / "first.pfm").string()}));
    ASSERT_EQ(first.exit_code, 0);
    EXPECT_NE(first.err.find("wrote checkpoint " + (dir / "first.partial.exr").string()), std::string::npos);
    ASSERT_EQ(run(render_args({"--spp", "160", "--resume", (dir / "first.partial.exr").string(), "-o",
                               (dir / "resumed.pfm").string()}))
                  .exit_code,
              0);
    EXPECT_EQ(differing_bytes(dir / "resumed.pfm", dir / "direct.pfm"), 0u);

    // 100 spp: six whole chunks and a short one. The checkpoint merges into the 100-spp frame,
    // and a resume renders the short chunk whole.
    ASSERT_EQ(run(render_args({"--spp", "100", "-o", (dir / "direct100.pfm").string()})).exit_code, 0);
    ASSERT_EQ(run(render_args({"--spp", "100", "--checkpoint-every", "1000", "-o", (dir / "short.pfm").string()})).exit_code, 0);
    ASSERT_EQ(run({"merge", (dir / "short.partial.exr").string(), "--spp", "100", "-o", (dir / "merged100.pfm").string()})
                  .exit_code,
              0);
    EXPECT_EQ(differing_bytes(dir / "merged100.pfm", dir / "direct100.pfm"), 0u);
    ASSERT_EQ(run(render_args({"--spp", "160", "--resume", (dir / "short.partial.exr").string(), "-o",
                               (dir / "resumed-short.pfm").string()}))
                  .exit_code,
              0);
    EXPECT_EQ(differing_bytes(dir / "resumed-short.pfm", dir / "direct.pfm"), 0u);

    // A partial image of samples 0:64 from --samples serves too.
    ASSERT_EQ(run(render_args({"--samples", "0:64", "-o", (dir / "samples.exr").string()})).exit_code, 0);
    ASSERT_EQ(run(render_args({"--spp", "160", "--resume", (dir / "samples.exr").string(), "-o",
                               (dir / "resumed-samples.pfm").string()}))
                  .exit_code,
              0);
    EXPECT_EQ(differing_bytes(dir / "resumed-samples.pfm", dir / "direct.pfm"), 0u);
}

// Ctrl-C, and SIGTERM (a farm's preemption), stop a checkpointed render with a checkpoint.
TEST_F(ResumeCli, ACheckpointFromMidRenderAndFromAStopResumeToTheSameBits)
{
    const std::string spp = "4000";
    const std::vector<std::string> frame = {k_cornell.string(), "--device", "cpu", "--res", "12x8", "--chunk-samples",
                                            "4", "--max-depth", "3", "--spp", spp};
    std::vector<std::string> direct = frame;
    for (const std::string& a : {std::string("--quiet"), std::string("-o"), (dir / "direct.pfm").string()}) direct.push_back(a);
    ASSERT_EQ(run(direct).exit_code, 0);

    for (const int signal : {SIGINT, SIGTERM}) {
        SCOPED_TRACE(signal == SIGINT ? "SIGINT" : "SIGTERM");
        const std::string name = signal == SIGINT ? "int" : "term";
        std::vector<std::string> args = frame;
        for (const char* a : {"-v", "--checkpoint-every", "0.05", "-o"}) args.push_back(a);
        args.push_back((dir / (name + ".pfm")).string());
        const fs::path partial = dir / (name + ".partial.exr");
        const fs::path early = dir / (name + "-early.exr");
        bool copied = false;
        const RunResult r = run_on_terminal(cli_path(), args, cli_options(), [&](int pid, const std::string& so_far) {
            // The log line comes after both files of the checkpoint are in place.
            if (!copied && so_far.find("checkpoint: ") != std::string::npos) {
                fs::copy_file(partial, early);
                copied = true;
                ::kill(pid, signal);
            }
        });
        std::printf("  -> %s after %.2f s\n", r.describe().c_str(), r.seconds);
        ASSERT_TRUE(copied) << "no checkpoint seen:\n" << r.out;
        EXPECT_EQ(r.exit_code, 130) << "the render ended before the signal; make it longer\n" << r.out;
        EXPECT_NE(r.out.find("wrote checkpoint"), std::string::npos) << r.out;

        for (const fs::path& from : {early, partial}) {
            std::vector<std::string> resume = frame;
            const fs::path out = dir / ("from-" + from.stem().string() + ".pfm");
            for (const std::string& a : {std::string("--resume"), from.string(), std::string("-o"), out.string()})
                resume.push_back(a);
            const RunResult rr = run(resume);
            ASSERT_EQ(rr.exit_code, 0);
            EXPECT_EQ(differing_bytes(out, dir / "direct.pfm"), 0u) << from;
        }
    }
}

TEST_F(ResumeCli, RefusesAnotherFrameOrADamagedFileAndWritesNothing)
{
    ASSERT_EQ(run(render_args({"--spp", "32", "--checkpoint-every", "1000", "-o", (dir / "base.pfm").string()})).exit_code, 0);
    const std::string base = (dir / "base.partial.exr").string();
    const std::string out = (dir / "out.pfm").string();
    const auto refused = [&](const std::vector<std::string>& args, int code, const std::string& expected) {
        const RunResult r = run(args);
        EXPECT_EQ(r.exit_code, code);
        EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out));
        for (const std::string& e : dir.entries()) EXPECT_EQ(e.find("out."), std::string::npos) << e;
    };
    refused(render_args({"--spp", "64", "--seed", "9", "--resume", base, "-o", out}), 3,
            "--resume '" + base + "': its seed (0) differs from this render's (9)");
    refused(render_args({"--spp", "64", "--max-depth", "5", "--resume", base, "-o", out}), 3,
            "its render-options hash");
    refused(render_args({"--spp", "64", "--res", "24x17", "--resume", base, "-o", out}), 3,
            "its size (24x16) differs from this render's (24x17)");
    refused(render_args({"--spp", "64", "--resume", base, "-o", out},
                        fs::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Sphere.obj"),
            3, "its scene hash");
    refused(render_args({"--spp", "64", "--chunk-samples", "8", "--resume", base, "-o", out}), 3, "differs");
    const std::string whole = read_file(base);
    write_file(dir / "truncated.exr", whole.substr(0, whole.size() / 2));
    refused(render_args({"--spp", "64", "--resume", (dir / "truncated.exr").string(), "-o", out}), 3,
            "partial image '" + (dir / "truncated.exr").string() + "': truncated");
    refused(render_args({"--spp", "64", "--resume", (dir / "nothing.exr").string(), "-o", out}), 3,
            (dir / "nothing.exr").string());
    refused(render_args({"--spp", "64", "--resume", base, "--samples", "0:64", "-o", (dir / "out.exr").string()}), 2,
            "not a --samples range");
}

}  // namespace
}  // namespace gc::test
