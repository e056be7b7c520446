// --noise-threshold end to end through the real geocold-cl: the render says where its samples
// went, writes the same bytes on every run and on two PoCL devices, and a bad threshold is a
// usage error (exit 2) that names the option.
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>

#include "process.h"

namespace gc::test {
namespace {

namespace fs = std::filesystem;

const fs::path k_sphere = fs::path(GC_TEST_SOURCE_DIR) / "scenes/cornell-box/CornellBox-Sphere.obj";

RunResult run(const std::vector<std::string>& args, const RunOptions& options = cli_options())
{
    const RunResult r = run_process(cli_path(), args, options);
    std::string what = "geocold-cl";
    for (const std::string& a : args) what += " " + a;
    std::printf("  %s -> %s (%.2f s)\n%s", what.c_str(), r.describe().c_str(), r.seconds, r.err.c_str());
    return r;
}

std::vector<std::string> adaptive_args(const std::string& device, const fs::path& output)
{
    return {k_sphere.string(), "--device", device, "--res", "40x32", "--spp", "64", "--chunk-samples", "16",
            "--noise-threshold", "0.2", "-o", output.string()};
}

TEST(AdaptiveCli, ReportsItsSamplesAndRepeatsItsBits)
{
    if (!have_cpu_device()) GTEST_SKIP() << "no CPU OpenCL device";
    const TempDir dir;
    const RunResult first = run(adaptive_args("cpu", dir / "first.pfm"));
    ASSERT_EQ(first.exit_code, 0) << first.err;
    // "adaptive sampling: N samples in total, mean M spp (cap 64)": fewer than 40 x 32 x 64.
    const std::size_t at = first.err.find("adaptive sampling: ");
    ASSERT_NE(at, std::string::npos) << first.err;
    const unsigned long long total = std::strtoull(first.err.c_str() + at + 19, nullptr, 10);
    std::printf("  %llu samples of at most %d\n", total, 40 * 32 * 64);
    EXPECT_GT(total, 40ull * 32 * 16);  // every pixel gets the samples before the first check point
    EXPECT_LT(total, 40ull * 32 * 64);
    EXPECT_NE(first.err.find("spp (cap 64)"), std::string::npos) << first.err;

    const RunResult again = run(adaptive_args("cpu", dir / "again.pfm"));
    ASSERT_EQ(again.exit_code, 0) << again.err;
    EXPECT_EQ(read_file(dir / "again.pfm"), read_file(dir / "first.pfm"));

    RunOptions two = cli_options();
    two.env["POCL_DEVICES"] = "pthread pthread";
    const RunResult both = run(adaptive_args("all", dir / "two.pfm"), two);
    ASSERT_EQ(both.exit_code, 0) << both.err;
    EXPECT_EQ(read_file(dir / "two.pfm"), read_file(dir / "first.pfm"));
}

TEST(AdaptiveCli, BadThresholdIsAUsageError)
{
    const RunResult r = run({k_sphere.string(), "--noise-threshold", "0"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--noise-threshold expects a relative standard error > 0"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace gc::test
